// One relaxed simulation (docs/math.md, "Branching: the Kohn–Müller model"):
// grid, initial guess, continuation in delta, measurements. Used by
// `shellspace branching simulate`, the scaling ladder, tests and benchmark.
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
  StopToken stop;  // RelaxedSolveOptions::stop

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

// Throws InputError "must be laminate, random, km, needle or lens, got 'x'"
// unless `init` names an initial guess (SimulationSettings::init); the
// message names no setting, so that a caller can prefix its own name.
void CheckInitialGuessName(const std::string& init);

// Why a finished simulation has no usable result, in one line without a
// prefix, or "" if it has one: the pattern collapsed to u = 0 (the last
// stage's termination "COLLAPSED": the grid cannot hold it) or the energy
// is not finite (epsilon, length and height too far apart for the grid).
std::string SimulationBreakdown(const SimulationResult& result);

// Builds the initial field only (validated settings).
SimulationResult InitialSimulation(const SimulationSettings& settings);

SimulationResult RunSimulation(const SimulationSettings& settings);

// Continues from `start` (a converged field, any grid of the same domain):
// the field is transferred onto the grid of `settings` (field_transfer.h)
// and solved in one LM stage at the width settings.Delta() (no fresh
// initial guess, no continuation schedule). `periods` is recorded only.
SimulationResult ContinueSimulation(const SimulationSettings& settings,
                                    const RelaxedField& start, int periods);

// One width of the delta -> 0 extrapolation.
struct DeltaWidth {
  double delta = 0.0;
  int nx = 0, ny = 0;
  double constant = 0.0;        // C = E_delta / (eps^(2/3) L^(1/3))
  double elastic = 0.0, interfacial = 0.0;  // the same split, / eps^(2/3) L^(1/3)
  int iterations = 0;           // LM iterations of this width (all stages)
  std::string termination;      // Ceres' termination of the last stage
  bool converged = false;       // the last stage met its criterion (CONVERGENCE)
  int interfaces_far = 0;       // interfaces crossing the row x = L
  int interfaces_max = 0;       // the most crossing any row
  double seconds = 0.0;
};

// A change of the interface count between neighbouring node rows of a
// field: rows i and i + 1 (x_i < x_{i+1}) carry `inner` and `outer`
// interfaces; x = (x_i + x_{i+1}) / 2. Where the pattern branches toward the
// austenite, inner > outer: the boundaries of its generations (or of the
// nucleation events inside one).
struct CountStep {
  double x = 0.0;
  int outer = 0, inner = 0;
};
// The steps of `counts` (CountInterfaces of `field`), from x = L toward 0.
std::vector<CountStep> CountSteps(const RelaxedField& field,
                                  const std::vector<int>& counts);

// The delta -> 0 extrapolation of the relaxed constant, one simulation per
// width delta_0 > delta_1 > ... (the other settings from `base`):
//  - grid: ny_k = the even integer >= 3 H / delta_k (dy <= delta / 3) and
//    nx_k = round(nx delta_0 / delta_k) (nx = base.nx), i.e. the x-grid
//    (graded as in base) is refined with the same factor as the y-grid, so
//    the discretisation error is a function of delta alone and is part of
//    what the fit in delta removes;
//  - width 0: RunSimulation (base's initial guess, base.continuation
//    stages ending at delta_0); width k >= 1: ContinueSimulation from the
//    converged field of width k - 1 (the same pattern and periods at every
//    width, one LM stage of at most base.max_iterations iterations);
//  - C_k = E_k / (eps^(2/3) L^(1/3)), fitted in d = delta / lambda,
//    lambda = eps^(1/3) L^(2/3), by least squares:
//      linear     C = c0 + c1 d            (>= 2 widths),
//      quadratic  C = q0 + q1 d + q2 d^2   (>= 4 widths; 3 would interpolate).
//      root       C = s0 + s1 d^(1/2) + s2 d  (>= 4 widths).
//    The root fit is the boundary-layer form: the sharp pattern's energy
//    density near the austenite is ~ eps^(2/3) x^(-2/3); the diffuse one
//    cannot refine below the width, i.e. where its period ~ delta, at
//    x* ~ delta^(3/2) eps^(-1/2), and the energy of (0, x*) is
//    ~ eps^(2/3) x*^(1/3) ~ eps^(1/2) delta^(1/2): C(delta) = C0 - a d^(1/2)
//    + O(d) at leading order, so polynomials in d extrapolate low.
//    The extrapolated constant is s0 (c0 with fewer than 4 widths); its
//    error estimate is the spread of the three fits, max(|s0 - q0|,
//    |s0 - c0|) (0 without the 4-width fits), next to their residuals.
// Deterministic: iteration caps and tolerances only, no clocks.
struct DeltaExtrapolation {
  std::vector<DeltaWidth> widths;
  bool all_converged = false;  // every width's last stage converged
  bool monotone = false;       // C_k strictly increases as delta decreases
  double c0 = 0.0, c1 = 0.0, linear_rms = 0.0;
  double q0 = 0.0, q1 = 0.0, q2 = 0.0, quadratic_rms = 0.0;
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, root_rms = 0.0;
  bool has_quadratic = false;  // and the root fit
  double extrapolated = 0.0, error = 0.0;
  // The field of the last (narrowest) width: x and interface count per node
  // row i = 1..nx, and its count steps.
  std::vector<double> x;
  std::vector<int> interfaces;
  std::vector<CountStep> steps;
};
// Polynomial least squares of degree `degree` (normal equations, small n);
// `rms` (if not null) receives the root-mean-square residual.
std::vector<double> PolynomialFit(const std::vector<double>& x,
                                  const std::vector<double>& y, int degree,
                                  double* rms = nullptr);
DeltaExtrapolation ExtrapolateDelta(
    const SimulationSettings& base, const std::vector<double>& deltas,
    const std::function<void(const DeltaWidth&)>& progress = nullptr);

// How many widths a delta extrapolation runs: 0 (none) or 2 ..
// kMaxExtrapolationWidths.
constexpr int kMaxExtrapolationWidths = 16;
// Throws InputError unless `count` is 0 or in [2, kMaxExtrapolationWidths].
void CheckExtrapolationCount(int count);

// The `count` widths delta_k = delta r^-k, r = 2^(1/2) (k = 0 .. count - 1),
// for ExtrapolateDelta; CheckExtrapolationCount(count) first.
std::vector<double> ExtrapolationWidths(double delta, int count);

// Twin interfaces crossing each node row i = 1..nx: sign changes of the
// staggered slope u_y around the periodic column.
std::vector<int> CountInterfaces(const RelaxedField& field);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_SIMULATION_H_
