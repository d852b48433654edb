// Shell PCA (docs/math.md, "Elastic mean and shell PCA"): principal modes of a
// set of shells at their elastic mean in the Hessian metric
//   g(u, w) = 1/2 u^T D_2^2 W[s_bar, s_bar] w,
// with displacements v_i = LOG_K(s_bar -> S_i) (or, cheaply, S_i - s_bar
// after rigid alignment), Gram matrix Gamma_ij = g(v_i, v_j) / n, eigenpairs
// lambda_1 >= lambda_2 >= ... and modes w_j = sum_i a^j_i v_i / sqrt(n
// lambda_j), so that g(w_j, w_k) = delta_jk. Mode shapes and reconstructions
// are EXP_K shots from s_bar.
#ifndef SHELLSPACE_PROBLEMS_STATISTICS_SHELL_PCA_H_
#define SHELLSPACE_PROBLEMS_STATISTICS_SHELL_PCA_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {

// The Hessian metric at a shell s: g(u, w) = 1/2 u^T H w with
// H = D_2^2 W[s, s] (= J^T J for the residual Jacobian J at (s, s), with W
// = 1/2 sum r^2 = the Ceres cost, since every residual vanishes at rest).
// Positive semi-definite with the 6 rigid motions (infinitesimal) in its
// kernel.
class ShellMetric {
 public:
  ShellMetric(const ShellSpace& space, const Positions& at);

  // g(u, w) = 1/2 u^T H w for variations u, w (vertex-major, like Positions).
  double Inner(const Positions& u, const Positions& w) const;
  // sqrt(g(u, u)).
  double Norm(const Positions& u) const;
  const Eigen::SparseMatrix<double>& hessian() const { return hessian_; }

 private:
  Eigen::SparseMatrix<double> hessian_;
};

// The Gram matrix Gamma_ij = g(v_i, v_j) / n of n displacements in the
// metric g (Gamma = V^T H V / (2 n) with the v_i as the columns of V).
Eigen::MatrixXd ShellGram(const ShellMetric& metric,
                          const std::vector<Positions>& displacements);

// Eigen-decomposition of a Gram matrix Gamma_ij = <v_i, v_j> / n of n
// displacements in some inner product: eigenvalues lambda_1 >= ... >=
// lambda_n (all n, unclipped), and the modes w_j = sum_i a^j_i v_i /
// sqrt(n lambda_j) (unit length in that inner product) for the leading
// lambda_j > relative_cutoff * max(lambda_1, 0).
struct GramModes {
  Eigen::VectorXd eigenvalues;
  std::vector<Positions> modes;
};
GramModes ModesFromGram(const Eigen::MatrixXd& gram,
                        const std::vector<Positions>& displacements,
                        double relative_cutoff = 1e-10);

// How the displacement of S_i from s_bar is measured.
enum class DisplacementKind {
  kLog,               // v_i = LOG_K(s_bar -> A(S_i))
  kAlignedDifference  // v_i = A(S_i) - s_bar (the cheap option)
};
// A = AlignRigidly(., s_bar) (unweighted Kabsch) in both cases (W and LOG
// do not depend on it; it only gives LOG_K's linear initial path a good
// start).

// Throws InputError unless `modes` <= inputs - 1 (n shapes have at most
// n - 1 modes) and, with `leave_one_out`, modes <= inputs - 2 (each fold
// has one input less). The messages name the two options as the caller
// knows them: `modes_name` and `leave_one_out_name` ("--modes" and "--loo"
// for the CLI's flags, "modes" and "loo" for the Python arguments).
void CheckPcaModeCount(int modes, int inputs, bool leave_one_out,
                       const std::string& modes_name,
                       const std::string& leave_one_out_name);

