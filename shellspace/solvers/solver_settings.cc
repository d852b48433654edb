#include "shellspace/solvers/solver_settings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"  // InputError

namespace shellspace {

SolverSettings UserSolverSettings(double tolerance, int max_iterations,
                                  int threads, bool quiet,
                                  const std::string& label) {
  if (!(tolerance > 0 && tolerance < 1)) {
    throw InputError("tolerance must be in (0, 1), got " +
                     std::to_string(tolerance));
  }
  if (max_iterations < 1) {
    throw InputError("max_iterations must be >= 1, got " +
                     std::to_string(max_iterations));
  }
  if (threads < 1 || threads > kMaxSolverThreads) {
    throw InputError("threads must be in [1, " +
                     std::to_string(kMaxSolverThreads) + "], got " +
                     std::to_string(threads));
  }
  SolverSettings settings;
  settings.gradient_tolerance = tolerance;
  settings.max_iterations = max_iterations;
  settings.num_threads = threads;
  settings.progress = !quiet;
  settings.progress_label = label;
  return settings;
}

ceres::Solver::Options MakeSolverOptions(const SolverSettings& settings,
                                         double initial_gradient_norm) {
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type =
      settings.linear_solver == SolverSettings::LinearSolver::kDenseQr
          ? ceres::DENSE_QR
          : ceres::SPARSE_NORMAL_CHOLESKY;
  options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  options.max_num_iterations = settings.max_iterations;
  options.function_tolerance = settings.function_tolerance;
  options.gradient_tolerance =
      settings.gradient_tolerance * std::max(1.0, initial_gradient_norm);
  options.parameter_tolerance = settings.parameter_tolerance;
  options.num_threads = settings.num_threads;
  options.initial_trust_region_radius = settings.initial_trust_region_radius;
  options.max_trust_region_radius = std::max(
      options.max_trust_region_radius, settings.initial_trust_region_radius);
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  return options;
}

ProgressPrinter::ProgressPrinter(std::string label, double cost_factor)
    : label_(std::move(label)),
      cost_factor_(cost_factor),
      start_(std::chrono::steady_clock::now()) {}

void PrintProgressLine(const std::string& label, int iteration, double energy,
                       double gradient, bool step_ok, double seconds) {
  std::fprintf(stderr,
               "%s iter %3d  energy %.10e  |grad| %.3e  step %s  %.2f s\n",
               label.c_str(), iteration, energy, gradient,
               step_ok ? "ok " : "rej", seconds);
}

ceres::CallbackReturnType ProgressPrinter::operator()(
    const ceres::IterationSummary& s) {
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_)
          .count();
  PrintProgressLine(label_, s.iteration, cost_factor_ * s.cost,
                    s.gradient_max_norm, s.step_is_successful, seconds);
  return ceres::SOLVER_CONTINUE;
}

}  // namespace shellspace

namespace shellspace {

double GradientMaxNorm(ceres::Problem* problem) {
  std::vector<double> gradient;
  double cost = 0;
  if (!problem->Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr,
                         &gradient, nullptr)) {
    return 0;
  }
  double norm = 0;
  for (double g : gradient) norm = std::max(norm, std::abs(g));
  return norm;
}

bool StoppedByRequest(const ceres::Solver::Summary& summary) {
  return summary.termination_type == ceres::USER_SUCCESS;
}

ceres::CallbackReturnType StopCallback::operator()(
    const ceres::IterationSummary&) {
  return stop_.stop_requested() ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
                                : ceres::SOLVER_CONTINUE;
}

ceres::Solver::Summary SolveWithSettings(ceres::Problem* problem,
                                         const SolverSettings& settings,
                                         double reference_gradient_norm) {
  ceres::Solver::Options options = MakeSolverOptions(
      settings, reference_gradient_norm >= 0 ? reference_gradient_norm
                                             : GradientMaxNorm(problem));
  ProgressPrinter printer(settings.progress_label);
  if (settings.progress) options.callbacks.push_back(&printer);
  StopCallback stop(settings.stop);
  if (settings.stop.stop_possible()) options.callbacks.push_back(&stop);
  ceres::Solver::Summary summary;
  ceres::Solve(options, problem, &summary);
  return summary;
}

}  // namespace shellspace
