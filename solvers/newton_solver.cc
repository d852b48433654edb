#include "shellspace/solvers/newton_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace shellspace {

NewtonResidual NewtonResidual::OfReduced(Eigen::VectorXd reduced) {
  NewtonResidual r;
  r.max_norm = reduced.size() ? reduced.cwiseAbs().maxCoeff() : 0.0;
  r.two_norm = reduced.norm();
  r.reduced = std::move(reduced);
  return r;
}

std::string NewtonStopText(NewtonStop stop, NewtonMode mode) {
  const bool minimize = mode == NewtonMode::kMinimize;
  switch (stop) {
    case NewtonStop::kConverged:
      return "converged";
    case NewtonStop::kMaxSteps:
      return "max steps";
    case NewtonStop::kInfeasibleStart:
      return "degenerate initial guess";
    case NewtonStop::kAssemblyFailed:
      return minimize ? "Hessian not assembled" : "Jacobian not assembled";
    case NewtonStop::kLinearSolveFailed:
      return minimize ? "Hessian not positive definite" : "singular Jacobian";
    case NewtonStop::kNotDescent:
      return "Newton direction not a descent direction";
    case NewtonStop::kLineSearchFailed:
      return minimize ? "no decrease along the Newton direction"
                      : "no decrease of |F| along the Newton step";
    case NewtonStop::kRoundOffFloor:
      return "round-off floor";
    case NewtonStop::kNoProgress:
      return "no progress";
    case NewtonStop::kStopped:
      return "stopped on request";
  }
  return "unknown";
}

void NewtonReport::Append(const NewtonReport& later) {
  if (attempts == 0) initial_gradient = later.initial_gradient;
  ++attempts;
  steps += later.steps;
  iterations += later.iterations;
  seconds += later.seconds;
  assembly_seconds += later.assembly_seconds;
  factorizations += later.factorizations;
  factorization_seconds += later.factorization_seconds;
  cg_iterations += later.cg_iterations;
  cg_seconds += later.cg_seconds;
  cg_not_converged += later.cg_not_converged;
  linear_solver = later.linear_solver;
  final_gradient = later.final_gradient;
  final_merit = later.final_merit;
  converged = later.converged;
  stop = later.stop;
  stop_reason = later.stop_reason;
}

namespace {

// Wall clock for the report only.
class Timer {
 public:
  double Seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start_)
        .count();
  }

 private:
  std::chrono::steady_clock::time_point start_ =
      std::chrono::steady_clock::now();
};

}  // namespace