struct ShellPcaOptions {
  DisplacementKind displacement = DisplacementKind::kLog;
  int steps = 2;  // K of LOG_K (>= 1)
  // K of EXP_K for mode shapes and reconstructions; 0: the same K as LOG_K
  // (then EXP_K(LOG_K(S)) = S exactly). See ShootFromMean for the safeguard.
  int exp_steps = 0;
  int max_exp_steps = 16;          // the safeguard doubles K up to this
  double max_energy_drift = 0.5;   // allowed |W_k - W_1| / W_1 along EXP_K
  double relative_cutoff = 1e-10;  // of ModesFromGram
};

// DisplacementKind of "log" (kLog) or "difference" (kAlignedDifference).
// Throws InputError starting with `name` (the caller's name of the option:
// "--displacement" for the CLI, "displacement" for Python) otherwise.
DisplacementKind ParseDisplacementKind(const std::string& value,
                                       const std::string& name);
// "log" or "difference": the word ParseDisplacementKind reads.
const char* DisplacementKindName(DisplacementKind kind);

// The options of the front ends' values (the others keep their defaults):
// log_steps (steps), exp_steps, max_exp_steps and the displacement. The
// step counts are checked by the functions that take the options.
ShellPcaOptions MakeShellPcaOptions(int log_steps, int exp_steps,
                                    int max_exp_steps,
                                    DisplacementKind displacement);

// How an EXP shot went: the K of the last attempt, the number of attempts,
// the largest relative step-energy drift max_k |W[s_{k-1}, s_k] - W[s_0,
// s_1]| / W[s_0, s_1] of the last attempt (+inf if one of its steps had no
// solution), and whether it passed the safeguard.
struct ExpShotReport {
  int steps = 0;
  int attempts = 0;
  double energy_drift = 0;
  bool ok = false;
  // Empty, or why the last attempt returned no shape: the step without a
  // solution or the degenerate element it met (TryShootFromMean false).
  std::string failure;
};

// EXP_K(s_bar, v) with a safeguard against the instability of shooting a
// large variation in few steps (s_1 = s_bar + v/K is a linear step: for a
// large v/K it shortens rotating parts and the forward steps amplify the
// error into rough surfaces or an LM failure, "Matrix not positive
// definite"). A discrete geodesic keeps its step energies W[s_{k-1}, s_k]
// nearly constant (the discrete energy conservation), so a shot is accepted
// if every step is solved (ExpStep's Newton converged, or its LM fallback,
// capped at 25 iterations, converged or reached a residual |F|_inf <= 1e-6
// |D_2 W[s_{k-1}, s_k]|_inf) and max_k |W_k - W_1| <= max_energy_drift *
// W_1. Otherwise K is doubled (K = exp_steps, 2 K, 4 K, ... <=
// max_exp_steps; exp_steps = 0 means `steps`) and the shot repeated. A shot
// stops at its first unsolved step. The last shot is returned if it solved
// every step, even if it fails the drift bound (report->ok = false); if it
// has an unsolved step (no EXP solution near the extrapolation: e.g. a
// variation that folds a patch of the mesh) or meets a degenerate triangle,
// the shot failed: a numerical status, false with report->failure naming the
// step, *shot untouched, and *report saying what was tried. Throws
// InputError only for invalid options.
bool TryShootFromMean(const ShellSpace& space, const Positions& mean,
                      const Positions& variation,
                      const ShellPcaOptions& options,
                      const SolverSettings& settings, Positions* shot,
                      ExpShotReport* report = nullptr);

// The same for a shot that must succeed (a mode shape the caller asked
// for): throws InputError with report->failure if it failed.
Positions ShootFromMean(const ShellSpace& space, const Positions& mean,
                        const Positions& variation,
                        const ShellPcaOptions& options,
                        const SolverSettings& settings,
                        ExpShotReport* report = nullptr);

struct ShellPcaModel {
  Positions mean;                        // s_bar
  std::vector<Positions> displacements;  // v_i
  Eigen::MatrixXd gram;                  // Gamma_ij = g(v_i, v_j) / n
  Eigen::VectorXd eigenvalues;           // lambda_1 >= ... >= lambda_n
  std::vector<Positions> modes;          // w_j, g(w_j, w_k) = delta_jk
  ShellMetric metric;
  // kLog: the LOG_K geodesics (s_bar, ..., A(S_i)) behind v_i, and the LM
  // iterations + Newton steps of their solves.
  std::vector<ShellPath> log_paths;
  int log_iterations = 0;
};

