// Solver settings shared by all problem builders, and the per-iteration
// progress line of long solves.
#ifndef SHELLSPACE_SOLVERS_SOLVER_SETTINGS_H_
#define SHELLSPACE_SOLVERS_SOLVER_SETTINGS_H_

#include <ceres/iteration_callback.h>
#include <ceres/solver.h>

#include <chrono>
#include <iosfwd>
#include <string>

#include "shellspace/runtime/stop_token.h"

namespace shellspace {

// Settings of the sparse Levenberg-Marquardt solves. Convergence is declared
// on the relative gradient norm max|grad| / max(1, |grad_0|) <=
// gradient_tolerance (a Ceres gradient_tolerance on the projected gradient
// scaled by the initial one) or on the relative cost decrease.
struct SolverSettings {
  // The linear solver of the LM steps: sparse normal equations (CHOLMOD via
  // Ceres, the shell problems) or dense QR (small problems, the branching
  // constructions).
  enum class LinearSolver { kSparseNormalCholesky, kDenseQr };
  LinearSolver linear_solver = LinearSolver::kSparseNormalCholesky;
  int max_iterations = 200;
  double function_tolerance = 1e-12;
  double gradient_tolerance = 1e-8;  // relative to the initial gradient
  double parameter_tolerance = 1e-12;
  int num_threads = 2;
  // LM's initial trust-region radius (Ceres' default 1e4). Root-finding
  // problems with a square, nonsingular Jacobian (EXP steps) want nearly
  // Gauss-Newton steps from the start: a large radius.
  double initial_trust_region_radius = 1e4;
  bool progress = false;  // one line per iteration on stderr
  std::string progress_label = "solve";
  // The caller's stop request (runtime/stop_token.h), asked between
  // iterations; copied into inner solves with the settings.
  StopToken stop;
};

// The most threads a solve accepts (num_threads).
constexpr int kMaxSolverThreads = 1024;

// The settings a front end takes from its users (the CLI's flags, the
// Python module's keywords): relative gradient tolerance, the outer
// solver's iteration cap, threads, and progress lines under `label` unless
// `quiet`; everything else default. Throws InputError unless tolerance is
// in (0, 1), max_iterations >= 1 and threads in [1, kMaxSolverThreads].
SolverSettings UserSolverSettings(double tolerance, int max_iterations,
                                  int threads, bool quiet,
                                  const std::string& label);

// A Ceres solve that a StopCallback ended (its termination USER_SUCCESS:
// the parameters hold the best iterate reached).
bool StoppedByRequest(const ceres::Solver::Summary& summary);

// Returns SOLVER_TERMINATE_SUCCESSFULLY once `stop` says stop (Ceres then
// keeps the best iterate; SOLVER_ABORT would restore the initial one).
// Added to a solve's callbacks only if stop.stop_possible().
class StopCallback : public ceres::IterationCallback {
 public:
  explicit StopCallback(StopToken stop) : stop_(std::move(stop)) {}
  ceres::CallbackReturnType operator()(
      const ceres::IterationSummary& summary) override;

 private:
  StopToken stop_;
};

// Ceres options for an LM solve (SPARSE_NORMAL_CHOLESKY over SuiteSparse,
// or DENSE_QR) with these settings: the one builder of LM options of the
// library. `initial_gradient_norm` (max norm of the gradient at the initial
// guess) turns the relative gradient tolerance into Ceres' absolute one
// gradient_tolerance * max(1, initial_gradient_norm); pass 0 for an
// absolute gradient_tolerance.
ceres::Solver::Options MakeSolverOptions(const SolverSettings& settings,
                                         double initial_gradient_norm);

// Prints one progress line on stderr,
//   "label iter N  energy E  |grad| G  step ok|rej  T s",
// the format of every iterative solve's progress (ProgressPrinter, the
// spline's L-BFGS rounds).
void PrintProgressLine(const std::string& label, int iteration, double energy,
                       double gradient, bool step_ok, double seconds);

// Prints PrintProgressLine per iteration: Ceres' iteration, energy and
// gradient max-norm, seconds since construction.
class ProgressPrinter : public ceres::IterationCallback {
 public:
  // The printed energy is cost_factor * Ceres' cost (1 for the shell
  // energies: W = 1/2 sum r^2 is Ceres' cost, and E_K with the sqrt(K)
  // residual scaling).
  explicit ProgressPrinter(std::string label, double cost_factor = 1.0);
  ceres::CallbackReturnType operator()(
      const ceres::IterationSummary& summary) override;

 private:
  std::string label_;
  double cost_factor_;
  std::chrono::steady_clock::time_point start_;
};

// Max-norm of the gradient of the problem's cost at the current parameters.
double GradientMaxNorm(ceres::Problem* problem);

// Solves `problem` with MakeSolverOptions(settings, g0) and, if
// settings.progress, a ProgressPrinter. g0 = reference_gradient_norm if it is
// >= 0 (a solve continuing an earlier one keeps that one's reference), else
// GradientMaxNorm(problem) at the initial guess.
ceres::Solver::Summary SolveWithSettings(ceres::Problem* problem,
                                         const SolverSettings& settings,
                                         double reference_gradient_norm = -1);

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_SOLVER_SETTINGS_H_
