#include "shellspace/problems/branching/self_similar_series.h"

#include <cmath>

#include "shellspace/geometry/mesh.h"

namespace shellspace::branching {

namespace {
void CheckTheta(int r, double theta) {
  if (!(theta > 1.0 / (r * r) && theta < 1.0 / r)) {
    throw InputError("branching series: theta must lie in (1/r^2, 1/r)");
  }
}
}  // namespace

double SeriesS1(int r, double theta) {
  CheckTheta(r, theta);
  const double q = r * r * theta;
  return q / (q - 1.0);
}

double SeriesS2(int r, double theta) {
  CheckTheta(r, theta);
  return 1.0 / (1.0 - r * theta);
}

SeriesEnergy SeriesEnergyAt(double A, double B, int r, double epsilon,
                            double length, double h0, double theta) {
  const double l0 = length * (1.0 - theta);
  SeriesEnergy e;
  e.elastic = A * h0 * h0 * SeriesS1(r, theta) / l0;
  e.interfacial = B * epsilon * l0 * SeriesS2(r, theta) / h0;
  return e;
}

double OptimalFirstPeriod(double A, double B, int r, double epsilon,
                          double length, double theta) {
  const double l0 = length * (1.0 - theta);
  return std::cbrt(B * epsilon * l0 * l0 * SeriesS2(r, theta) /
                   (2.0 * A * SeriesS1(r, theta)));
}

double SeriesConstant(double A, double B, int r, double theta) {
  return 3.0 * std::pow(2.0, -2.0 / 3.0) *
         std::cbrt(A * SeriesS1(r, theta)) *
         std::pow(B * SeriesS2(r, theta), 2.0 / 3.0) * std::cbrt(1.0 - theta);
}

double OptimalTheta(int r) {
  auto f = [r](double t) {
    return std::log(SeriesS1(r, t)) + 2.0 * std::log(SeriesS2(r, t)) +
           std::log(1.0 - t);
  };
  double a = 1.0 / (r * r), b = 1.0 / r;
  const double width = b - a;
  a += 1e-9 * width;
  b -= 1e-9 * width;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  while (b - a > 1e-13) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - g * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + g * (b - a), fd = f(d);
    }
  }
  return 0.5 * (a + b);
}

namespace {

constexpr int kFreeGenerations = 200;

// E / L^(1/3) with A = B = eps = h0 = 1 at multiplier lambda = e^z - 1.
double FreeRatio(int r, double z, double* E_out, double* L_out,
                 std::vector<double>* lengths) {
  const double lambda = std::expm1(z);
  double E = 0.0, L = 0.0, h = 1.0;
  if (lengths != nullptr) lengths->clear();
  // Terms decay like h^(1/2); stop at h < 1e-60 (h^3 must not underflow).
  for (int k = 0; k < kFreeGenerations && h > 1e-60; ++k) {
    const double l = std::sqrt(h * h * h / (1.0 + lambda * h));
    E += h * h / l + l / h;
    L += l;
    if (lengths != nullptr) lengths->push_back(l);
    h /= r;
  }
  if (E_out != nullptr) *E_out = E;
  if (L_out != nullptr) *L_out = L;
  return E / std::cbrt(L);
}

double FreeOptimalZ(int r) {
  double a = -8.0, b = 12.0;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = FreeRatio(r, c, nullptr, nullptr, nullptr);
  double fd = FreeRatio(r, d, nullptr, nullptr, nullptr);
  while (b - a > 1e-12) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - g * (b - a), fc = FreeRatio(r, c, nullptr, nullptr, nullptr);
    } else {
      a = c, c = d, fc = fd;
      d = a + g * (b - a), fd = FreeRatio(r, d, nullptr, nullptr, nullptr);
    }
  }
  return 0.5 * (a + b);
}

}  // namespace

double FreeLengthSeriesConstant(int r) {
  if (r < 2) throw InputError("branching series: r must be >= 2");
  return FreeRatio(r, FreeOptimalZ(r), nullptr, nullptr, nullptr);
}

FreeLengthSeries OptimalFreeLengths(double A, double B, int r, double epsilon,
                                    double length) {
  if (!(A > 0) || !(B > 0) || !(epsilon > 0) || !(length > 0)) {
    throw InputError("branching series: A, B, epsilon, length must be > 0");
  }
  FreeLengthSeries out;
  double E1 = 0.0, L1 = 0.0;
  std::vector<double> l1;
  FreeRatio(r, FreeOptimalZ(r), &E1, &L1, &l1);
  // Scale h = alpha h', l = beta l' so that both terms scale alike.
  const double beta = length / L1;
  const double alpha = std::cbrt(B * epsilon * beta * beta / A);
  const double scale = B * epsilon * beta / alpha;  // = A alpha^2 / beta
  out.h0 = alpha;
  for (double l : l1) out.lengths.push_back(beta * l);
  double h = alpha;
  for (double l : out.lengths) {
    out.elastic += A * h * h / l;
    out.interfacial += B * epsilon * l / h;
    h /= r;
  }
  (void)scale;
  out.constant = (out.elastic + out.interfacial) /
                 (std::pow(epsilon, 2.0 / 3.0) * std::cbrt(length));
  return out;
}

}  // namespace shellspace::branching
