// The globalisations of the Newton engine (SolveNewton, newton_solver.h) as
// strategies: each turns one assembled Hessian into an accepted step or a
// failure, and keeps its own state (a shift, a damping parameter, a trust
// radius and a held preconditioner) from one iteration to the next. The
// engine's loop owns the stopping tests, the assembly and the bookkeeping of
// an accepted step; a strategy owns only how a step is found.
//   kLineSearch          newton_line_search.cc
//   kLevenbergMarquardt  newton_levenberg_marquardt.cc
//   kTrustRegion         newton_trust_region.cc
#ifndef SHELLSPACE_SOLVERS_NEWTON_STEP_STRATEGY_H_
#define SHELLSPACE_SOLVERS_NEWTON_STEP_STRATEGY_H_

#include <functional>
#include <memory>

#include "shellspace/solvers/linear_solver.h"
#include "shellspace/solvers/newton_solver.h"

namespace shellspace {

// What one iteration gives its strategy: H assembled at the current point in
// *system (a strategy may shift its diagonal in place but restores it
// exactly), the current residual and merit (merit 0 for root finding), the
// linear solver's relative tolerance `forcing` for this iteration.
struct NewtonIteration {
  NewtonProblem* problem = nullptr;
  LinearSolver* linear_solver = nullptr;
  const NewtonSettings* settings = nullptr;
  LinearSystem* system = nullptr;
  const NewtonResidual* current = nullptr;
  double merit = 0;
  double forcing = 0;
  NewtonReport* report = nullptr;  // counters a strategy adds to
  // Reports a rejected trial to settings.progress (for strategies that
  // report every trial; the counters are brought up to date first).
  std::function<void()> report_rejection;
};

struct NewtonStepOutcome {
  bool accepted = false;
  // At the accepted trial point (problem->SetTrial was its last trial).
  NewtonResidual residual;
  double merit = 0;
  bool shifted = false;  // the step solved a shifted or damped system
  NewtonStop failure = NewtonStop::kLineSearchFailed;  // if not accepted
  // Accepted, and the solve ends after it with `failure` (unless the step
  // met the tolerance).
  bool end = false;
};

class NewtonStepStrategy {
 public:
  virtual ~NewtonStepStrategy() = default;
  virtual NewtonStepOutcome Step(const NewtonIteration& iteration) = 0;
  // True if Step reports every rejected trial itself (report_rejection):
  // the engine then reports an iteration only when it accepted a step.
  virtual bool ReportsTrials() const { return false; }
  // The damping the next step would start from (kLevenbergMarquardt's
  // lambda; 0 for the others).
  virtual double damping() const { return 0; }
};

// The strategy of settings.globalisation (kLineSearch for root finding,
// whatever the setting).
std::unique_ptr<NewtonStepStrategy> MakeNewtonStepStrategy(
    const NewtonSettings& settings, LinearSolver* linear_solver);

// Each strategy's maker (one file each).
std::unique_ptr<NewtonStepStrategy> MakeLineSearchStrategy(
    const NewtonSettings& settings);
std::unique_ptr<NewtonStepStrategy> MakeLevenbergMarquardtStrategy(
    const NewtonSettings& settings);
std::unique_ptr<NewtonStepStrategy> MakeTrustRegionStrategy(
    const NewtonSettings& settings, LinearSolver* linear_solver);

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_NEWTON_STEP_STRATEGY_H_
