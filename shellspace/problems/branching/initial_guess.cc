#include "shellspace/problems/branching/initial_guess.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "shellspace/problems/branching/km_family.h"
#include "shellspace/problems/branching/self_similar_series.h"

namespace shellspace::branching {

void FillFromSlope(RelaxedField* field,
                   const std::function<double(double, double)>& slope,
                   const std::function<double(double)>& ramp) {
  const RelaxedGrid& g = field->grid;
  const double dy = g.dy();
  std::vector<double> increment(g.ny);
  for (int i = 1; i <= g.nx; ++i) {
    const double x = g.x(i);
    double mean_increment = 0.0;
    for (int j = 0; j < g.ny; ++j) {
      const double y0 = g.y(j);
      const double s = (slope(x, y0) + 4.0 * slope(x, y0 + 0.5 * dy) +
                        slope(x, y0 + dy)) /
                       6.0;
      increment[j] = s * dy;
      mean_increment += increment[j] / g.ny;
    }
    double u = 0.0, mean_u = 0.0;
    for (int j = 0; j < g.ny; ++j) {
      field->at(i, j) = u;
      mean_u += u / g.ny;
      u += increment[j] - mean_increment;
    }
    const double factor = ramp ? ramp(x) : 1.0;
    for (int j = 0; j < g.ny; ++j) {
      field->at(i, j) = factor * (field->at(i, j) - mean_u);
    }
  }
  for (int j = 0; j < g.ny; ++j) field->at(0, j) = 0.0;
}

void InitLaminate(RelaxedField* field, int periods, double delta) {
  const double p = field->grid.height / std::max(1, periods);
  auto slope = [p, delta](double, double y) {
    double eta = y / p - std::floor(y / p);
    const double v = (eta >= 0.25 && eta < 0.75) ? 1.0 : -1.0;
    const double d = std::min({std::fabs(eta - 0.25), std::fabs(eta - 0.75),
                               1.0 - std::fabs(eta - 0.75)}) * p;
    return v * std::tanh(d / delta);
  };
  auto ramp = [p](double x) { return std::min(1.0, x / (0.5 * p)); };
  FillFromSlope(field, slope, ramp);
}

void InitRandom(RelaxedField* field, unsigned seed, double delta) {
  const RelaxedGrid& g = field->grid;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int max_mode = std::max(2, static_cast<int>(g.height / (8.0 * delta)));
  std::uniform_int_distribution<int> mode(1, max_mode);
  struct Term {
    int k;
    double amplitude, phase, drift;
  };
  std::vector<Term> terms(12);
  for (Term& t : terms) {
    t.k = mode(rng);
    t.amplitude = 0.5 + unit(rng);
    t.phase = 2.0 * M_PI * unit(rng);
    t.drift = 2.0 * M_PI * (unit(rng) - 0.5) * 3.0;
  }
  const double L = g.length, H = g.height;
  auto slope = [&terms, L, H, delta](double x, double y) {
    double phi = 0.0;
    for (const Term& t : terms) {
      phi += t.amplitude *
             std::cos(2.0 * M_PI * t.k * y / H + t.phase + t.drift * x / L);
    }
    return std::tanh(phi * H / (4.0 * delta));
  };
  FillFromSlope(field, slope);
}

void InitConstruction(RelaxedField* field, const Construction& construction,
                      double delta) {
  auto slope = [&construction, delta](double x, double y) {
    double d = 0.0;
    const int v = construction.VariantAt(x, y, &d);
    return v * std::tanh(d / delta);
  };
  FillFromSlope(field, slope);
}

int KmPeriodsFor(double epsilon, double length, double height) {
  const double theta = KmOptimalTheta();
  const double h0 = OptimalFirstPeriod(kNeedleA, kNeedleB, 2, epsilon, length, theta);
  return std::max(1, static_cast<int>(std::lround(height / h0)));
}

}  // namespace shellspace::branching
