// One relaxed Kohn–Müller simulation: grid + initial guess + continuation in
// delta + measurements (spec branching.md). Used by `shellspace branching
// simulate`, the scaling ladder, the tests and the benchmark.
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_SIMULATION_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_SIMULATION_H_

#include <functional>
#include <string>
#include <vector>

#include "shellspace/problems/branching/relaxed_problem.h"

namespace shellspace::branching {

struct SimulationSettings {
  double epsilon = 1e-3;
  double length = 1.0;   // L
  double height = 0.5;   // H
  int nx = 64;
  int ny = 128;
  double grading = 2.0;  // x_i = L (i/nx)^grading
  // Target interface width; <= 0 selects the resolution rule delta = 3 dy
  // (dy = delta / 3 <= delta / 2.5, spec: surface-energy error ~0.5 %).
  double delta = 0.0;
  int continuation = 3;          // widths 4 delta, 2 delta, delta
  std::string init = "needle";   // laminate | random | km | needle | lens
  int periods = 0;               // periods in H (0: needle optimum)
  unsigned seed = 1;             // random init
  int max_iterations = 200;      // per continuation stage
  int num_threads = 1;
  std::function<void(double, int, double)> progress;  // may be empty
  std::function<bool()> stop;  // RelaxedSolveOptions::stop; may be empty

  double Delta() const;  // the target width after the rule
};

struct SimulationResult {
  RelaxedField field;
  double delta = 0.0;
  int periods = 0;
  std::vector<RelaxedStage> stages;
  RelaxedEnergy energy;            // at the final delta
  std::vector<int> interfaces;     // per node row i = 1..nx (index i - 1)
  double seconds = 0.0;
  int iterations = 0;              // total LM iterations
  explicit SimulationResult(const RelaxedGrid& grid) : field(grid) {}
};

// Validates the settings (InputError with a one-line message).
void CheckSimulationSettings(const SimulationSettings& settings);

// Builds the initial field only (validated settings).
SimulationResult InitialSimulation(const SimulationSettings& settings);

SimulationResult RunSimulation(const SimulationSettings& settings);

// The delta -> 0 extrapolation of the relaxed constant: one simulation per
// width delta_k (ny = the even integer >= 3 H / delta_k, so dy <= delta/3;
// the other settings from `base`), C_k = E_k / (eps^(2/3) L^(1/3)), and
// least-squares fits in d = delta / lambda, lambda = eps^(1/3) L^(2/3):
//   linear     C = c0 + c1 d            (>= 2 widths),
//   quadratic  C = q0 + q1 d + q2 d^2   (>= 4 widths; 3 would interpolate).
struct DeltaExtrapolation {
  std::vector<double> deltas, constants;
  std::vector<int> ny;
  double c0 = 0.0, c1 = 0.0, linear_rms = 0.0;
  double q0 = 0.0, q1 = 0.0, q2 = 0.0, quadratic_rms = 0.0;
  bool has_quadratic = false;
};
// Polynomial least squares of degree `degree` (normal equations, small n);
// `rms` (if not null) receives the root-mean-square residual.
std::vector<double> PolynomialFit(const std::vector<double>& x,
                                  const std::vector<double>& y, int degree,
                                  double* rms = nullptr);
DeltaExtrapolation ExtrapolateDelta(
    const SimulationSettings& base, const std::vector<double>& deltas,
    const std::function<void(double delta, double constant)>& progress = nullptr);

// Twin interfaces crossing each node row i = 1..nx: sign changes of the
// staggered slope u_y around the periodic column.
std::vector<int> CountInterfaces(const RelaxedField& field);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_SIMULATION_H_
