// NewtonSettings::Globalisation::kTrustRegion: Steihaug-Toint CG
// (steihaug_cg.h) on the model g^T p + p^T H p / 2 in the trust region
// |p|_M <= radius, M the linear solver's preconditioner (factorised from H,
// or from H + sigma I where H is not positive definite, and held while the
// subproblems stay cheap); rho = actual / predicted decrease accepts a step
// at rho >= tr_accept, the radius shrinks to a quarter of the step below
// rho = 1/4 and doubles above 3/4 when the boundary cut the step short.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "shellspace/solvers/newton_step_strategy.h"
#include "shellspace/solvers/steihaug_cg.h"

namespace shellspace {
namespace {

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

// One Steihaug-Toint trial judged: its rho = actual / predicted decrease
// (-1 where the trial cannot be evaluated), whether the merit changed by less
// than its round-off, and whether the step is taken (with the residual at the
// trial point).
struct TrustRegionTrial {
  double ratio = -1;
  bool round_off = false;
  double merit = 0;
  bool residual_decides = false;
  bool take = false;
  NewtonResidual residual;
};

// Evaluates the trial point of `step` from the current point of `it` and
// decides whether the step is taken.
TrustRegionTrial JudgeTrial(const NewtonIteration& it,
                            const SteihaugResult& step) {
  NewtonProblem* const problem = it.problem;
  const NewtonSettings& settings = *it.settings;
  const double merit = it.merit;
  const NewtonResidual& current = *it.current;
  TrustRegionTrial trial;
  if (step.model_decrease > 0 && step.step.allFinite()) {
    problem->SetTrial(step.step);
    if (problem->Merit(NewtonPoint::kTrial, &trial.merit) ==
            EvaluationStatus::kOk &&
        std::isfinite(trial.merit)) {
      trial.ratio = (merit - trial.merit) / step.model_decrease;
      trial.round_off = std::abs(trial.merit - merit) <=
                        settings.merit_round_off * std::abs(merit);
    }
  }
  // Where the merit changes by less than its round-off (with
  // accept_smaller_max_norm, or where the predicted decrease itself is
  // below it), rho is noise: the residual alone decides, and a step that
  // raises its max norm is not taken however good its rho.
  const bool model_at_round_off =
      step.model_decrease <= settings.merit_round_off * std::abs(merit);
  trial.residual_decides =
      trial.round_off &&
      (settings.accept_smaller_max_norm || model_at_round_off);
  if (trial.ratio >= settings.tr_accept || trial.residual_decides) {
    trial.take =
        problem->Residual(NewtonPoint::kTrial, &trial.residual) ==
            EvaluationStatus::kOk &&
        (trial.residual_decides ? trial.residual.max_norm < current.max_norm
                                : trial.ratio >= settings.tr_accept);
  }
  return trial;
}

// The basin probe: anything but a full step of a good model ends it (a
// step whose decrease is below round-off, taken because the residual
// fell, counts as good: its rho is noise).
bool OutsideBasin(const NewtonSettings& settings, const SteihaugResult& step,
                  const TrustRegionTrial& trial, bool on_boundary) {
  return settings.tr_basin_ratio > 0 &&
         (!trial.take || on_boundary ||
          step.stop == SteihaugResult::Stop::kNegativeCurvature ||
          (!(trial.ratio >= settings.tr_basin_ratio) &&
           !trial.residual_decides));
}

class TrustRegionStrategy : public NewtonStepStrategy {
 public:
  TrustRegionStrategy(const NewtonSettings& settings,
                      LinearSolver* linear_solver)
      : preconditioner_(linear_solver->preconditioner()),
        radius_(settings.tr_initial_radius) {}

  NewtonStepOutcome Step(const NewtonIteration& it) override;

 private:
  SteihaugResult SolveSubproblem(const NewtonIteration& it);
  void UpdateRadius(const SteihaugResult& step, const TrustRegionTrial& trial,
                    bool on_boundary);

