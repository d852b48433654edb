// Leave-one-out evaluation of shell PCA against Procrustes PCA (docs/math.md,
// "Elastic mean and shell PCA"): for each held-out shape S_h, build
// both models from the other shapes and reconstruct S_h from their first m
// modes.
//   shell:      s_bar = elastic mean of the others, v = LOG_K(s_bar -> S_h),
//               c_j = g(v, w_j), R = EXP_K(s_bar, sum_{j<m} c_j w_j)
//               (safeguarded shot, shell_pca.h ShootFromMean);
//   Procrustes: x_bar = Procrustes mean, x = A(S_h) aligned to x_bar,
//               R = x_bar + sum_{j<m} <x - x_bar, w_j> w_j.
// Errors of a reconstruction R of the truth T:
//   vertex error = (1/N) sum_v |A(R)_v - T_v| with A(R) = AlignRigidly(R, T),
//   energy       = W[T, R] (the truth as reference, R deformed).
#ifndef SHELLSPACE_PROBLEMS_STATISTICS_LEAVE_ONE_OUT_H_
#define SHELLSPACE_PROBLEMS_STATISTICS_LEAVE_ONE_OUT_H_

#include <functional>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/problems/statistics/shell_pca.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {

struct LeaveOneOutOptions {
  int max_modes = 5;          // m = 0 .. max_modes (m = 0: the mean)
  std::vector<int> held_out;  // folds to run (indices); empty = all
  ShellPcaOptions pca;        // displacement kind and K
  // Initial guess of every fold's elastic mean (e.g. the elastic mean of
  // all n shapes: faster, same minimiser up to solver tolerance). Empty: the
  // aligned vertex average of the fold's shapes.
  Positions initial_mean;
  // With initial_mean and LOG displacements: solve the LOG_K geodesics from
  // initial_mean to all n shapes once and start every fold's LOGs from them
  // (WarmLogPath): the folds' means are near initial_mean, so each LOG
  // needs a few iterations instead of a solve from the linear path.
  bool warm_logs = true;
  // Called with one line per finished step (fold progress), if set.
  std::function<void(const std::string&)> log;
};

// One row of the table: averages over the folds for m modes. The shell
// averages skip folds whose EXP shot failed (ExpShotReport::ok false: its
// reconstruction is not a solution of the EXP equations, and its errors
// would only measure the failure); shell_failed counts them. Procrustes
// averages are over all folds, and over the shell's folds in *_shell_folds.
struct LeaveOneOutRow {
  int modes = 0;
  int shell_failed = 0;
  double shell_vertex_error = 0;
  double shell_energy = 0;  // mean W[truth, reconstruction]
  double procrustes_vertex_error_shell_folds = 0;
  double procrustes_energy_shell_folds = 0;
  double procrustes_vertex_error = 0;
  double procrustes_energy = 0;
};

// Per fold and m: [fold][m].
struct LeaveOneOutFold {
  int held_out = 0;
  double mean_energy = 0;          // sum_{i != h} W[S_i, s_bar]
  int mean_iterations = 0;         // LM iterations of the elastic mean
  int mean_newton_iterations = 0;  // its Newton steps
  bool mean_converged = false;     // ElasticMeanResult::converged
  int log_iterations = 0;  // LM + Newton of the fold's LOG_K solves
  Eigen::VectorXd shell_eigenvalues, procrustes_eigenvalues;
  std::vector<double> shell_vertex_error, shell_energy;
  std::vector<double> procrustes_vertex_error, procrustes_energy;
  // The EXP shots of the shell reconstructions, per m (m = 0: the mean,
  // nothing shot). A shot that throws (degenerate triangle) leaves its
  // report with ok = false and the errors NaN.
  std::vector<ExpShotReport> shell_shots;
  double seconds = 0;
};

struct LeaveOneOutTable {
  std::vector<LeaveOneOutRow> rows;  // m = 0 .. max_modes
  std::vector<LeaveOneOutFold> folds;
  double seconds = 0;
};

// (1/N) sum_v |AlignRigidly(reconstruction, truth)_v - truth_v|.
double MeanVertexErrorUpToRigidMotion(const Positions& reconstruction,
                                      const Positions& truth);

// Runs the evaluation over `shapes` (n >= 3). A fold with fewer than m
// modes (n - 1 shapes give at most n - 1) reuses its last available mode
// count. Throws InputError on bad options or inputs.
LeaveOneOutTable EvaluateLeaveOneOut(const ShellSpace& space,
                                     const std::vector<Positions>& shapes,
                                     const LeaveOneOutOptions& options,
                                     const SolverSettings& settings);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_STATISTICS_LEAVE_ONE_OUT_H_
