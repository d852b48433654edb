#include "shellspace/problems/calculus/exp_step_continuation.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace shellspace {

namespace {

// Newton steps per load step; a step that needs at most kEasySteps lets the
// next load step double, one that needs more than kHardSteps halves it.
constexpr int kSubstepNewtonSteps = 8;
constexpr int kEasySteps = 3;
constexpr int kHardSteps = 5;

// The shape at load t before Newton: the secant through the last two roots
// (t0, r0), (t1, r1) extended to t, or, with one root, that root (Newton's
// first step from it is then the tangent of the root curve). Masked rows:
// b + t (m - b) either way.
Positions Predict(const Positions& b, const Positions& plain_guess,
                  const std::vector<int>& fixed_vertices, double t,
                  const Positions* r0, double t0, const Positions& r1,
                  double t1) {
  Positions p = r0 == nullptr
                    ? r1
                    : Positions(r1 + (t - t1) / (t1 - t0) * (r1 - *r0));
  for (int v : fixed_vertices) {
    p.row(v) = b.row(v) + t * (plain_guess.row(v) - b.row(v));
  }
  return p;
}

}  // namespace

ExpContinuationReport SolveExpStepByContinuation(
    const ExpStepEquation& equation, const Positions& plain_guess,
    const ExpContinuationSettings& settings, Positions* s) {
  ExpContinuationReport report;
  const Positions& b = equation.fixed;
  Positions root = b;      // the root at load t (t = 0: b)
  Positions previous;      // the root before it
  double t = 0, t_previous = 0;
  bool has_previous = false;
  double load_step = settings.first_load_step;
  Eigen::VectorXd constant;
  for (int attempt = 0; attempt < settings.max_substeps &&
                       report.newton_steps < settings.max_newton_steps;
       ++attempt) {
    const double target = std::min(1.0, t + load_step);
    const bool last = target >= 1.0;
    Positions trial =
        Predict(b, plain_guess, equation.fixed_vertices, target,
                has_previous ? &previous : nullptr, t_previous, root, t);
    constant = target * equation.constant;
    const ExpStepEquation loaded{equation.space, equation.fixed,
                                 equation.unknown_side, constant,
                                 equation.fixed_vertices};
    const double goal =
        last ? settings.tolerance : settings.intermediate_tolerance;
    const double good_enough =
        last ? settings.accept : settings.intermediate_tolerance;
    bool found = false;
    if (std::isfinite(ExpResidualMaxNorm(loaded, trial))) {
      const ExpNewtonReport newton = SolveExpStepNewton(
          loaded,
          ExpNewtonStopping{goal, std::max(goal, settings.accept),
                            kSubstepNewtonSteps},
          &trial);
      report.newton_steps += newton.steps;
      found = newton.final_gradient <= good_enough;
      if (found && last) report.final_residual = newton.final_gradient;
      if (found && newton.steps > kHardSteps) {
        load_step = std::max(load_step / 2, settings.min_load_step);
      } else if (found && newton.steps <= kEasySteps) {
        load_step *= 2;
      }
    }
    if (!found) {
      load_step /= 2;
      if (load_step < settings.min_load_step) {
        report.stop_reason = "load step below the minimum";
        return report;
      }
      continue;
    }
    ++report.substeps;
    previous = std::move(root);
    t_previous = t;
    has_previous = true;
    root = std::move(trial);
    t = target;
    report.load = t;
    if (last) {
      *s = std::move(root);
      report.solved = true;
      report.stop_reason = "converged";
      return report;
    }
  }
  report.stop_reason = "budget spent";
  return report;
}

}  // namespace shellspace