  Preconditioner* const preconditioner_;
  double radius_;  // in the norm |.|_M of the preconditioner
  // The preconditioner held across iterations: M of an earlier H is kept
  // while the subproblems it preconditions take at most
  // tr_refactor_cg_iterations CG iterations (a deterministic count, no
  // clock); near a minimiser successive Hessians differ little.
  bool held_ = false;
  int last_cg_iterations_ = 0;
};

// The Steihaug-Toint step for the current radius (its CG iterations and time
// counted by the linear solver).
SteihaugResult TrustRegionStrategy::SolveSubproblem(const NewtonIteration& it) {
  const auto cg_start = std::chrono::steady_clock::now();
  const SteihaugResult step =
      SolveSteihaugCg(it.system->matrix, it.current->reduced, *preconditioner_,
                      radius_, it.forcing, it.settings->tr_max_cg_iterations);
  last_cg_iterations_ = step.iterations;
  it.linear_solver->CountCg(
      step.iterations,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - cg_start)
          .count());
  return step;
}

// The radius: shrink to a quarter of the step on a poor model, a trial
// that cannot be evaluated or one not taken (below round-off, a good
// rho does not take a step that raises the residual), double it after a
// good step that the boundary cut short.
void TrustRegionStrategy::UpdateRadius(const SteihaugResult& step,
                                       const TrustRegionTrial& trial,
                                       bool on_boundary) {
  if (!trial.take || (!(trial.ratio >= 0.25) && !trial.round_off)) {
    radius_ = 0.25 * step.step_norm;
  } else if (trial.ratio > 0.75 && on_boundary) {
    radius_ = 2 * radius_;
  }
}

// One iteration at the current point (H assembled in *system): the
// preconditioner factorised (shifted where needed) unless it is held, then
// Steihaug-Toint steps for the radius until one is accepted or
// tr_max_rejections trials in a row are rejected.
NewtonStepOutcome TrustRegionStrategy::Step(const NewtonIteration& it) {
  const NewtonSettings& settings = *it.settings;
  NewtonReport* const report = it.report;
  NewtonStepOutcome outcome;
  if (preconditioner_ == nullptr) {
    outcome.failure = NewtonStop::kLinearSolveFailed;
    return outcome;
  }
  if (!held_ || last_cg_iterations_ > settings.tr_refactor_cg_iterations) {
    held_ =
        FactorizePreconditioner(preconditioner_, settings, it.system, report);
  }
  if (!held_) {
    outcome.failure = NewtonStop::kLinearSolveFailed;
    return outcome;
  }
  for (int rejected = 0; rejected <= settings.tr_max_rejections; ++rejected) {
    if (rejected > 0 && settings.stop.stop_requested()) {
      outcome.failure = NewtonStop::kStopped;
      return outcome;
    }
    const SteihaugResult step = SolveSubproblem(it);
    const bool on_boundary =
        step.stop == SteihaugResult::Stop::kBoundary ||
        (step.stop == SteihaugResult::Stop::kNegativeCurvature &&
         std::isfinite(radius_));
    TrustRegionTrial trial = JudgeTrial(it, step);
    const bool outside_basin = OutsideBasin(settings, step, trial, on_boundary);
    UpdateRadius(step, trial, on_boundary);
    if (trial.take) {
      if (on_boundary) ++report->boundary_steps;
      if (step.stop == SteihaugResult::Stop::kNegativeCurvature) {
        ++report->negative_curvature_steps;
      }
      outcome.accepted = true;
      outcome.residual = std::move(trial.residual);
      outcome.merit = trial.merit;
      outcome.end = outside_basin;
      if (outside_basin) outcome.failure = NewtonStop::kOutsideBasin;
      return outcome;
    }
    ++report->rejected_trials;
    if (outside_basin) {
      outcome.failure = NewtonStop::kOutsideBasin;
      return outcome;
    }
    if (!(step.step_norm > 0)) break;  // no step left to shrink
  }
  return outcome;
}

}  // namespace

std::unique_ptr<NewtonStepStrategy> MakeTrustRegionStrategy(
    const NewtonSettings& settings, LinearSolver* linear_solver) {
  return std::make_unique<TrustRegionStrategy>(settings, linear_solver);
}

}  // namespace shellspace
