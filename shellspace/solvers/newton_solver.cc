#include "shellspace/solvers/newton_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "shellspace/geometry/named_values.h"
#include "shellspace/solvers/newton_step_strategy.h"

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
    {NewtonStop::kHandedOver, "gradient contracting: handed over"},
    {NewtonStop::kOutsideBasin, "not yet in Newton's basin"},
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
  final_damping = later.final_damping;
  linear_solver = later.linear_solver;
  final_gradient = later.final_gradient;
  final_merit = later.final_merit;
  converged = later.converged;
  stop = later.stop;
  stop_reason = later.stop_reason;
  restored_best = restored_best || later.restored_best;
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

// The linear solver's counters of this solve (its stats now minus `before`)
// and the seconds so far, into *report.
void SetSolveCounters(const LinearSolverStats& before,
                      const LinearSolverStats& now, const Timer& timer,
                      NewtonReport* report) {
  report->seconds = timer.Seconds();
  report->factorizations = now.factorizations - before.factorizations;
  report->time_coupled_factorizations =
      now.time_coupled_factorizations - before.time_coupled_factorizations;
  report->factorization_seconds =
      now.factorization_seconds - before.factorization_seconds;
  report->cg_iterations = now.cg_iterations - before.cg_iterations;
  report->cg_seconds = now.cg_seconds - before.cg_seconds;
  report->cg_not_converged = now.cg_not_converged - before.cg_not_converged;
}

// The relative residual the linear solve of this step must reach
// (NewtonSettings::forcing_rule).
double ForcingTerm(const NewtonSettings& settings,
                   const NewtonResidual& current, double initial_two_norm) {
  switch (settings.forcing_rule) {
    case NewtonSettings::Forcing::kInexactNewton: {
      const double g = std::max(current.reduced.norm(), 1e-300);
      const double fall = g / initial_two_norm;
      return std::min(0.1, std::max(std::min(settings.forcing, fall * fall),
                                    0.25 * settings.tolerance / g));
    }
    case NewtonSettings::Forcing::kRelativeResidual:
      return std::clamp(current.max_norm / current.scale, settings.forcing_min,
                        settings.forcing);
    case NewtonSettings::Forcing::kFixed:
      break;
  }
  return settings.forcing;
}

// The stop rules checked before a step: the tolerance, the step budget and
// the caller's stop token.
std::optional<NewtonStop> StopBeforeStep(const NewtonSettings& settings,
                                         const NewtonReport& report,
                                         const NewtonResidual& current) {
  if (report.final_gradient <= settings.tolerance * current.scale) {
    return NewtonStop::kConverged;
  }
  if (report.steps >= settings.max_steps) return NewtonStop::kMaxSteps;
  if (settings.stop.stop_requested()) return NewtonStop::kStopped;
  return std::nullopt;
}

// The stop rules checked after an accepted step that brought max_norm from
// `previous_norm` to report.final_gradient without reaching the tolerance:
// the strategy's end, the round-off floor, the hand-over to the caller, the
// stall rule (over *accepted_norms, appended here) and the no-progress rule.
std::optional<NewtonStop> StopAfterStep(const NewtonSettings& settings,
                                        const NewtonStepOutcome& outcome,
                                        const NewtonReport& report,
                                        double previous_norm, double scale,
                                        std::vector<double>* accepted_norms) {
  const double norm = report.final_gradient;
  if (norm <= settings.tolerance * scale) return std::nullopt;
  if (outcome.end) return outcome.failure;
  if (norm <= settings.round_off_floor &&
      !(norm <= settings.round_off_factor * previous_norm)) {
    return NewtonStop::kRoundOffFloor;
  }
  if (settings.mode == NewtonMode::kMinimize &&
      settings.hand_over_contraction > 0 &&
      norm * settings.hand_over_contraction <= previous_norm) {
    return NewtonStop::kHandedOver;
  }
  if (settings.stall_steps > 0) {
    accepted_norms->push_back(norm);
    const size_t steps = accepted_norms->size();
    if (steps > static_cast<size_t>(settings.stall_steps) &&
        !(norm <= settings.stall_factor *
                      (*accepted_norms)[steps - 1 - settings.stall_steps])) {
      return NewtonStop::kNoProgress;
    }
  }
  if (settings.progress_steps > 0 && report.steps >= settings.progress_steps &&
      !(norm <= settings.progress_factor * report.initial_gradient)) {
    return NewtonStop::kNoProgress;
  }
  return std::nullopt;
}

// The solve's end `stop` (worded for `mode`) into *report.
void FinishReport(NewtonStop stop, NewtonMode mode, NewtonReport* report) {
  report->stop = stop;
  report->stop_reason = NewtonStopText(stop, mode);
  report->converged = stop == NewtonStop::kConverged;
}

// The report of a start where the residual or merit cannot be evaluated.
// No residual, not a residual of 0: a caller that compares final_gradient
// with its tolerance must not see a converged start.
void ReportInfeasibleStart(NewtonMode mode, NewtonReport* report) {
  report->initial_gradient = report->final_gradient = HUGE_VAL;
  report->final_merit = HUGE_VAL;
  FinishReport(NewtonStop::kInfeasibleStart, mode, report);
}

