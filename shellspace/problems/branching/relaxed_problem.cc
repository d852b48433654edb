#include "shellspace/problems/branching/relaxed_problem.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "shellspace/cost_functions/branching/double_well_cost_function.h"
#include "shellspace/cost_functions/branching/elastic_cost_function.h"
#include "shellspace/cost_functions/branching/gradient_cost_function.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace::branching {

RelaxedEnergy EvaluateRelaxedEnergy(const RelaxedField& field, double epsilon,
                                    double delta) {
  const RelaxedGrid& g = field.grid;
  const double dy = g.dy();
  RelaxedEnergy e;
  for (int i = 1; i <= g.nx; ++i) {
    const double dx = g.dx(i);
    const double wx = g.wx(i);
    for (int j = 0; j < g.ny; ++j) {
      const double ux = (field.at(i, j) - field.at(i - 1, j)) / dx;
      e.elastic += dx * dy / g.height * ux * ux;
      const double uyy = (field.at(i, (j + g.ny - 1) % g.ny) -
                          2.0 * field.at(i, j) + field.at(i, (j + 1) % g.ny)) /
                         (dy * dy);
      e.gradient += 0.75 * epsilon * delta * wx * dy / g.height * uyy * uyy;
      const double uy = field.uy(i, j);
      const double well = 1.0 - uy * uy;
      e.well += 0.75 * epsilon / delta * wx * dy / g.height * well * well;
    }
  }
  return e;
}

void AddRelaxedResiduals(RelaxedField* field, double epsilon, double delta,
                         ceres::Problem* problem) {
  const RelaxedGrid& g = field->grid;
  const double dy = g.dy();
  auto node = [&](int i, int j) { return &field->u[g.index(i, (j + g.ny) % g.ny)]; };
  for (int j = 0; j < g.ny; ++j) {
    problem->AddParameterBlock(node(0, j), 1);
    problem->SetParameterBlockConstant(node(0, j));
  }
  for (int i = 1; i <= g.nx; ++i) {
    const double dx = g.dx(i);
    const double wx = g.wx(i);
    for (int j = 0; j < g.ny; ++j) {
      problem->AddResidualBlock(ElasticCostFunction::Create(dx, dy, g.height),
                                nullptr, node(i - 1, j), node(i, j));
      problem->AddResidualBlock(
          GradientCostFunction::Create(epsilon, delta, wx, dy, g.height),
          nullptr, node(i, j - 1), node(i, j), node(i, j + 1));
      problem->AddResidualBlock(
          DoubleWellCostFunction::Create(epsilon, delta, wx, dy, g.height),
          nullptr, node(i, j), node(i, j + 1));
    }
  }
}

namespace {

class ProgressCallback : public ceres::IterationCallback {
 public:
  ProgressCallback(double delta,
                   const std::function<void(double, int, double)>& progress)
      : delta_(delta), progress_(progress) {}
  ceres::CallbackReturnType operator()(
      const ceres::IterationSummary& summary) override {
    progress_(delta_, summary.iteration, 2.0 * summary.cost);
    return ceres::SOLVER_CONTINUE;
  }

 private:
  double delta_;
  const std::function<void(double, int, double)>& progress_;
};

}  // namespace

double MaxSlope(const RelaxedField& field) {
  double m = 0.0;
  for (int i = 1; i <= field.grid.nx; ++i) {
    for (int j = 0; j < field.grid.ny; ++j) {
      m = std::max(m, std::fabs(field.uy(i, j)));
    }
  }
  return m;
}

namespace {

RelaxedStage SolveStage(RelaxedField* field, double epsilon, double delta,
                        const RelaxedSolveOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    ceres::Problem problem;
    AddRelaxedResiduals(field, epsilon, delta, &problem);
    SolverSettings settings;
    settings.max_iterations = options.max_iterations;
    settings.function_tolerance = options.function_tolerance;
    settings.gradient_tolerance = 1e-14;  // absolute (reference 0 below)
    settings.parameter_tolerance = 1e-12;
    settings.num_threads = options.num_threads;
    settings.stop = options.stop;
    ceres::Solver::Options solver =
        MakeSolverOptions(settings, /*initial_gradient_norm=*/0);
    std::unique_ptr<ProgressCallback> callback;
    if (options.progress) {
      callback = std::make_unique<ProgressCallback>(delta, options.progress);
      solver.callbacks.push_back(callback.get());
    }
    StopCallback stop(options.stop);
    if (options.stop.stop_possible()) solver.callbacks.push_back(&stop);
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    RelaxedStage stage;
    stage.delta = delta;
    stage.iterations = static_cast<int>(summary.iterations.size()) - 1;
    stage.seconds = std::chrono::duration<double>(
                        std::chrono::steady_clock::now() - start)
                        .count();
    stage.energy = EvaluateRelaxedEnergy(*field, epsilon, delta);
    stage.termination = ceres::TerminationTypeToString(summary.termination_type);
    stage.max_slope = MaxSlope(*field);
    return stage;
}

}  // namespace

std::vector<RelaxedStage> SolveRelaxed(RelaxedField* field, double epsilon,
                                       const RelaxedSolveOptions& options) {
  if (options.deltas.empty()) {
    throw InputError("branching solve: empty continuation schedule");
  }
  std::vector<RelaxedStage> stages;
  const double final_delta = options.deltas.back();
  for (double delta : options.deltas) {
    if (!(delta > 0)) throw InputError("branching solve: delta must be > 0");
    const std::vector<double> stage_start = field->u;
    bool retried = false;
    for (;;) {
      RelaxedStage stage = SolveStage(field, epsilon, delta, options);
      stage.retried = retried;
      const bool collapsed = stage.max_slope < kCollapsedSlope;
      if (collapsed && delta / 2.0 >= final_delta * (1.0 - 1e-12)) {
        field->u = stage_start;
        delta /= 2.0;
        retried = true;
        continue;
      }
      if (collapsed) stage.termination = "COLLAPSED";
      stages.push_back(stage);
      break;
    }
    if (stages.back().termination == "COLLAPSED") break;
    if (options.stop.stop_requested()) break;  // the stages done so far
  }
  return stages;
}

std::vector<double> ContinuationDeltas(double delta, int steps, double factor) {
  if (steps < 1) throw InputError("branching: continuation steps must be >= 1");
  std::vector<double> deltas;
  for (int k = steps - 1; k >= 0; --k) {
    deltas.push_back(delta * std::pow(factor, k));
  }
  return deltas;
}

}  // namespace shellspace::branching
