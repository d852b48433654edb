#include "shellspace/solvers/newton_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>
#include <vector>

#include "shellspace/geometry/named_values.h"
#include "shellspace/solvers/steihaug_cg.h"

namespace shellspace {

NewtonResidual NewtonResidual::OfReduced(Eigen::VectorXd reduced) {
  NewtonResidual r;
  r.max_norm = reduced.size() ? reduced.cwiseAbs().maxCoeff() : 0.0;
  r.two_norm = reduced.norm();
  r.reduced = std::move(reduced);
  return r;
}

namespace {

// The stop texts; root finding words three of them differently.
constexpr NamedValue<NewtonStop> kNewtonStopTexts[] = {
    {NewtonStop::kConverged, "converged"},
    {NewtonStop::kMaxSteps, "max steps"},
    {NewtonStop::kInfeasibleStart, "degenerate initial guess"},
    {NewtonStop::kAssemblyFailed, "Hessian not assembled"},
    {NewtonStop::kLinearSolveFailed, "Hessian not positive definite"},
    {NewtonStop::kNotDescent, "Newton direction not a descent direction"},
    {NewtonStop::kLineSearchFailed, "no decrease along the Newton direction"},
    {NewtonStop::kRoundOffFloor, "round-off floor"},
    {NewtonStop::kNoProgress, "no progress"},
    {NewtonStop::kStopped, "stopped on request"}};
constexpr NamedValue<NewtonStop> kRootFindingStopTexts[] = {
    {NewtonStop::kAssemblyFailed, "Jacobian not assembled"},
    {NewtonStop::kLinearSolveFailed, "singular Jacobian"},
    {NewtonStop::kLineSearchFailed,
     "no decrease of |F| along the Newton step"}};

}  // namespace

std::string NewtonStopText(NewtonStop stop, NewtonMode mode) {
  if (mode != NewtonMode::kMinimize) {
    if (const char* text = NameOf(kRootFindingStopTexts, stop, nullptr)) {
      return text;
    }
  }
  return NameOf(kNewtonStopTexts, stop);
}

void NewtonReport::Append(const NewtonReport& later) {
  if (attempts == 0) initial_gradient = later.initial_gradient;
  ++attempts;
  steps += later.steps;
  iterations += later.iterations;
  seconds += later.seconds;
  assembly_seconds += later.assembly_seconds;
  factorizations += later.factorizations;
  time_coupled_factorizations += later.time_coupled_factorizations;
  factorization_seconds += later.factorization_seconds;
  cg_iterations += later.cg_iterations;
  cg_seconds += later.cg_seconds;
  cg_not_converged += later.cg_not_converged;
  shifted_steps += later.shifted_steps;
  boundary_steps += later.boundary_steps;
  negative_curvature_steps += later.negative_curvature_steps;
  rejected_trials += later.rejected_trials;
  shifted_preconditioners += later.shifted_preconditioners;
  max_shift = std::max(max_shift, later.max_shift);
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

// One iteration of NewtonSettings::Globalisation::kTrustRegion at the
// current point (H assembled in *system): the preconditioner factorised
// (shifted where needed), then Steihaug-Toint steps for the radius until
// one is accepted or tr_max_rejections trials in a row are rejected.
struct TrustRegionOutcome {
  bool accepted = false;
  NewtonResidual residual;  // at the accepted trial
  double merit = 0;
  NewtonStop failure = NewtonStop::kLineSearchFailed;
};

// Factorises M from H, or from H + sigma I where H's factorisation is not
// positive definite (the diagonal shifted in place and restored exactly).
bool FactorizePreconditioner(Preconditioner* preconditioner,
                             const NewtonSettings& settings,
                             LinearSystem* system, NewtonReport* report) {
  // M from H, or from H + sigma I where H's factorisation is not positive
  // definite: the diagonal is shifted in place and restored exactly.
  const int n = static_cast<int>(system->matrix.rows());
  std::vector<double*> diagonal_entry(n);
  std::vector<double> unshifted(n);
  double mean_diagonal = 0;
  for (int i = 0; i < n; ++i) {
    diagonal_entry[i] = &system->matrix.coeffRef(i, i);
    unshifted[i] = *diagonal_entry[i];
    mean_diagonal += std::abs(unshifted[i]) / n;
  }
  bool factorized = preconditioner->Factorize(*system);
  double sigma = settings.tr_shift_initial * std::max(mean_diagonal, 1e-300);
  for (int shift = 0; !factorized && shift < settings.tr_max_shifts;
       ++shift, sigma *= 10) {
    for (int i = 0; i < n; ++i) *diagonal_entry[i] = unshifted[i] + sigma;
    factorized = preconditioner->Factorize(*system);
    for (int i = 0; i < n; ++i) *diagonal_entry[i] = unshifted[i];
    if (factorized) ++report->shifted_preconditioners;
  }
  return factorized;
}

// The preconditioner held across iterations: M of an earlier H is kept
// while the subproblems it preconditions take at most
// tr_refactor_cg_iterations CG iterations (a deterministic count, no
// clock); near a minimiser successive Hessians differ little.
struct HeldPreconditioner {
  bool held = false;
  int last_cg_iterations = 0;
};

TrustRegionOutcome TrustRegionIteration(
    NewtonProblem* problem, LinearSolver* linear_solver,
    Preconditioner* preconditioner, const NewtonSettings& settings,
    double forcing, double merit, const NewtonResidual& current,
    LinearSystem* system, double* radius, HeldPreconditioner* held,
    NewtonReport* report) {
  TrustRegionOutcome outcome;
  if (preconditioner == nullptr) {
    outcome.failure = NewtonStop::kLinearSolveFailed;
    return outcome;
  }
  if (!held->held ||
      held->last_cg_iterations > settings.tr_refactor_cg_iterations) {
    held->held = FactorizePreconditioner(preconditioner, settings, system,
                                         report);
  }
  if (!held->held) {
    outcome.failure = NewtonStop::kLinearSolveFailed;
    return outcome;
  }
  const Eigen::VectorXd& g = current.reduced;
  for (int rejected = 0; rejected <= settings.tr_max_rejections; ++rejected) {
    if (rejected > 0 && settings.stop && settings.stop()) {
      outcome.failure = NewtonStop::kStopped;
      return outcome;
    }
    const auto cg_start = std::chrono::steady_clock::now();
    const SteihaugResult step =
        SolveSteihaugCg(system->matrix, g, *preconditioner, *radius, forcing,
                        settings.tr_max_cg_iterations);
    held->last_cg_iterations = step.iterations;
    linear_solver->CountCg(
        step.iterations,
        std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                      cg_start)
            .count());
    const bool on_boundary =
        step.stop == SteihaugResult::Stop::kBoundary ||
        (step.stop == SteihaugResult::Stop::kNegativeCurvature &&
         std::isfinite(*radius));
    double ratio = -1;
    bool round_off = false;
    double trial_merit = 0;
    if (step.model_decrease > 0 && step.step.allFinite()) {
      problem->SetTrial(step.step);
      if (problem->Merit(NewtonPoint::kTrial, &trial_merit) ==
              EvaluationStatus::kOk &&
          std::isfinite(trial_merit)) {
        ratio = (merit - trial_merit) / step.model_decrease;
        round_off = std::abs(trial_merit - merit) <=
                    settings.merit_round_off * std::abs(merit);
      }
    }
    // Where the predicted decrease itself is below the merit's round-off,
    // rho is noise: the residual decides (as with accept_smaller_max_norm).
    const bool model_at_round_off =
        step.model_decrease <= settings.merit_round_off * std::abs(merit);
    const bool residual_decides =
        round_off && (settings.accept_smaller_max_norm || model_at_round_off);
    bool take = false;
    NewtonResidual trial;
    if (ratio >= settings.tr_accept || residual_decides) {
      take = problem->Residual(NewtonPoint::kTrial, &trial) ==
                 EvaluationStatus::kOk &&
             (ratio >= settings.tr_accept ||
              trial.max_norm < current.max_norm);
    }
    // The radius: shrink to a quarter of the step on a poor model (or a
    // trial that cannot be evaluated), double it after a good step that the
    // boundary cut short.
    if (!(ratio >= 0.25) && !(take && round_off)) {
      *radius = 0.25 * step.step_norm;
    } else if (ratio > 0.75 && on_boundary) {
      *radius = 2 * *radius;
    }
    if (take) {
      if (on_boundary) ++report->boundary_steps;
      if (step.stop == SteihaugResult::Stop::kNegativeCurvature) {
        ++report->negative_curvature_steps;
      }
      outcome.accepted = true;
      outcome.residual = std::move(trial);
      outcome.merit = trial_merit;
      return outcome;
    }
    ++report->rejected_trials;
    if (!(step.step_norm > 0)) break;  // no step left to shrink
  }
  return outcome;
}

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
    report.time_coupled_factorizations =
        s.time_coupled_factorizations -
        stats_before.time_coupled_factorizations;
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
  double shift = 0;  // lambda of the last accepted step's H + lambda I
  const bool levenberg_marquardt =
      minimize &&
      settings.globalisation == NewtonSettings::Globalisation::kLevenbergMarquardt;
  double lm_lambda = settings.lm_initial;  // kLevenbergMarquardt's lambda, nu
  double lm_nu = 2;
  const bool trust_region =
      minimize &&
      settings.globalisation == NewtonSettings::Globalisation::kTrustRegion;
  Preconditioner* const preconditioner =
      trust_region ? linear_solver->preconditioner() : nullptr;
  double radius = settings.tr_initial_radius;  // kTrustRegion's, in |.|_M
  HeldPreconditioner held_preconditioner;
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
    bool accepted = false;
    NewtonStop failure = NewtonStop::kLineSearchFailed;
    const double previous_norm = report.final_gradient;
    // x = the trial point (residual `trial`, merit `trial_merit`).
    const auto accept = [&](NewtonResidual trial, double trial_merit,
                            bool shifted) {
      problem->AcceptTrial();
      current = std::move(trial);
      merit = trial_merit;
      report.final_gradient = current.max_norm;
      report.final_merit = merit;
      ++report.steps;
      if (shifted) ++report.shifted_steps;
      accepted = true;
    };
    if (levenberg_marquardt) {
      // Steps of (H + lambda D) p = -reduced until one decreases the merit
      // by lm_min_ratio of the model's prediction.
      const int n = static_cast<int>(system.matrix.rows());
      Eigen::VectorXd diagonal = system.matrix.diagonal().cwiseAbs();
      const double mean = n > 0 ? diagonal.sum() / n : 0.0;
      diagonal = diagonal.cwiseMax(settings.lm_min_diagonal *
                                   std::max(mean, 1e-300));
      // H + lambda D is solved in place: the stored diagonal of H is shifted
      // for the solve and restored (exactly, from `undamped`) before the
      // model is evaluated -- no copy of H (on the cactus x4 one H is about
      // 0.3 GB).
      std::vector<double*> diagonal_entry(n);
      std::vector<double> undamped(n);
      for (int i = 0; i < n; ++i) {
        diagonal_entry[i] = &system.matrix.coeffRef(i, i);
        undamped[i] = *diagonal_entry[i];
      }
      bool stop_requested = false;
      for (int rejected = 0; !accepted; ++rejected) {
        if (rejected > settings.lm_max_rejections) break;
        // Polled once per retry (the first try was polled above).
        if (rejected > 0 && settings.stop && settings.stop()) {
          stop_requested = true;
          break;
        }
        for (int i = 0; i < n; ++i) {
          *diagonal_entry[i] = undamped[i] + lm_lambda * diagonal(i);
        }
        report.max_shift = std::max(report.max_shift, lm_lambda);
        Eigen::VectorXd p;
        const bool solved =
            linear_solver->Solve(system, -current.reduced, forcing, &p) &&
            p.allFinite();
        for (int i = 0; i < n; ++i) *diagonal_entry[i] = undamped[i];
        double ratio = -1;
        bool round_off = false;  // |merit change| below round-off
        NewtonResidual trial;
        double trial_merit = 0;
        if (solved) {
          const Eigen::VectorXd hp =
              system.matrix.selfadjointView<Eigen::Lower>() * p;
          const double predicted = -(current.reduced.dot(p) + 0.5 * p.dot(hp));
          if (predicted > 0) {
            problem->SetTrial(p);
            if (problem->Merit(NewtonPoint::kTrial, &trial_merit) ==
                    EvaluationStatus::kOk &&
                std::isfinite(trial_merit) &&
                trial_merit <=
                    merit + settings.merit_round_off * std::abs(merit)) {
              ratio = (merit - trial_merit) / predicted;
              round_off = std::abs(trial_merit - merit) <=
                          settings.merit_round_off * std::abs(merit);
            }
          }
        } else {
          failure = NewtonStop::kLinearSolveFailed;
        }
        // Accepted on the model's ratio, or (accept_smaller_max_norm) where
        // the merit change is below round-off and the residual falls.
        bool take = false;
        if (ratio >= settings.lm_min_ratio ||
            (settings.accept_smaller_max_norm && round_off)) {
          take = problem->Residual(NewtonPoint::kTrial, &trial) ==
                     EvaluationStatus::kOk &&
                 (ratio >= settings.lm_min_ratio ||
                  trial.max_norm < current.max_norm);
        }
        if (take) {
          accept(std::move(trial), trial_merit, true);
          const double c = 2 * std::clamp(ratio, 0.0, 1.0) - 1;
          lm_lambda *= std::max(1.0 / 3.0, 1 - c * c * c);
          lm_nu = 2;
        } else {
          lm_lambda *= lm_nu;
          lm_nu *= 2;
          if (solved) failure = NewtonStop::kLineSearchFailed;
        }
        if (settings.progress) {
          update_counters();
          settings.progress(report, merit, accepted);
        }
      }
      if (!accepted && stop_requested) failure = NewtonStop::kStopped;
    }
    if (trust_region) {
      const TrustRegionOutcome outcome = TrustRegionIteration(
          problem, linear_solver, preconditioner, settings, forcing, merit,
          current, &system, &radius, &held_preconditioner, &report);
      if (outcome.accepted) {
        accept(outcome.residual, outcome.merit, false);
      } else {
        failure = outcome.failure;
      }
      if (settings.progress) {
        update_counters();
        settings.progress(report, merit, accepted);
      }
    }
    // The Newton step, then (minimisation with max_shifts > 0) steps of
    // H + lambda I while the step cannot be used.
    const bool can_shift =
        minimize && settings.max_shifts > 0 && !levenberg_marquardt &&
        !trust_region;
    double mean_diagonal = 0;
    if (can_shift && system.matrix.rows() > 0) {
      mean_diagonal =
          system.matrix.diagonal().cwiseAbs().sum() / system.matrix.rows();
    }
    const double min_shift =
        settings.shift_initial * std::max(mean_diagonal, 1e-300);
    if (shift < min_shift) shift = 0;
    for (int tries = 0; !accepted && !levenberg_marquardt && !trust_region;
         ++tries) {
      if (tries > 0) {
        if (!can_shift || tries > settings.max_shifts) break;
        shift = shift > 0 ? shift * settings.shift_factor : min_shift;
      }
      LinearSystem shifted_system;
      const LinearSystem* to_solve = &system;
      if (shift > 0) {
        shifted_system = system;
        Eigen::SparseMatrix<double> identity(system.matrix.rows(),
                                             system.matrix.cols());
        identity.setIdentity();
        shifted_system.matrix = system.matrix + shift * identity;
        to_solve = &shifted_system;
        report.max_shift = std::max(report.max_shift, shift);
      }
      Eigen::VectorXd p;
      if (!linear_solver->Solve(*to_solve, -current.reduced, forcing, &p) ||
          !p.allFinite()) {
        failure = NewtonStop::kLinearSolveFailed;
        continue;
      }
      const double slope = current.reduced.dot(p);
      if (minimize && !(slope < 0)) {
        failure = NewtonStop::kNotDescent;
        continue;
      }
      failure = NewtonStop::kLineSearchFailed;

      // Line search: t = 1, 1/2, ..., 2^-max_halvings.
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
          // The merit never rises beyond round-off.
          const bool not_worse =
              trial_merit <= merit + settings.merit_round_off * std::abs(merit);
          if (!decrease &&
              (!not_worse ||
               (!(settings.accept_smaller_max_norm && round_off) &&
                !settings.accept_smaller_two_norm &&
                !(settings.accept_max_norm_reduction > 0)))) {
            continue;
          }
        }
        NewtonResidual trial;
        if (problem->Residual(NewtonPoint::kTrial, &trial) !=
            EvaluationStatus::kOk) {
          continue;
        }
        const bool smaller_max = settings.accept_smaller_max_norm &&
                                 round_off &&
                                 trial.max_norm < current.max_norm;
        const bool smaller_two = settings.accept_smaller_two_norm &&
                                 trial.two_norm < current.two_norm;
        const bool reduced_max =
            settings.accept_max_norm_reduction > 0 &&
            trial.max_norm <= settings.accept_max_norm_reduction *
                                  current.max_norm;
        if (!decrease && !smaller_max && !smaller_two && !reduced_max) {
          continue;
        }
        accept(std::move(trial), trial_merit, shift > 0);
      }
    }
    if (accepted && shift > 0) shift /= settings.shift_factor;
    if (settings.progress && !levenberg_marquardt && !trust_region) {
      update_counters();
      settings.progress(report, merit, accepted);
    }
    if (!accepted) {
      finish(failure);
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