// The residual (and, when minimising, the merit) at the start; false if
// either cannot be evaluated.
bool EvaluateStart(NewtonProblem* problem, const NewtonSettings& settings,
                   NewtonResidual* current, double* merit) {
  const bool minimize = settings.mode == NewtonMode::kMinimize;
  return !((minimize && problem->Merit(NewtonPoint::kCurrent, merit) !=
                            EvaluationStatus::kOk) ||
           problem->Residual(NewtonPoint::kCurrent, current) !=
               EvaluationStatus::kOk);
}

// H at the current point into *system, counted as an iteration and timed;
// false if it cannot be assembled.
bool AssembleTimed(NewtonProblem* problem, const Timer& timer,
                   LinearSystem* system, NewtonReport* report) {
  const double assembly_start = timer.Seconds();
  ++report->iterations;
  const EvaluationStatus assembled = problem->Assemble(system);
  report->assembly_seconds += timer.Seconds() - assembly_start;
  return assembled == EvaluationStatus::kOk;
}

// The iteration at the current point for the step strategy (without its
// report_rejection).
NewtonIteration IterationAt(NewtonProblem* problem, LinearSolver* linear_solver,
                            const NewtonSettings& settings,
                            LinearSystem* system, const NewtonResidual& current,
                            double merit, double forcing,
                            NewtonReport* report) {
  NewtonIteration iteration;
  iteration.problem = problem;
  iteration.linear_solver = linear_solver;
  iteration.settings = &settings;
  iteration.system = system;
  iteration.current = &current;
  iteration.merit = merit;
  iteration.forcing = forcing;
  iteration.report = report;
  return iteration;
}

// Moves to the trial point of an accepted step `outcome`: its residual and
// merit become the current ones, and the step is counted.
void TakeStep(NewtonProblem* problem, NewtonStepOutcome* outcome,
              NewtonResidual* current, double* merit, NewtonReport* report) {
  problem->AcceptTrial();
  *current = std::move(outcome->residual);
  *merit = outcome->merit;
  report->final_gradient = current->max_norm;
  report->final_merit = *merit;
  ++report->steps;
  if (outcome->shifted) ++report->shifted_steps;
}

}  // namespace

std::unique_ptr<NewtonStepStrategy> MakeNewtonStepStrategy(
    const NewtonSettings& settings, LinearSolver* linear_solver) {
  if (settings.mode != NewtonMode::kMinimize) {
    return MakeLineSearchStrategy(settings);
  }
  switch (settings.globalisation) {
    case NewtonSettings::Globalisation::kLevenbergMarquardt:
      return MakeLevenbergMarquardtStrategy(settings);
    case NewtonSettings::Globalisation::kTrustRegion:
      return MakeTrustRegionStrategy(settings, linear_solver);
    case NewtonSettings::Globalisation::kLineSearch:
      break;
  }
  return MakeLineSearchStrategy(settings);
}

NewtonReport SolveNewton(NewtonProblem* problem, LinearSolver* linear_solver,
                         const NewtonSettings& settings) {
  const Timer timer;
  const LinearSolverStats stats_before = linear_solver->stats();
  NewtonReport report;
  report.linear_solver = linear_solver->name();
  const auto update_counters = [&]() {
    SetSolveCounters(stats_before, linear_solver->stats(), timer, &report);
  };

  NewtonResidual current;
  double merit = 0;
  if (!EvaluateStart(problem, settings, &current, &merit)) {
    ReportInfeasibleStart(settings.mode, &report);
    update_counters();
    return report;
  }
  report.initial_gradient = report.final_gradient = current.max_norm;
  report.final_merit = merit;
  const double initial_two_norm = std::max(current.reduced.norm(), 1e-300);
  LinearSystem system;
  const std::unique_ptr<NewtonStepStrategy> strategy =
      MakeNewtonStepStrategy(settings, linear_solver);
  // max_norm after each accepted step (the stall rule).
  std::vector<double> accepted_norms;
  while (true) {
    if (const auto stop = StopBeforeStep(settings, report, current)) {
      FinishReport(*stop, settings.mode, &report);
      break;
    }
    if (!AssembleTimed(problem, timer, &system, &report)) {
      FinishReport(NewtonStop::kAssemblyFailed, settings.mode, &report);
      break;
    }
    const double previous_norm = report.final_gradient;
    NewtonIteration iteration =
        IterationAt(problem, linear_solver, settings, &system, current, merit,
                    ForcingTerm(settings, current, initial_two_norm), &report);
    iteration.report_rejection = [&]() {
      if (!settings.progress) return;
      update_counters();
      settings.progress(report, merit, false);
    };
    NewtonStepOutcome outcome = strategy->Step(iteration);
    const bool accepted = outcome.accepted;
    if (accepted) TakeStep(problem, &outcome, &current, &merit, &report);
    if (settings.progress && (accepted || !strategy->ReportsTrials())) {
      update_counters();
      settings.progress(report, merit, accepted);
    }
    if (!accepted) {
      FinishReport(outcome.failure, settings.mode, &report);
      break;
    }
    if (const auto stop =
            StopAfterStep(settings, outcome, report, previous_norm,
                          current.scale, &accepted_norms)) {
      FinishReport(*stop, settings.mode, &report);
      break;
    }
  }
  report.final_damping = strategy->damping();
  update_counters();
  return report;
}

}  // namespace shellspace
