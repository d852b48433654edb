// Riemannian splines through keyframes and shape regression (docs/math.md,
// "Riemannian splines", "Regression"): the reduced spline / regression
// functional (problems/spline_energy.h) minimised by L-BFGS.
#ifndef SHELLSPACE_PROBLEMS_SPLINES_SPLINE_H_
#define SHELLSPACE_PROBLEMS_SPLINES_SPLINE_H_

#include <ceres/gradient_problem_solver.h>

#include <vector>

#include "shellspace/problems/splines/spline_energy.h"

namespace shellspace {

struct SplineResult {
  ShellPath path;            // K + 1 shapes (periodic: K + 1 with s_K = s_0)
  double spline_energy = 0;  // F_K
  double data_energy = 0;    // sum_j W[S_j, s_{k_j}] (regression)
  double objective = 0;      // data + sigma F_K
  ceres::GradientProblemSolver::Summary summary;  // of the last round
  int rounds = 0;  // L-BFGS rounds (SplineSettings::preconditioner_refresh)
  SplineTimings timings;  // where the evaluations spent their time
  // Max norm of the L-BFGS gradient (in the first round's preconditioned,
  // scaled variables) at the start and at the end; their ratio (0 for an
  // initial gradient 0); whether it met relative <= settings.
  // gradient_tolerance or the absolute floor kAbsoluteGradientFloor; and
  // converged: that, or Ceres'
  // function-tolerance stop (relative change of the objective below
  // settings.function_tolerance) -- unlike the Newton-finished geodesic and
  // mean, the spline's gradient carries the error of the inner midpoint
  // solves (a keyframe spline on a geodesic, F_K = 6.5e-15, stops at a
  // relative gradient of 6.5e-6), so the relative gradient alone would call
  // converged splines unconverged. True with no free shapes.
  int iterations = 0;  // L-BFGS iterations of all rounds (no iteration 0)
  double initial_gradient_norm = 0;
  double final_gradient_norm = 0;
  double relative_gradient_norm = 0;
  bool gradient_criterion_met = false;
  bool converged = false;
  // False when SplineSettings::stop was set on entry or during the first
  // evaluation of F_K: the path is the initial path and the energies are NaN
  // (never evaluated).
  bool evaluated = true;
};

// The absolute floor of the spline's gradient criterion: a max-norm of the
// gradient of F_K (unscaled) at or below it has met the criterion whatever
// the initial gradient. Without it a start at a stationary point (constant
// keyframes: initial gradient exactly 0) could never meet the relative
// criterion, and a run whose gradient is 2.7e-15 reported "not converged".
inline constexpr double kAbsoluteGradientFloor = 1e-10;

// Settings of the outer L-BFGS loop.
struct SplineSettings {
  int max_iterations = 100;  // L-BFGS iterations (the outer solver only)
  double gradient_tolerance = 1e-8;  // relative to the initial gradient
  // Relative change of the objective that ends the run. 1e-13 is some 500
  // ulps: a stall at round-off, not slow progress. (At 1e-10 the cactus
  // keyframe spline 0, 9, 18, K = 8, stopped at a relative gradient of
  // 3.6e-4 while its gradient was still falling by ~5 % an iteration.)
  double function_tolerance = 1e-13;
  bool progress = false;
  std::string progress_label = "spline";
  SolverSettings inner;  // the midpoint solves
  // Asked on entry and by the midpoints' cold-start LM runs of the first
  // evaluation (set: the initial path is returned unevaluated,
  // SplineResult::evaluated), then by the outer L-BFGS loop
  // (SolverSettings::stop); give the inner solves none, so that every
  // evaluation of F_K that is used stays exact.
  StopToken stop;
  // L-BFGS in the variables of SplinePreconditioner (spline_preconditioner.h;
  // metrics of the initial free shapes); false: in the vertex coordinates.
  bool precondition = true;
  double preconditioner_regularization = 1e-6;
  // Bound on the first trial step's largest vertex move, relative to the
  // size of the path's first shape.
  double max_first_move = 0.01;
  // L-BFGS in rounds: once a round has run at least preconditioner_refresh
  // iterations and some vertex of a free shape has moved by more than
  // refresh_move times the size of the path's first shape since the round
  // began, a new round starts with the preconditioner's metrics at the
  // current free shapes and an empty L-BFGS memory (0: one round, the
  // initial metrics throughout). A refresh costs the factorisations and the
  // memory, so shapes that stay near their start keep one round: the cactus
  // keyframe spline from its LΘA guess moves by ~0.3 % of the size in 15
  // iterations, the cactus regression (0, 3, ..., 18, K = 6, sigma 0.01)
  // from its inputs by several %. That regression met a relative gradient
  // of 1e-4 in 76 iterations (5 rounds); with the initial metrics it was at
  // 0.15 after 104, and with the threshold at 5 % (3 rounds) at 7.4e-4
  // after 104. The gradient and its tolerance stay measured in the first
  // round's variables.
  int preconditioner_refresh = 15;
  double refresh_move = 0.01;
};

// Spline through `keyframes` at path indices `at` (strictly increasing, in
// [0, K]; non-periodic paths need at.front() = 0 and at.back() = K; periodic
// ones use indices in [0, K) and s_K = s_0). The inner shapes start from
// `initial` (K + 1 shapes, e.g. the LThetaSpline) or, if empty, from the
// piecewise linear interpolation of the keyframes.
SplineResult SolveSpline(const ShellSpace& space,
                         const std::vector<Positions>& keyframes,
                         const std::vector<int>& at, int steps, bool periodic,
                         const ShellPath& initial,
                         const SplineSettings& settings);

// Regression: min over all s_0..s_K of sum_j W[inputs_j, s_{at_j}] + sigma
// F_K[s], initialised from `initial` or the piecewise linear interpolation of
// the inputs (extended constantly before the first / after the last).
SplineResult SolveRegression(const ShellSpace& space,
                             const std::vector<Positions>& inputs,
                             const std::vector<int>& at, int steps,
                             double sigma, const ShellPath& initial,
                             const SplineSettings& settings);

// Piecewise linear interpolation of shapes at indices `at` over 0..K (or
// 0..K-1 wrapping around if periodic), constant outside [at.front(),
// at.back()].
ShellPath PiecewiseLinearPath(const std::vector<Positions>& shapes,
                              const std::vector<int>& at, int steps,
                              bool periodic);

// Throws InputError unless `at` holds one strictly increasing index per
// keyframe (`count` of them, at least 2) in [0, K] (periodic: [0, K)), with
// 0 and K among them unless periodic, and K >= 2: SolveSpline's checks.
void CheckSplineKeyframes(size_t count, const std::vector<int>& at, int steps,
                          bool periodic);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_SPLINES_SPLINE_H_
