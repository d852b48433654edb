// NewtonSettings::Globalisation::kLineSearch (and every root finding): the
// Newton step p of H p = -g, backtracked t = 1, 1/2, ..., 2^-max_halvings
// until the Armijo condition (or one of the accept_* rules) holds; for
// minimisation with max_shifts > 0, steps of H + lambda I (lambda from
// shift_initial times the mean |diagonal|, times shift_factor a retry) while
// the step cannot be used. The last accepted lambda, divided by
// shift_factor, starts the next iteration.
#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "shellspace/solvers/newton_step_strategy.h"

namespace shellspace {
namespace {

class LineSearchStrategy : public NewtonStepStrategy {
 public:
  explicit LineSearchStrategy(const NewtonSettings& settings)
      : minimize_(settings.mode == NewtonMode::kMinimize) {}

  NewtonStepOutcome Step(const NewtonIteration& it) override {
    const NewtonSettings& settings = *it.settings;
    const LinearSystem& system = *it.system;
    const NewtonResidual& current = *it.current;
    NewtonStepOutcome outcome;
    const bool can_shift = minimize_ && settings.max_shifts > 0;
    double mean_diagonal = 0;
    if (can_shift && system.matrix.rows() > 0) {
      mean_diagonal =
          system.matrix.diagonal().cwiseAbs().sum() / system.matrix.rows();
    }
    const double min_shift =
        settings.shift_initial * std::max(mean_diagonal, 1e-300);
    if (shift_ < min_shift) shift_ = 0;
    for (int tries = 0; !outcome.accepted; ++tries) {
      if (tries > 0) {
        if (!can_shift || tries > settings.max_shifts) break;
        shift_ = shift_ > 0 ? shift_ * settings.shift_factor : min_shift;
      }
      LinearSystem shifted_system;
      const LinearSystem* to_solve = &system;
      if (shift_ > 0) {
        shifted_system = system;
        Eigen::SparseMatrix<double> identity(system.matrix.rows(),
                                             system.matrix.cols());
        identity.setIdentity();
        shifted_system.matrix = system.matrix + shift_ * identity;
        to_solve = &shifted_system;
        it.report->max_shift = std::max(it.report->max_shift, shift_);
      }
      Eigen::VectorXd p;
      if (!it.linear_solver->Solve(*to_solve, -current.reduced, it.forcing,
                                   &p) ||
          !p.allFinite()) {
        outcome.failure = NewtonStop::kLinearSolveFailed;
        continue;
      }
      const double slope = current.reduced.dot(p);
      if (minimize_ && !(slope < 0)) {
        outcome.failure = NewtonStop::kNotDescent;
        continue;
      }
      outcome.failure = NewtonStop::kLineSearchFailed;
      Backtrack(it, p, slope, &outcome);
    }
    if (outcome.accepted && shift_ > 0) shift_ /= settings.shift_factor;
    return outcome;
  }

 private:
  // Trials x + t p, t = 1, 1/2, ..., 2^-max_halvings; the first acceptable
  // one fills *outcome.
  void Backtrack(const NewtonIteration& it, const Eigen::VectorXd& p,
                 double slope, NewtonStepOutcome* outcome) const {
    const NewtonSettings& settings = *it.settings;
    const NewtonResidual& current = *it.current;
    const double merit = it.merit;
    for (int halving = 0; halving <= settings.max_halvings; ++halving) {
      const double t = std::ldexp(1.0, -halving);
      it.problem->SetTrial(t * p);
      double trial_merit = 0;
      bool decrease = false;
      bool round_off = true;  // root finding: no merit gate
      if (minimize_) {
        if (it.problem->Merit(NewtonPoint::kTrial, &trial_merit) !=
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
      if (it.problem->Residual(NewtonPoint::kTrial, &trial) !=
          EvaluationStatus::kOk) {
        continue;
      }
      const bool smaller_max = settings.accept_smaller_max_norm && round_off &&
                               trial.max_norm < current.max_norm;
      const bool smaller_two = settings.accept_smaller_two_norm &&
                               trial.two_norm < current.two_norm;
      const bool reduced_max =
          settings.accept_max_norm_reduction > 0 &&
          trial.max_norm <=
              settings.accept_max_norm_reduction * current.max_norm;
      if (!decrease && !smaller_max && !smaller_two && !reduced_max) continue;
      outcome->accepted = true;
      outcome->residual = std::move(trial);
      outcome->merit = trial_merit;
      outcome->shifted = shift_ > 0;
      return;
    }
  }

  const bool minimize_;
  double shift_ = 0;  // lambda of the last accepted step's H + lambda I
};

}  // namespace

std::unique_ptr<NewtonStepStrategy> MakeLineSearchStrategy(
    const NewtonSettings& settings) {
  return std::make_unique<LineSearchStrategy>(settings);
}

}  // namespace shellspace