NewtonReport SolveNewton(NewtonProblem* problem, LinearSolver* linear_solver,
                         const NewtonSettings& settings) {
  const Timer timer;
  const LinearSolverStats stats_before = linear_solver->stats();
  const bool minimize = settings.mode == NewtonMode::kMinimize;
  NewtonReport report;
  report.linear_solver = linear_solver->name();
  const auto finish = [&](NewtonStop stop) {
    report.stop = stop;
    report.stop_reason = NewtonStopText(stop, settings.mode);
    report.converged = stop == NewtonStop::kConverged;
  };
  const auto update_counters = [&]() {
    const LinearSolverStats& s = linear_solver->stats();
    report.seconds = timer.Seconds();
    report.factorizations = s.factorizations - stats_before.factorizations;
    report.factorization_seconds =
        s.factorization_seconds - stats_before.factorization_seconds;
    report.cg_iterations = s.cg_iterations - stats_before.cg_iterations;
    report.cg_seconds = s.cg_seconds - stats_before.cg_seconds;
    report.cg_not_converged = s.cg_not_converged - stats_before.cg_not_converged;
  };

  NewtonResidual current;
  double merit = 0;
  if ((minimize && problem->Merit(NewtonPoint::kCurrent, &merit) !=
                       EvaluationStatus::kOk) ||
      problem->Residual(NewtonPoint::kCurrent, &current) !=
          EvaluationStatus::kOk) {
    finish(NewtonStop::kInfeasibleStart);
    update_counters();
    return report;
  }
  report.initial_gradient = report.final_gradient = current.max_norm;
  report.final_merit = merit;
  const double initial_two_norm = std::max(current.reduced.norm(), 1e-300);
  LinearSystem system;
  while (true) {
    if (report.final_gradient <= settings.tolerance * current.scale) {
      finish(NewtonStop::kConverged);
      break;
    }
    if (report.steps >= settings.max_steps) {
      finish(NewtonStop::kMaxSteps);
      break;
    }
    if (settings.stop && settings.stop()) {
      finish(NewtonStop::kStopped);
      break;
    }
    const double assembly_start = timer.Seconds();
    ++report.iterations;
    const EvaluationStatus assembled = problem->Assemble(&system);
    report.assembly_seconds += timer.Seconds() - assembly_start;
    if (assembled != EvaluationStatus::kOk) {
      finish(NewtonStop::kAssemblyFailed);
      break;
    }
    double forcing = settings.forcing;
    if (settings.forcing_rule == NewtonSettings::Forcing::kInexactNewton) {
      const double g = std::max(current.reduced.norm(), 1e-300);
      forcing = std::min(0.1, std::max(std::min(settings.forcing,
                                                g / initial_two_norm),
                                       0.25 * settings.tolerance / g));
    } else if (settings.forcing_rule ==
               NewtonSettings::Forcing::kRelativeResidual) {
      forcing = std::clamp(current.max_norm / current.scale,
                           settings.forcing_min, settings.forcing);
    }
    Eigen::VectorXd p;
    if (!linear_solver->Solve(system, -current.reduced, forcing, &p) ||
        !p.allFinite()) {
      finish(NewtonStop::kLinearSolveFailed);
      break;
    }
    const double slope = current.reduced.dot(p);
    if (minimize && !(slope < 0)) {
      finish(NewtonStop::kNotDescent);
      break;
    }

    // Line search: t = 1, 1/2, ..., 2^-max_halvings.
    bool accepted = false;
    const double previous_norm = report.final_gradient;
    for (int halving = 0; halving <= settings.max_halvings && !accepted;
         ++halving) {
      const double t = std::ldexp(1.0, -halving);
      problem->SetTrial(t * p);
      double trial_merit = 0;
      bool decrease = false;
      bool round_off = true;  // root finding: no merit gate
      if (minimize) {
        if (problem->Merit(NewtonPoint::kTrial, &trial_merit) !=
                EvaluationStatus::kOk ||
            !std::isfinite(trial_merit)) {
          continue;  // infeasible trial point: shorter step
        }
        decrease = trial_merit <= merit + settings.armijo * t * slope;
        round_off = std::abs(trial_merit - merit) <=
                    settings.merit_round_off * std::abs(merit);
        if (!decrease && !(settings.accept_smaller_max_norm && round_off) &&
            !settings.accept_smaller_two_norm &&
            !(settings.accept_max_norm_reduction > 0)) {
          continue;
        }
      }
      NewtonResidual trial;
      if (problem->Residual(NewtonPoint::kTrial, &trial) !=
          EvaluationStatus::kOk) {
        continue;
      }
      const bool smaller_max = settings.accept_smaller_max_norm && round_off &&
                               trial.max_norm < current.max_norm;
      const bool smaller_two = settings.accept_smaller_two_norm &&
                               trial.two_norm < current.two_norm;
      const bool reduced_max =
          settings.accept_max_norm_reduction > 0 &&
          trial.max_norm <= settings.accept_max_norm_reduction *
                                current.max_norm;
      if (!decrease && !smaller_max && !smaller_two && !reduced_max) continue;
      problem->AcceptTrial();
      current = std::move(trial);
      merit = trial_merit;
      report.final_gradient = current.max_norm;
      report.final_merit = merit;
      ++report.steps;
      accepted = true;
    }
    if (settings.progress) {
      update_counters();
      settings.progress(report, merit, accepted);
    }
    if (!accepted) {
      finish(NewtonStop::kLineSearchFailed);
      break;
    }
    const double norm = report.final_gradient;
    if (norm <= settings.round_off_floor &&
        !(norm <= settings.round_off_factor * previous_norm) &&
        !(norm <= settings.tolerance * current.scale)) {
      finish(NewtonStop::kRoundOffFloor);
      break;
    }
    if (settings.progress_steps > 0 && report.steps >= settings.progress_steps &&
        !(norm <= settings.progress_factor * report.initial_gradient)) {
      finish(NewtonStop::kNoProgress);
      break;
    }
  }
  update_counters();
  return report;
}

}  // namespace shellspace
