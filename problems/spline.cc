#include "problems/spline.h"

#include <ceres/gradient_problem.h>

#include <algorithm>
#include <cmath>

namespace shellspace {
namespace {

void CheckIndices(const std::vector<int>& at, size_t count, int steps,
                  bool periodic, bool need_ends) {
  if (at.size() != count) {
    throw InputError("--at must give one index per shape (" +
                     std::to_string(count) + ")");
  }
  if (count < 2) throw InputError("need at least two keyframes / inputs");
  for (size_t i = 0; i < at.size(); ++i) {
    const int limit = periodic ? steps - 1 : steps;
    if (at[i] < 0 || at[i] > limit) {
      throw InputError("index " + std::to_string(at[i]) + " outside [0, " +
                       std::to_string(limit) + "]");
    }
    if (i > 0 && at[i] <= at[i - 1]) {
      throw InputError("--at must be strictly increasing");
    }
  }
  if (need_ends && !periodic && (at.front() != 0 || at.back() != steps)) {
    throw InputError("a spline needs keyframes at 0 and at K = " +
                     std::to_string(steps));
  }
}

// The objective divided by a constant. L-BFGS' first trial step is the
// negative gradient itself; scaling the objective so that this step moves
// vertices by 0.1 % of the shape's size keeps it from crumpling the shapes
// (a failed evaluation would end the line search).
class ScaledObjective : public ceres::FirstOrderFunction {
 public:
  ScaledObjective(const SplineObjective& inner, double scale)
      : inner_(inner), inverse_scale_(1.0 / scale) {}
  int NumParameters() const override { return inner_.NumParameters(); }
  bool Evaluate(const double* x, double* cost,
                double* gradient) const override {
    if (!inner_.Evaluate(x, cost, gradient)) return false;
    *cost *= inverse_scale_;
    if (gradient) {
      for (int i = 0; i < NumParameters(); ++i) gradient[i] *= inverse_scale_;
    }
    return true;
  }

 private:
  const SplineObjective& inner_;
  double inverse_scale_;
};

SplineResult Run(const ShellSpace& space, SplineSpec spec,
                 const SplineSettings& settings) {
  const SplineObjective objective(space, spec, settings.inner);
  std::vector<double> x = objective.InitialParameters();
  SplineResult result;
  if (!x.empty()) {
    double cost = 0;
    std::vector<double> gradient(x.size());
    if (!objective.Evaluate(x.data(), &cost, gradient.data())) {
      throw InputError("the initial path has degenerate shapes or midpoints");
    }
    double norm = 0;
    for (double g : gradient) norm = std::max(norm, std::abs(g));
    const Positions& shape = spec.initial.front();
    const double size =
        (shape.colwise().maxCoeff() - shape.colwise().minCoeff()).norm();
    const double scale = std::max(norm / (0.001 * size), 1e-300);
    ceres::GradientProblem problem(new ScaledObjective(objective, scale));
    ceres::GradientProblemSolver::Options options;
    options.line_search_direction_type = ceres::LBFGS;
    options.max_num_iterations = settings.max_iterations;
    options.gradient_tolerance =
        settings.gradient_tolerance * std::max(norm, 1e-300) / scale;
    options.function_tolerance = settings.function_tolerance;
    options.logging_type = ceres::SILENT;
    ProgressPrinter printer(settings.progress_label, scale);
    if (settings.progress) options.callbacks.push_back(&printer);
    ceres::Solve(options, problem, x.data(), &result.summary);
  }
  result.path = objective.PathFrom(x.data());
  result.spline_energy = objective.SplineEnergyOf(result.path);
  for (const SplineDatum& d : spec.data) {
    result.data_energy +=
        EvaluateDeformationEnergy(space, d.shape, result.path[d.index]).total;
  }
  result.objective = result.data_energy + spec.sigma * result.spline_energy;
  result.timings = objective.timings();
  if (spec.periodic) result.path.push_back(result.path.front());
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

SplineResult SolveSpline(const ShellSpace& space,
                         const std::vector<Positions>& keyframes,
                         const std::vector<int>& at, int steps, bool periodic,
                         const ShellPath& initial,
                         const SplineSettings& settings) {
  if (steps < 2) throw InputError("--steps must be at least 2");
  CheckIndices(at, keyframes.size(), steps, periodic, true);
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
  if (steps < 2) throw InputError("--steps must be at least 2");
  if (!(sigma >= 0) || !std::isfinite(sigma)) {
    throw InputError("--sigma must be a non-negative number");
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