// The initial guess of a LOG_K geodesic from `mean` to `end` made from a
// geodesic `old` (K + 1 shapes) between nearby ends, e.g. from the mean of a
// superset of the shapes: with t = k/K, L_k = (1 - t) mean + t end and A_k
// the rigid alignment to L_k,
//   s_k = A_k(old_k) + (1 - t) (mean - A_0(old_0)) + t (end - A_K(old_K)),
// so s_0 = mean, s_K = end, and in between it bends like `old` (a linear
// path would start LM from scratch: on the cactus 7-9 s per LOG_2, 26 s and
// not converged in 30 iterations for cactus8's).
ShellPath WarmLogPath(const ShellPath& old, const Positions& mean,
                      const Positions& end);

// The displacement of `shape` from `mean` (ShellPcaOptions::displacement).
// kLog: LOG_K(mean -> A(shape)), its geodesic solve in *geodesic if given,
// solved from WarmLogPath(*warm, ...) if `warm` is given (else from the
// linear path).
Positions ShellDisplacement(const ShellSpace& space, const Positions& mean,
                            const Positions& shape,
                            const ShellPcaOptions& options,
                            const SolverSettings& settings,
                            const ShellPath* warm = nullptr,
                            GeodesicResult* geodesic = nullptr);

// Shell PCA of `shapes` at `mean` (usually their elastic mean); `warm`
// (optional, kLog): one LOG_K path per shape to start its LOG from (see
// ShellDisplacement), e.g. ShellPcaModel::log_paths of a model at a nearby
// mean. Throws InputError on inconsistent inputs or options.
ShellPcaModel ComputeShellPca(const ShellSpace& space, const Positions& mean,
                              const std::vector<Positions>& shapes,
                              const ShellPcaOptions& options,
                              const SolverSettings& settings,
                              const std::vector<ShellPath>* warm = nullptr);

// The shape of mode j (0-based) at amplitude t: EXP_K(s_bar, t sqrt(lambda_j)
// w_j) by TryShootFromMean, aligned rigidly to s_bar; false
// (report->failure) if the shot failed. Throws InputError for a mode the
// model does not have.
bool TryShellModeShape(const ShellSpace& space, const ShellPcaModel& model,
                       int j, double t, const ShellPcaOptions& options,
                       const SolverSettings& settings, Positions* shape,
                       ExpShotReport* report = nullptr);

// The same; throws InputError with the failure if the shot failed.
Positions ShellModeShape(const ShellSpace& space, const ShellPcaModel& model,
                         int j, double t, const ShellPcaOptions& options,
                         const SolverSettings& settings);

// Coefficients c_j = g(v, w_j), j < m, of a displacement v: the g-orthogonal
// projection of v onto the span of the first m modes is sum_j c_j w_j.
Eigen::VectorXd ShellModeCoefficients(const ShellPcaModel& model,
                                      const Positions& v, int m);

// EXP_K(s_bar, sum_{j<m} c_j w_j) by TryShootFromMean for the first m =
// coefficients.size() modes (s_bar itself for m = 0), aligned rigidly to
// s_bar; false (report->failure) if the shot failed.
bool TryShellFromCoefficients(const ShellSpace& space,
                              const ShellPcaModel& model,
                              const Eigen::VectorXd& coefficients,
                              const ShellPcaOptions& options,
                              const SolverSettings& settings, Positions* shell,
                              ExpShotReport* report = nullptr);

// The same; throws InputError with report->failure if the shot failed.
Positions ShellFromCoefficients(const ShellSpace& space,
                                const ShellPcaModel& model,
                                const Eigen::VectorXd& coefficients,
                                const ShellPcaOptions& options,
                                const SolverSettings& settings,
                                ExpShotReport* report = nullptr);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_STATISTICS_SHELL_PCA_H_
