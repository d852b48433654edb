#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/problems/splines/spline.h"

#include <ceres/gradient_problem.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "shellspace/runtime/blas_threads.h"
#include "shellspace/problems/splines/spline_preconditioner.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {
namespace {

void CheckIndices(const std::vector<int>& at, size_t count, int steps,
                  bool periodic, bool need_ends) {
  if (at.size() != count) {
    throw InputError("spline: need one time index per shape: " +
                     std::to_string(at.size()) + " indices for " +
                     std::to_string(count) + " shapes");
  }
  if (count < 2) throw InputError("need at least two keyframes / inputs");
  for (size_t i = 0; i < at.size(); ++i) {
    const int limit = periodic ? steps - 1 : steps;
    if (at[i] < 0 || at[i] > limit) {
      throw InputError("index " + std::to_string(at[i]) + " outside [0, " +
                       std::to_string(limit) + "]");
    }
    if (i > 0 && at[i] <= at[i - 1]) {
      throw InputError("spline: the time indices must be strictly increasing");
    }
  }
  if (need_ends && !periodic && (at.front() != 0 || at.back() != steps)) {
    throw InputError("a spline needs keyframes at 0 and at K = " +
                     std::to_string(steps));
  }
}

double MaxNorm(const std::vector<double>& v) {
  double norm = 0;
  for (double g : v) norm = std::max(norm, std::abs(g));
  return norm;
}

// L-BFGS works on y with x = x0 + T y (SplinePreconditioner; T = I
// without preconditioning), on the objective divided by a constant `scale`
// (see Run). Every gradient evaluation also records the gradient's max norm
// in the reference variables (the first round's T0 and scale0), under the
// objective value L-BFGS sees, for RoundCallback to look up.
class PreconditionedObjective : public ceres::FirstOrderFunction {
 public:
  struct Record {
    double cost;                // as returned to L-BFGS
    double reference_gradient;  // max |T0^T g_x| / scale0
    double move;                // max |x - x0| (the round's start)
  };
  PreconditionedObjective(const SplineObjective& inner,
                          const SplinePreconditioner* preconditioner,
                          std::vector<double> x0)
      : inner_(inner), preconditioner_(preconditioner), x0_(std::move(x0)) {}
  int NumParameters() const override { return inner_.NumParameters(); }
  bool Evaluate(const double* y, double* cost,
                double* gradient) const override {
    const std::vector<double> x = ToX(y);
    std::vector<double> gx(gradient ? x.size() : 0);
    if (!inner_.Evaluate(x.data(), cost, gradient ? gx.data() : nullptr)) {
      return false;
    }
    *cost *= inverse_scale_;
    if (gradient) {
      Transpose(preconditioner_, gx, gradient);
      for (int i = 0; i < NumParameters(); ++i) gradient[i] *= inverse_scale_;
      std::vector<double> reference(gx.size());
      Transpose(reference_, gx, reference.data());
      double move = 0;
      for (size_t i = 0; i < x.size(); ++i) {
        move = std::max(move, std::abs(x[i] - x0_[i]));
      }
      records_.push_back(
          {*cost, MaxNorm(reference) * reference_inverse_scale_, move});
    }
    return true;
  }
  std::vector<double> ToX(const double* y) const {
    std::vector<double> x(x0_.size());
    if (preconditioner_) {
      preconditioner_->Apply(y, x.data());
    } else {
      std::copy(y, y + x.size(), x.begin());
    }
    for (size_t i = 0; i < x.size(); ++i) x[i] += x0_[i];
    return x;
  }
  void set_scale(double scale) { inverse_scale_ = 1.0 / scale; }
  void set_reference(const SplinePreconditioner* reference, double scale) {
    reference_ = reference;
    reference_inverse_scale_ = 1.0 / scale;
  }
  // The reference gradient recorded with objective value `cost` (the latest
  // such record), NaN if none.
  const Record* RecordAt(double cost) const {
    for (auto r = records_.rbegin(); r != records_.rend(); ++r) {
      if (r->cost == cost) return &*r;
    }
    return nullptr;
  }

