// Summing the generations of a self-similar construction (docs/math.md,
// "Branching: the Kohn–Müller model"): generation k has period h_k = h0 r^-k
// and x-length l_k = l0 theta^k, l0 = L (1 - theta) so that sum l_k = L. With a
// cell costing A h^2 / l + B eps l / h per unit height,
//
//   E(h0, theta) = A h0^2 S1 / l0 + B eps l0 S2 / h0,
//   S1 = sum (r^2 theta)^-k = r^2 theta / (r^2 theta - 1),
//   S2 = sum (r theta)^k   = 1 / (1 - r theta),      1/r^2 < theta < 1/r.
//
// Minimising in h0: h0^3 = B eps l0^2 S2 / (2 A S1), and
//   E = 3 2^(-2/3) (A S1)^(1/3) (B S2)^(2/3) (1 - theta)^(1/3) eps^(2/3) L^(1/3)
// = C(theta) eps^(2/3) L^(1/3). At the optimal h0 the elastic part is C/3 and
// the interfacial part 2C/3.
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_SELF_SIMILAR_SERIES_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_SELF_SIMILAR_SERIES_H_

#include <vector>

namespace shellspace::branching {

struct SeriesEnergy {
  double elastic = 0.0;
  double interfacial = 0.0;
  double total() const { return elastic + interfacial; }
};

double SeriesS1(int r, double theta);
double SeriesS2(int r, double theta);

// E(h0, theta) for cell coefficients A, B (per unit height).
SeriesEnergy SeriesEnergyAt(double A, double B, int r, double epsilon,
                            double length, double h0, double theta);

// The optimal first period for fixed theta (closed form above).
double OptimalFirstPeriod(double A, double B, int r, double epsilon,
                          double length, double theta);

// C(theta) (h0 optimal), independent of eps and L.
double SeriesConstant(double A, double B, int r, double theta);

// theta minimising C(theta) on (1/r^2, 1/r) (golden section on the
// unimodal log C; accurate to ~1e-12 in theta). A and B do not matter.
double OptimalTheta(int r);

// Free generation lengths (every l_k free, sum l_k = L; h_k = h0 r^-k).
// Stationarity in l_k with a multiplier lambda for the constraint gives
//   l_k = sqrt(A h_k^3 / (B eps + lambda h_k))     (B eps + lambda h0 > 0),
// geometric (ratio r^(-3/2)) only asymptotically. By the exact scaling
// (x -> a x, y -> a^(2/3) y) the constant is C = K_r^free (A B^2)^(1/3) with
//   K_r^free = min_lambda E(lambda) / L(lambda)^(1/3)   (A = B = eps = h0 = 1),
// E, L the series summed over the generations with h_k > 1e-60 (at most
// 200; the terms of E decay like h_k^(1/2)); golden section in
// log(1 + lambda).
struct FreeLengthSeries {
  double constant = 0.0;       // C = K_r^free (A B^2)^(1/3)
  double h0 = 0.0;             // optimal first period for (eps, L)
  std::vector<double> lengths; // l_k, k = 0.. (sum = L up to 1e-15 L)
  double elastic = 0.0, interfacial = 0.0;  // energy per unit height
};
double FreeLengthSeriesConstant(int r);  // K_r^free
FreeLengthSeries OptimalFreeLengths(double A, double B, int r, double epsilon,
                                    double length);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_SELF_SIMILAR_SERIES_H_
