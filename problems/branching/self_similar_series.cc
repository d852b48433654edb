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

}  // namespace shellspace::branching
