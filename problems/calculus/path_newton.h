// Newton's method on the Euler-Lagrange equations of the path energy
// (calculus.md): the finishing stage of geodesic interpolation.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_PATH_NEWTON_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_PATH_NEWTON_H_

#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/solvers/newton_solver.h"

namespace shellspace {

using ShellPath = std::vector<Positions>;

// The linear solver of the Newton steps (H p = -G):
//  - kDirect: ReusableCholesky, a supernodal Cholesky factorisation of the
//    whole space-time H (space-time ordering), reused as a CG
//    preconditioner across steps; fill grows superlinearly with the mesh
//    (cactus x4, 21k vertices, K = 8: 8.9 GB);
//  - kBlockJacobi: BlockJacobiSolver, CG preconditioned by the Cholesky
//    factors of the K - 1 diagonal (one-shape) blocks: memory O(K x one
//    shape's factor), more iterations;
//  - kAuto: kBlockJacobi when the reduced unknowns of the whole path,
//    (K - 1) x (free coordinates per shape), reach
//    kBlockJacobiFromUnknowns, else kDirect (a size rule, no clock; see
//    ChooseLinearSolver).
enum class PathLinearSolver { kAuto, kDirect, kBlockJacobi };

// The threshold of kAuto on the reduced unknowns of the whole path.
// Measured (bench/scale_bench, cactus_ring levels:1, K = 8, 103,950
// unknowns on the fine level): the Newton finish took 73.7 s direct (one
// Cholesky 52.8 s, 1.9 s CG) against 39.0 s block-Jacobi (one block set
// 4.3 s, 22 CG iterations 6.9 s), the same E_K to 12 digits; on its coarse
// level (1,315 vertices) factorisation + CG 2.5 s against 0.6 s. The
// threshold sits just below the cactus ring; the meshes of the tests
// (plate, finger: at most 43k unknowns) stay direct, where the exact
// solves often save a Newton step.
inline constexpr int kBlockJacobiFromUnknowns = 100000;

// kDirect or kBlockJacobi for a path Hessian with `unknowns` reduced
// unknowns in all (the rule of kAuto; `choice` other than kAuto is
// returned as it is).
PathLinearSolver ChooseLinearSolver(PathLinearSolver choice, int unknowns);

// At most this many shifted Hessians H + lambda I per Newton iteration
// (NewtonSettings::max_shifts): where H is not positive definite or the
// Newton step raises E_K, the step of H + lambda I (lambda = 1e-3, 1e-2, ...
// times mean |diag H|) is tried before the polish gives up.
inline constexpr int kPathNewtonMaxShifts = 6;

struct PathNewtonSettings {
  PathLinearSolver linear_solver = PathLinearSolver::kAuto;
  int max_steps = 8;
  int max_shifts = kPathNewtonMaxShifts;  // 0: plain Newton (no H + lambda I)
  // Stop when max |G| <= gradient_tolerance (absolute, max norm over the
  // free coordinates; the same quantity as Ceres' gradient_max_norm).
  double gradient_tolerance = 0;
  // kLevenbergMarquardt: instead of the Newton iteration below, the
  // Levenberg-Marquardt iteration of the engine (NewtonSettings::
  // Globalisation) on the Gauss-Newton matrix J^T J of the residuals
  // (HessianModel::kGaussNewton) -- the model of Ceres' LM, with the same
  // linear solvers (block-Jacobi CG: memory O(K x one shape)).
  NewtonSettings::Globalisation globalisation =
      NewtonSettings::Globalisation::kLineSearch;
  int num_threads = 2;  // Hessian blocks are assembled in parallel
  bool progress = false;
  std::string progress_label = "newton";
  std::function<bool()> stop;  // NewtonSettings::stop
};

// The report of PolishPathNewton (solvers/newton_solver.h): steps, max |G|
// before / after, converged, stop reason, linear-solver work and times.
using PathNewtonReport = NewtonReport;

// Newton polish of the inner shapes s_1..s_{K-1} of `path` (K + 1 shapes,
// ends fixed) for E_K = K sum_k W[s_{k-1}, s_k]. The gradient
//   G_k = K (D_2 W[s_{k-1}, s_k] + D_1 W[s_k, s_{k+1}])
// and the exact block-tridiagonal Hessian
//   H_kk = K (D_2^2 W[s_{k-1}, s_k] + D_1^2 W[s_k, s_{k+1}]),
//   H_k,k+1 = K D_1 D_2 W[s_k, s_{k+1}]   (rows s_k, columns s_{k+1})
// are restricted to the free coordinates of each inner shape: the vertices
// not in `fixed_vertices`, or, without a mask, the 3n - 6 directions of
// RigidGaugeBasis (gauge_reduced_solve.h). H is assembled by
// PathHessianAssembler; the iteration is SolveNewton (newton_solver.h) in
// minimisation mode: each step solves H p = -G inexactly (relative
// residual min(1e-2, |G|/|G_0|), never tighter than a quarter of the
// tolerance needs) by the linear solver of settings.linear_solver
// (PathLinearSolver: ReusableCholesky -- CG preconditioned by the last
// Cholesky factor, a new factorisation only when CG stalls -- or
// BlockJacobiSolver, the slices as blocks). A step is
// accepted on sufficient decrease of E_K (Armijo, c = 1e-4) or, once E_K
// changes only at round-off level, on a smaller max |G|; halving the step
// twice at most. E_K never rises beyond round-off (1e-10 |E_K|): where H is
// not positive definite, the step is not a descent direction or no step
// length is accepted, the step of the shifted Hessian H + lambda I is tried
// (kPathNewtonMaxShifts, NewtonSettings::max_shifts).
// Gauss-Newton (Ceres' LM on the residuals) converges only linearly near a
// geodesic, whose residuals are not zero; from its result Newton converges
// quadratically. Stops (leaving the last accepted path) if even the most
// shifted H gives no accepted step, or the tolerance or max_steps is
// reached.
PathNewtonReport PolishPathNewton(const ShellSpace& space,
                                  const std::vector<int>& fixed_vertices,
                                  const PathNewtonSettings& settings,
                                  ShellPath* path);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_PATH_NEWTON_H_