 private:
  static void Transpose(const SplinePreconditioner* t,
                        const std::vector<double>& gx, double* gy) {
    if (t) {
      t->ApplyTransposed(gx.data(), gy);
    } else {
      std::copy(gx.begin(), gx.end(), gy);
    }
  }
  const SplineObjective& inner_;
  const SplinePreconditioner* preconditioner_;
  std::vector<double> x0_;
  double inverse_scale_ = 1.0;
  const SplinePreconditioner* reference_ = nullptr;
  double reference_inverse_scale_ = 1.0;
  mutable std::vector<Record> records_;
};

// Per iteration of a round: the accepted iterate's reference gradient; ends
// the run once it is at most `target`; progress lines numbered over all
// rounds (a later round's iteration 0 repeats the previous round's last
// iterate and is not printed).
class RoundCallback : public ceres::IterationCallback {
 public:
  using Clock = std::chrono::steady_clock;
  RoundCallback(const PreconditionedObjective& objective, double target,
                int refresh_iterations, double refresh_move,
                int first_iteration, double cost_factor,
                const std::string* label, Clock::time_point start,
                double* last_gradient, bool* met, bool* refresh)
      : objective_(objective), target_(target),
        refresh_iterations_(refresh_iterations), refresh_move_(refresh_move),
        first_(first_iteration), cost_factor_(cost_factor), label_(label),
        start_(start), last_gradient_(last_gradient), met_(met),
        refresh_(refresh) {}
  ceres::CallbackReturnType operator()(
      const ceres::IterationSummary& s) override {
    const auto* record = objective_.RecordAt(s.cost);
    const double g = record ? record->reference_gradient : NAN;
    if (std::isfinite(g)) *last_gradient_ = g;
    if (label_ && (first_ == 0 || s.iteration > 0)) {
      PrintProgressLine(
          *label_, first_ + s.iteration, cost_factor_ * s.cost,
          *last_gradient_, s.step_is_successful,
          std::chrono::duration<double>(Clock::now() - start_).count());
    }
    if (std::isfinite(g) && g <= target_) {
      *met_ = true;
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    if (refresh_iterations_ > 0 && s.iteration >= refresh_iterations_ &&
        record && record->move > refresh_move_) {
      *refresh_ = true;  // the metrics are stale: a new round
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const PreconditionedObjective& objective_;
  double target_;
  int refresh_iterations_;
  double refresh_move_;  // absolute
  int first_;
  double cost_factor_;
  const std::string* label_;
  Clock::time_point start_;  // of the run
  double* last_gradient_;
  bool* met_;
  bool* refresh_;
};

// The result of a run stopped before (or during) its first evaluation: the
// start, unevaluated. That evaluation solves every midpoint from its linear
// guess (20 s on cactus 2, 10, 17 at 5.3k vertices), too long to keep a stop
// request waiting.
SplineResult UnevaluatedStart(const SplineObjective& objective,
                              const std::vector<double>& x,
                              const SplineSpec& spec) {
  SplineResult result;
  result.path = objective.PathFrom(x.data());
  result.evaluated = false;
  result.spline_energy = result.data_energy = result.objective =
      std::numeric_limits<double>::quiet_NaN();
  result.summary.termination_type = ceres::USER_SUCCESS;
  result.summary.message = "stopped before the first evaluation finished";
  if (spec.periodic) result.path.push_back(result.path.front());
  return result;
}

// What the rounds of a run carry over: the reference variables (the first
// round's preconditioner and scale), the gradient target in them, and
// whether RoundCallback found it met.
struct RoundState {
  std::unique_ptr<SplinePreconditioner> reference;  // the first round's
  double reference_scale = 1, target = 0;
  bool met = false;
};

// How a round of Run ended.
enum class RoundEnd {
  kStopped,  // a stop request during the first evaluation
  kDone,     // L-BFGS ended: no further round
  kRefresh,  // RoundCallback found the metrics stale: a new round
};

// The preconditioner of a round at the metrics of spec.initial; null
// without preconditioning.
std::unique_ptr<SplinePreconditioner> RoundPreconditioner(
    const ShellSpace& space, const SplineSpec& spec,
    const SplineSettings& settings) {
  std::unique_ptr<SplinePreconditioner> preconditioner;
  if (settings.precondition) {
    preconditioner = std::make_unique<SplinePreconditioner>(
        space, spec, settings.preconditioner_regularization,
        settings.inner.num_threads);
  }
  return preconditioner;
}

// The divisor of a round's objective (see Run) from its gradient in y at
// the round's start x0: the trial step -gradient, mapped to x, is to move
// no coordinate by more than max_move (with preconditioning, a shorter
// step is left as is). Negates *gradient.
double RoundScale(const PreconditionedObjective& scaled,
                  const std::vector<double>& x0, bool preconditioned,
                  double max_move, std::vector<double>* gradient) {
  for (double& g : *gradient) g = -g;
  std::vector<double> first_move = scaled.ToX(gradient->data());
  for (size_t i = 0; i < x0.size(); ++i) first_move[i] -= x0[i];
  const double move = MaxNorm(first_move) / max_move;
  return std::max(preconditioned ? std::max(move, 1.0) : move, 1e-300);
}

// Ceres' L-BFGS options of a round with `iterations` of the run done (the
// callbacks are the round's).
ceres::GradientProblemSolver::Options RoundOptions(
    const SplineSettings& settings, int iterations) {
  ceres::GradientProblemSolver::Options options;
  options.line_search_direction_type = ceres::LBFGS;
  options.max_num_iterations = settings.max_iterations - iterations;
  options.gradient_tolerance = 0;  // RoundCallback stops on the target
  options.function_tolerance = settings.function_tolerance;
  options.logging_type = ceres::SILENT;
  return options;
}

// One round of Run from the free shapes *x (moved to the round's end): the
// metrics and preconditioner at *x, the scale, and L-BFGS until the target,
// a refresh or the end. `size` is the first shape's bounding-box diagonal,
// `start` the run's start.
RoundEnd RunRound(const ShellSpace& space, const SplineSettings& settings,
                  double size, RoundCallback::Clock::time_point start,
                  SplineSpec* spec, SplineObjective* objective,
                  std::vector<double>* x, RoundState* state,
                  SplineResult* result) {
  const std::vector<double> x0 = *x;
  if (result->rounds > 0) {  // the metrics at the current free shapes
    const ShellPath now = objective->PathFrom(x0.data());
    for (size_t k = 0; k < now.size(); ++k) spec->initial[k] = now[k];
  }
  std::unique_ptr<SplinePreconditioner> preconditioner =
      RoundPreconditioner(space, *spec, settings);
  // The problem owns the function; `scaled` stays valid while it lives.
  auto* function =
      new PreconditionedObjective(*objective, preconditioner.get(), x0);
  ceres::GradientProblem problem(function);
  PreconditionedObjective& scaled = *function;
  scaled.set_reference(
      result->rounds == 0 ? preconditioner.get() : state->reference.get(),
      state->reference_scale);
  std::vector<double> y(x0.size(), 0.0), gradient(x0.size());
  double cost = 0;
  // The first evaluation solves the midpoints from scratch: a stop
  // request may end it (and the run) early; later ones stay exact.
  if (result->rounds == 0) objective->set_cold_start_stop(settings.stop);
  const bool evaluated = scaled.Evaluate(y.data(), &cost, gradient.data());
  objective->set_cold_start_stop(StopToken());
  if (objective->stopped()) return RoundEnd::kStopped;
  if (!evaluated) {
    throw InputError("the initial path has degenerate shapes or midpoints");
  }
  const double norm = MaxNorm(gradient);
  const double scale = RoundScale(scaled, x0, preconditioner != nullptr,
                                  settings.max_first_move * size, &gradient);
  scaled.set_scale(scale);
  if (result->rounds == 0) {
    state->reference_scale = scale;
    scaled.set_reference(preconditioner.get(), scale);
    result->initial_gradient_norm = result->final_gradient_norm = norm / scale;
    // The relative criterion, with an absolute floor: a start at a
    // stationary point (constant keyframes: initial gradient 0) has met
    // it, however the round-off of later evaluations moves the gradient.
    state->target =
        std::max(settings.gradient_tolerance * norm, kAbsoluteGradientFloor) /
        scale;
  }
  ceres::GradientProblemSolver::Options options =
      RoundOptions(settings, result->iterations);
  bool refresh = false;
  RoundCallback round(scaled, state->target, settings.preconditioner_refresh,
                      settings.refresh_move * size, result->iterations, scale,
                      settings.progress ? &settings.progress_label : nullptr,
                      start, &result->final_gradient_norm, &state->met,
                      &refresh);
  options.callbacks.push_back(&round);
  StopCallback stop(settings.stop);
  if (settings.stop.stop_possible()) options.callbacks.push_back(&stop);
  ceres::Solve(options, problem, y.data(), &result->summary);
  *x = scaled.ToX(y.data());
  if (preconditioner && result->rounds == 0) {
    state->reference = std::move(preconditioner);
  }
  ++result->rounds;
  result->iterations +=
      std::max(0, static_cast<int>(result->summary.iterations.size()) - 1);
  return refresh ? RoundEnd::kRefresh : RoundEnd::kDone;
}

// The run's convergence verdict in *result, at the free shapes x (empty:
// none, converged).
void SetConvergence(const std::vector<double>& x, const RoundState& state,
                    SplineResult* result) {
  // RoundCallback's stop: what Ceres' own tolerance would say.
  if (state.met) {
    result->summary.termination_type = ceres::CONVERGENCE;
    result->summary.message =
        "Gradient tolerance reached (in the first round's variables).";
  }
  if (x.empty()) {  // no free shapes
    result->gradient_criterion_met = result->converged = true;
  } else {
    result->relative_gradient_norm =
        result->initial_gradient_norm > 0
            ? result->final_gradient_norm / result->initial_gradient_norm
            : 0.0;
    result->gradient_criterion_met =
        result->final_gradient_norm <= state.target ||
        result->final_gradient_norm * state.reference_scale <=
            kAbsoluteGradientFloor;
    result->converged = result->gradient_criterion_met ||
                        result->summary.termination_type == ceres::CONVERGENCE;
  }
}

// The final path at the free shapes x, its energies and the timings in
// *result (a periodic path closed by repeating its first shape).
void SetFinalPath(const ShellSpace& space, const SplineSpec& spec,
                  const SplineObjective& objective,
                  const std::vector<double>& x, SplineResult* result) {
  result->path = objective.PathFrom(x.data());
  result->spline_energy = objective.SplineEnergyOf(result->path);
  for (const SplineDatum& d : spec.data) {
    result->data_energy +=
        EvaluateDeformationEnergy(space, d.shape, result->path[d.index]).total;
  }
  result->objective = result->data_energy + spec.sigma * result->spline_energy;
  result->timings = objective.timings();
  if (spec.periodic) result->path.push_back(result->path.front());
}

// One round's first L-BFGS trial step is -gradient in y. The objective is
// divided by `scale` so that this step moves no vertex by more than
// `max_first_move` of the shape's size (a crumpled trial shape fails to
// evaluate and ends the line search): with preconditioning scale = 1 unless
// the model step is larger (the model Hessian is the identity, so the unit
// step is the model's Newton step); without, the gradient step is scaled to
// max_first_move. Rounds: SplineSettings::preconditioner_refresh and
// refresh_move.
SplineResult Run(const ShellSpace& space, SplineSpec spec,
                 const SplineSettings& settings) {
  // One BLAS thread: the midpoint solves factorise many small systems, where
  // a second OpenBLAS thread mostly spins. The cactus regression (0, 3, ...,
  // 18, K = 6, 60 s limit, 4 L-BFGS iterations either way) took 92.4 s wall
  // / 93.9 user + 76.4 sys with 2 threads, 79.0 s / 82.8 + 18.9 with 1.
  const ScopedBlasThreads blas(1);
  SplineObjective objective(space, spec, settings.inner);
  std::vector<double> x = objective.InitialParameters();
  SplineResult result;
  if (!x.empty() && settings.stop.stop_requested()) {
    return UnevaluatedStart(objective, x, spec);
  }
  RoundState state;
  const Positions& first_shape = spec.initial.front();
  const double size =
      (first_shape.colwise().maxCoeff() - first_shape.colwise().minCoeff())
          .norm();
  const auto start = RoundCallback::Clock::now();
  while (!x.empty()) {
    const RoundEnd end = RunRound(space, settings, size, start, &spec,
                                  &objective, &x, &state, &result);
    if (end == RoundEnd::kStopped) return UnevaluatedStart(objective, x, spec);
    if (end != RoundEnd::kRefresh ||
        result.iterations >= settings.max_iterations) {
      break;
    }
  }
  SetConvergence(x, state, &result);
  SetFinalPath(space, spec, objective, x, &result);
  return result;
}

}  // namespace

ShellPath PiecewiseLinearPath(const std::vector<Positions>& shapes,
                              const std::vector<int>& at, int steps,
                              bool periodic) {
  const int count = periodic ? steps : steps + 1;
  ShellPath path(count);
  const int n = static_cast<int>(at.size());
  for (int k = 0; k < count; ++k) {
    // The keyframe interval [at[i], at[i+1]] holding k.
    int i = 0;
    while (i + 1 < n && at[i + 1] <= k) ++i;
    if (periodic && (k < at.front() || k > at.back())) {
      const int from = at.back(), to = at.front() + steps;
      const int kk = k < at.front() ? k + steps : k;
      const double t = static_cast<double>(kk - from) / (to - from);
      path[k] = (1 - t) * shapes.back() + t * shapes.front();
    } else if (k <= at.front()) {
      path[k] = shapes.front();
    } else if (k >= at.back()) {
      path[k] = shapes.back();
    } else {
      const double t = static_cast<double>(k - at[i]) / (at[i + 1] - at[i]);
      path[k] = (1 - t) * shapes[i] + t * shapes[i + 1];
    }
  }
  return path;
}

void CheckSplineKeyframes(size_t count, const std::vector<int>& at, int steps,
                          bool periodic) {
  if (steps < 2) {
    throw InputError("spline: the number of steps K must be at least 2, got " +
                     std::to_string(steps));
  }
  CheckIndices(at, count, steps, periodic, true);
}

SplineResult SolveSpline(const ShellSpace& space,
                         const std::vector<Positions>& keyframes,
                         const std::vector<int>& at, int steps, bool periodic,
                         const ShellPath& initial,
                         const SplineSettings& settings) {
  CheckSplineKeyframes(keyframes.size(), at, steps, periodic);
  SplineSpec spec;
  spec.steps = steps;
  spec.periodic = periodic;
  spec.initial = initial.empty()
                     ? PiecewiseLinearPath(keyframes, at, steps, periodic)
                     : initial;
  if (periodic && static_cast<int>(spec.initial.size()) == steps + 1) {
    spec.initial.pop_back();
  }
  spec.is_free.assign(spec.initial.size(), 1);
  for (size_t i = 0; i < at.size(); ++i) {
    spec.initial[at[i]] = keyframes[i];
    spec.is_free[at[i]] = 0;
  }
  return Run(space, spec, settings);
}

SplineResult SolveRegression(const ShellSpace& space,
                             const std::vector<Positions>& inputs,
                             const std::vector<int>& at, int steps,
                             double sigma, const ShellPath& initial,
                             const SplineSettings& settings) {
  if (steps < 2) {
    throw InputError("spline: the number of steps K must be at least 2, got " +
                     std::to_string(steps));
  }
  if (!(sigma >= 0) || !std::isfinite(sigma)) {
    throw InputError(
        "regression: the weight sigma of the spline energy must be a "
        "non-negative number");
  }
  CheckIndices(at, inputs.size(), steps, false, false);
  SplineSpec spec;
  spec.steps = steps;
  spec.sigma = sigma;
  spec.initial =
      initial.empty() ? PiecewiseLinearPath(inputs, at, steps, false) : initial;
  spec.is_free.assign(spec.initial.size(), 1);
  for (size_t i = 0; i < at.size(); ++i)
    spec.data.push_back({inputs[i], at[i]});
  return Run(space, spec, settings);
}

}  // namespace shellspace
