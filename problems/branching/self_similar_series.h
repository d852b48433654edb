// Summing the generations of a self-similar construction (spec branching.md):
// generation k has period h_k = h0 r^-k and x-length l_k = l0 theta^k,
// l0 = L (1 - theta) so that sum l_k = L. With a cell costing
// A h^2 / l + B eps l / h per unit height,
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

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_SELF_SIMILAR_SERIES_H_
