// Newton on the Euler-Lagrange equations of E_K (docs/math.md, "Path energy
// and discrete geodesics"): the finishing stage of geodesic interpolation.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_PATH_NEWTON_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_PATH_NEWTON_H_

#include <memory>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/problems/calculus/shell_path.h"
#include "shellspace/cost_functions/shell/shell_space_renumbering.h"
#include "shellspace/solvers/newton_solver.h"

namespace shellspace {

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

// The threshold of kAuto on the reduced unknowns of the whole path; from it
// on the geodesic's LM stages also run on the engine (GeodesicLm::kAuto).
// Measured (bench/scale_bench, K = 8, levels:0, engine LM then the engine's
// trust-region Newton, 2 cores, idle): finger_ring (33k unknowns)
// block-Jacobi 6.3 s wall / 9.6 s CPU / 220 MB against direct 11.4 s /
// 21.1 s / 411 MB; cactus_ring (104k) 9.7 s / 14.9 s / 676 MB against
// 19.7 s / 35.0 s / 1.58 GB; the same E_K to 1e-9. (Ceres' LM with the
// direct Newton finish: finger_ring 94.4 s / 177 s / 441 MB.) Earlier, for
// the Newton finish alone, the cactus ring's direct factorisation took
// 52.8 s against 4.3 s for a block set. Below the threshold (the plates and
// squares of most tests) both are fast and the direct solves save
// iterations.
inline constexpr int kBlockJacobiFromUnknowns = 20000;

// kDirect or kBlockJacobi for a path Hessian with `unknowns` reduced
// unknowns in all (the rule of kAuto; `choice` other than kAuto is
// returned as it is).
PathLinearSolver ChooseLinearSolver(PathLinearSolver choice, int unknowns);

class BlockJacobiSolver;
class StiffVertexElimination;

// The block-Jacobi solver of consecutive PolishPathNewton stages on one path
// problem (the same K and free vertices; PathNewtonSettings::solvers),
// kept from one stage to the next so that a stage starts with the blocks'
// pattern analysis (fill-reducing orderings, supernodes) of the stage
// before. Every stage factorises afresh: the last factorisation of a
// Levenberg-Marquardt stage (of its damped Gauss-Newton matrix) is a poor
// preconditioner for the exact Hessian's tight solves (cactus 10-ring,
// K = 8: 113 CG iterations on it where a fresh factor needs 4).
class PathLinearSolvers {
 public:
  PathLinearSolvers();
  ~PathLinearSolvers();
  PathLinearSolvers(const PathLinearSolvers&) = delete;
  PathLinearSolvers& operator=(const PathLinearSolvers&) = delete;

  BlockJacobiSolver& block_jacobi();

 private:
  std::unique_ptr<BlockJacobiSolver> block_jacobi_;
};

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
  // kLevenbergMarquardt: instead of the line-search Newton iteration below,
  // the Levenberg-Marquardt iteration of the engine (NewtonSettings::
  // Globalisation), a trust region on the model `model`: the Gauss-Newton
  // matrix J^T J of the residuals (HessianModel::kGaussNewton, the model of
  // Ceres' LM) or the exact Hessian (kExact: a trust-region Newton, lambda
  // -> 0 near a minimiser, so quadratic there), with the same linear
  // solvers (block-Jacobi CG: memory O(K x one shape)) starting from lambda
  // = lm_initial. The line-search iteration always uses the exact Hessian.
  NewtonSettings::Globalisation globalisation =
      NewtonSettings::Globalisation::kLineSearch;
  HessianModel model = HessianModel::kExact;
  double lm_initial = 1e-4;
  // Block-Jacobi CG only: precondition with the time-coupled Kronecker
  // model (time_coupled_preconditioner.h) where every slice has the same
  // free coordinates (a mask), plain block Jacobi otherwise. On the finger
  // and cactus ring masks it needs 2-4x fewer CG iterations.
  bool time_coupled_preconditioner = true;
  // The linear solves' relative residual: min(0.1, max(min(forcing,
  // (|G| / |G_0|)^2), 0.25 tolerance / |G|)) (NewtonSettings::Forcing::
  // kInexactNewton). Away from the quadratic regime the steps are limited by
  // the nonlinearity, not by the solve: on finger_ring the Newton finish
  // takes 5 steps with forcing 1e-4, 1e-3, 1e-2 and 1e-1 alike (110, 89, 77
  // and 48 CG iterations), and the faces geodesic 62.8 s (1e-2) against
  // 52.6 s (1e-1).
  double forcing = 1e-1;
  // NewtonSettings::hand_over_contraction (0: off).
  double hand_over_contraction = 0;
  // NewtonSettings::stall_steps (0: off; stall_factor 0.5).
  int stall_steps = 0;
  // NewtonSettings::tr_basin_ratio (kTrustRegion; 0: off).
  double basin_ratio = 0;
  // The step limit of every trial path (0: off): a trial in which a
  // triangle of an inner shape keeps less than this fraction of its area in
  // the current path, or turns over against it (normals with a negative dot
  // product), is not evaluated (EvaluationStatus::kInfeasible): the line
  // search shortens the step, the trust region shrinks. No triangle is
  // driven to zero area in one step: a sliver of the input that the path
  // compresses gets there, if at all, through steps the energy accepts one
  // by one, never by jumping across the barrier of the membrane energy.
  double min_area_fraction = 0;
  // Nonlinear elimination (stiff_vertex_elimination.h), or nullptr: every
  // trial path is handed to its Solve (at most kEliminationNewtonSteps
  // steps, down to gradient_tolerance) before its merit is measured. The
  // space must be the one `elimination` was built on.
  StiffVertexElimination* elimination = nullptr;
  // The best-iterate rule: a stage that ends short of its tolerance with a
  // larger gradient max norm than an iterate it met (its start included)
  // leaves that iterate in the path, not the last one, and says so in its
  // stop reason (NewtonReport::restored_best). A stage never hands on a
  // path with a larger gradient than the one it received.
  bool keep_best_iterate = true;
  // The solvers of the stage before on the same path problem (its pattern
  // analysis reused), or nullptr: solvers of this stage alone.
  PathLinearSolvers* solvers = nullptr;
  // The solve runs in a renumbered space (`space` is renumbering->space;
  // shell_space_renumbering.h), or nullptr. Without a mask the rigid gauge
  // is then pinned at the vertices ChooseGaugeVertices picks in the caller's
  // numbering, so that the result is the caller's solve's up to round-off
  // (on a symmetric mesh the farthest vertices tie, and the ties go to the
  // lower index).
  const RenumberedShellSpace* renumbering = nullptr;
  int num_threads = 2;  // Hessian blocks are assembled in parallel
  bool progress = false;
  std::string progress_label = "newton";
  StopToken stop;  // NewtonSettings::stop
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
// residual min(forcing, (|G|/|G_0|)^2), never tighter than a quarter of the
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
