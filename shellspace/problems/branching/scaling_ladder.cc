#include "shellspace/problems/branching/scaling_ladder.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "shellspace/geometry/mesh.h"
#include "shellspace/problems/branching/km_family.h"
#include "shellspace/problems/branching/self_similar_series.h"
#include "shellspace/problems/branching/simulation.h"

namespace shellspace::branching {

void FitPowerLaw(const std::vector<double>& epsilons,
                 const std::vector<double>& energies, double length,
                 double* exponent, double* constant) {
  const size_t n = epsilons.size();
  if (n < 2 || energies.size() != n) {
    throw InputError("power-law fit needs at least two points");
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t k = 0; k < n; ++k) {
    const double x = std::log(epsilons[k]), y = std::log(energies[k]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double p = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double b = (sy - p * sx) / n;
  *exponent = p;
  *constant = std::exp(b) / std::cbrt(length);
}

LadderResult RunLadder(const LadderSettings& settings,
                       const std::function<void(const LadderRung&)>& progress) {
  LadderResult result;
  std::vector<double> energies;
  for (double epsilon : settings.epsilons) {
    const double lambda =
        std::cbrt(epsilon) * std::pow(settings.length, 2.0 / 3.0);
    const double delta = settings.delta_over_lambda * lambda;
    int ny = static_cast<int>(std::ceil(3.0 * settings.height / delta));
    ny += ny % 2;
    const double h0 = OptimalFirstPeriod(kNeedleA, kNeedleB, 2, epsilon,
                                         settings.length, KmOptimalTheta());
    const int lower = std::max(1, static_cast<int>(settings.height / h0));
    std::set<int> counts = {lower, lower + 1};
    LadderRung best;
    best.energy = INFINITY;
    double seconds = 0.0;
    int iterations = 0;
    for (int periods : counts) {
      SimulationSettings s;
      s.epsilon = epsilon;
      s.length = settings.length;
      s.height = settings.height;
      s.nx = settings.nx;
      s.ny = ny;
      s.grading = settings.grading;
      s.delta = delta;
      s.continuation = settings.continuation;
      s.init = "needle";
      s.periods = periods;
      s.max_iterations = settings.max_iterations;
      const SimulationResult run = RunSimulation(s);
      seconds += run.seconds;
      iterations += run.iterations;
      if (run.energy.total() < best.energy) {
        best.energy = run.energy.total();
        best.elastic = run.energy.elastic;
        best.interfacial = run.energy.interfacial();
        best.periods = periods;
      }
    }
    best.epsilon = epsilon;
    best.delta = delta;
    best.ny = ny;
    best.seconds = seconds;
    best.iterations = iterations;
    if (progress) progress(best);
    result.rungs.push_back(best);
    energies.push_back(best.energy);
  }
  FitPowerLaw(settings.epsilons, energies, settings.length, &result.exponent,
              &result.constant);
  return result;
}

}  // namespace shellspace::branching
