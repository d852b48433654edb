#include "tests/testing/statistics_fixtures.h"

#include <random>

#include "tests/testing/test_support.h"

namespace shellspace::testing {

std::vector<Positions> LoadSpheres() {
  std::vector<Positions> shapes;
  for (const char* name : kSpheres) shapes.push_back(LoadData(name).positions);
  return shapes;
}

SolverSettings StatisticsSettings() {
  SolverSettings settings;
  settings.gradient_tolerance = 1e-10;
  settings.function_tolerance = 1e-14;
  return settings;
}

Positions GaussianNoise(int rows, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Positions p(rows, 3);
  for (int i = 0; i < p.size(); ++i) p.data()[i] = scale * normal(rng);
  return p;
}

}  // namespace shellspace::testing
