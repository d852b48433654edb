// One Newton engine for the Newton iterations of the library: minimisation
// of a merit function (geodesic finish, elastic mean) and root finding
// (EXP step), on reduced coordinates chosen by the problem.
#ifndef SHELLSPACE_SOLVERS_NEWTON_SOLVER_H_
#define SHELLSPACE_SOLVERS_NEWTON_SOLVER_H_

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>

#include "shellspace/runtime/stop_token.h"
#include "shellspace/solvers/linear_solver.h"

namespace shellspace {

// An evaluation at a point the problem cannot evaluate (a degenerate
// triangle of a trial shape) is a status, not an exception.
enum class EvaluationStatus { kOk, kInfeasible };

// The current point x (accepted) and the trial point x ⊕ T(x) p of the line
// search.
enum class NewtonPoint { kCurrent, kTrial };

// The residual of Newton's equation at a point: the gradient G (minimisation)
// or F (root finding).
//  - reduced: T(x)^T G, resp. R^T F, in the n reduced coordinates of the
//    linear system (its right-hand side is -reduced; for minimisation the
//    slope of the merit along x ⊕ T(x) t p is reduced . p);
//  - max_norm, two_norm: the norms the tolerance and the acceptance rules
//    measure, in the coordinates the problem reports (e.g. the full 3 #V
//    gradient, or F on the unmasked vertices).
//  - scale: the tolerance is relative to it (1: absolute), e.g. the size of
//    one of the gradient's terms at this point.
struct NewtonResidual {
  Eigen::VectorXd reduced;
  double max_norm = 0;
  double two_norm = 0;
  double scale = 1;
  // max_norm and two_norm of `reduced` itself.
  static NewtonResidual OfReduced(Eigen::VectorXd reduced);
};

// The problem side of the engine. The problem holds the current point x and
// one trial point; p lives in the reduced coordinates at x (T(x) may depend
// on x, e.g. a rigid-gauge basis of the current shape).
class NewtonProblem {
 public:
  virtual ~NewtonProblem() = default;
  // The merit (minimisation only; root finding never asks): the function
  // being minimised at `point`.
  virtual EvaluationStatus Merit(NewtonPoint point, double* merit) = 0;
  virtual EvaluationStatus Residual(NewtonPoint point,
                                    NewtonResidual* residual) = 0;
  // The reduced Hessian (minimisation: symmetric, lower triangle suffices)
  // or Jacobian (root finding) at the current point, n x n.
  virtual EvaluationStatus Assemble(LinearSystem* system) = 0;
  // trial = x ⊕ T(x) step (the retraction; step in reduced coordinates).
  virtual void SetTrial(const Eigen::VectorXd& step) = 0;
  // x = trial (the last SetTrial).
  virtual void AcceptTrial() = 0;
};

enum class NewtonMode {
  // Minimise the merit: H p = -G with H SPD, accepted on sufficient decrease
  // of the merit (Armijo) or the alternative rules below.
  kMinimize,
  // Solve F = 0: J p = -F, accepted on the rules below only (no merit).
  kRootFind,
};

struct NewtonReport;

// Settings of one Newton solve; the stall and acceptance rules of the former
// hand-written loops are named settings here.
struct NewtonSettings {
  NewtonMode mode = NewtonMode::kMinimize;
  int max_steps = 10;  // accepted steps
  // Converged at residual max_norm <= tolerance * scale (NewtonResidual).
  double tolerance = 0;

  // Relative residual of the linear solve (LinearSolver tolerance):
  //  - kFixed: `forcing`;
  //  - kInexactNewton: with g = |reduced|_2 and g_0 its value at the start,
  //    min(0.1, max(min(forcing, (g / g_0)^2), 0.25 tolerance / g)):
  //    tighter as the gradient falls, but no tighter than needed to land
  //    below the tolerance. (g / g_0)^2 rather than g / g_0: the Newton
  //    finish starts where the gradient is already small, and with g / g_0
  //    the solve's residual, not the nonlinearity, set the rate (cactus
  //    10-ring: |grad| 1.9e-5, 7.9e-7, 8.8e-10, 1.9e-12 in 4 steps; squared:
  //    1.9e-5, 1.0e-7, 2.3e-12 in 3, the same 10 CG iterations; finger ring
  //    6 -> 5 steps, faces 16 -> 15, 256 -> 230 CG);
  //  - kRelativeResidual: max_norm / scale clamped to [forcing_min, forcing].
  enum class Forcing { kFixed, kInexactNewton, kRelativeResidual };
  Forcing forcing_rule = Forcing::kFixed;
  double forcing = 1e-10;
  double forcing_min = 0;

  // Line search: step lengths 1, 1/2, ..., 2^-max_halvings.
  int max_halvings = 2;
  double armijo = 1e-4;  // minimisation: merit <= merit_0 + armijo t slope
  // Accept a trial whose residual max_norm is at most this factor times the
  // current one (0: off; root finding without merit, e.g. 0.5).
  double accept_max_norm_reduction = 0;
  // Also accept a trial whose residual max_norm is smaller than the current
  // one (strictly), in minimisation only when the merit changes by at most
  // merit_round_off |merit| (the merit decrease is below round-off and the
  // gradient decides; in the trust region the gradient alone then decides,
  // so a step that raises it is not taken whatever its rho).
  bool accept_smaller_max_norm = false;
  double merit_round_off = 1e-10;
  // Also accept a trial whose residual two_norm is smaller (strictly).
  bool accept_smaller_two_norm = false;

  // Globalisation of minimisation (0: off): when the Newton step cannot be
  // used -- H not positive definite, slope reduced . p >= 0, or no step
  // length of the line search accepted -- the step is recomputed from the
  // shifted Hessian H + lambda I (a Levenberg-Marquardt shift on the exact
  // Hessian: for growing lambda the step turns towards -reduced and
  // shortens, a trust region on H), with lambda = shift_initial * mean
  // |diag H| and then shift_factor times the previous one, at most
  // max_shifts times per iteration. After an accepted shifted step the next
  // iteration starts from lambda / shift_factor (back to 0 once it drops
  // below shift_initial * mean |diag H|). Every accepted step of
  // minimisation (shifted or not, by any rule above) has a merit no larger
  // than merit + merit_round_off |merit|: the merit never rises beyond
  // round-off.
  int max_shifts = 0;
  double shift_initial = 1e-3;
  double shift_factor = 10;

  // How minimisation steps are globalised:
  //  - kLineSearch: the Newton step with the line search and the shifts
  //    above;
  //  - kLevenbergMarquardt: every step from (H + lambda D) p = -reduced, a
  //    trust region on the quadratic model q(p) = reduced . p + 1/2 p^T H p
  //    of the merit (H e.g. a Gauss-Newton matrix, positive semidefinite):
  //    D = diag |H| floored at lm_min_diagonal x its mean (Marquardt's
  //    scaling: stiff and soft unknowns are damped alike); the step is
  //    accepted when the merit falls by at least lm_min_ratio of the
  //    decrease -q(p) the model predicts (rho = actual / predicted);
  //    lambda starts at lm_initial, and after an accepted step becomes
  //    lambda max(1/3, 1 - (2 rho - 1)^3) (nu = 2), after a rejected one
  //    lambda nu (nu doubles) -- Nielsen's rule, as Ceres' LM. Where the
  //    merit changes by less than merit_round_off |merit| (with
  //    accept_smaller_max_norm, or where the predicted decrease is below
  //    that too) rho is round-off: the step is accepted if and only if it
  //    lowers the residual's max_norm, whatever rho, and lambda stays. A
  //    step whose
  //    predicted decrease is not positive is rejected without a trial. At
  //    most lm_max_rejections rejected steps in a row, then
  //    kLineSearchFailed. The line-search and shift settings above are not
  //    used.
  //  - kTrustRegion: a trust region on the model q(p) above with the exact
  //    H (possibly indefinite), in the norm |p|_M of the linear solver's
  //    preconditioner M (LinearSolver::preconditioner: the Cholesky factor
  //    of H or of its diagonal blocks, factorised at most once per
  //    iteration and kept while the last subproblem took at most
  //    tr_refactor_cg_iterations CG iterations; where
  //    that factorisation is not positive definite, of H + sigma I with
  //    sigma = tr_shift_initial x mean |diag H|, ten times larger per
  //    failure, at most tr_max_shifts times). The step solves the
  //    subproblem by Steihaug-Toint CG (steihaug_cg.h) to the forcing
  //    tolerance: the inexact Newton step whenever CG stays inside the
  //    region and meets no negative curvature, else a step to the boundary
  //    (along a direction of negative curvature where H has one). The
  //    radius starts at tr_initial_radius (+inf: the first step is the
  //    Newton step); rho = actual / predicted decrease; rho >= tr_accept
  //    accepts, except where the merit changes by less than its round-off
  //    (with accept_smaller_max_norm, or where the predicted decrease is
  //    below it too): there rho is noise, and the trial is accepted if and
  //    only if its residual max_norm is smaller; rho < 1/4, a trial that
  //    cannot be evaluated or one not taken sets the radius to |p|_M / 4;
  //    rho > 3/4 on a step at the boundary doubles it. At most
  //    tr_max_rejections rejected trials in a row, then kLineSearchFailed. The
  //    line-search, shift and LM settings are not used.
  enum class Globalisation { kLineSearch, kLevenbergMarquardt, kTrustRegion };
  Globalisation globalisation = Globalisation::kLineSearch;
  double lm_initial = 1e-4;
  double lm_min_diagonal = 1e-6;
  double lm_min_ratio = 1e-3;
  int lm_max_rejections = 12;
  double tr_initial_radius = std::numeric_limits<double>::infinity();
  double tr_accept = 1e-4;
  int tr_max_rejections = 12;
  int tr_max_cg_iterations = 2000;
  int tr_max_shifts = 16;
  double tr_shift_initial = 1e-6;
  // The preconditioner of an earlier iteration is reused while its
  // subproblems need at most this many CG iterations.
  int tr_refactor_cg_iterations = 25;
  // kTrustRegion as a probe of Newton's basin (0: off): the solve ends
  // (kOutsideBasin) at the first step that is not a full Newton step of a
  // good model -- a rejected trial (not taken), or one that ended on the
  // boundary or along negative curvature or whose ratio rho is below
  // tr_basin_ratio (taken if acceptable; a decrease below the merit's
  // round-off taken on a smaller residual is not judged by its rho). Near a
  // minimiser rho -> 1; a caller that handed over early (hand_over_contraction)
  // goes back to its first method there instead of globalising Newton far from
  // the basin.
  double tr_basin_ratio = 0;

  // Stall rules (0: off).
  // Round-off floor: stop after an accepted step that leaves max_norm <=
  // round_off_floor but has not reduced it by round_off_factor.
  double round_off_floor = 0;
  double round_off_factor = 0.5;
  // No progress: stop when progress_steps accepted steps have not brought
  // max_norm to progress_factor times its initial value.
  int progress_steps = 0;
  double progress_factor = 0.5;
  // Hand-over (minimisation; 0: off): stop (kHandedOver) after an accepted
  // step that divided the residual's max_norm by at least this factor,
  // for a caller that then switches to another method. Meant for a
  // Levenberg-Marquardt stage on a Gauss-Newton model: Gauss-Newton
  // converges linearly, at a rate set by the second-order term of the
  // residuals it leaves out; one step that cuts the gradient tenfold shows
  // that term already small against J^T J along the step, and Newton's
  // method on the exact Hessian can take over. Deterministic: it reads
  // norms, no clock.
  double hand_over_contraction = 0;
  // Stall (0: off): stop (kNoProgress) once the residual's
  // max_norm after an accepted step is above stall_factor times its value
  // stall_steps accepted steps before. Meant for a Levenberg-Marquardt stage
  // whose Gauss-Newton model has stopped explaining the problem (its rate
  // tends to 1): its caller tries the exact Hessian instead of spending the
  // iteration budget. Deterministic: it reads norms, no clock.
  int stall_steps = 0;
  double stall_factor = 0.5;

  // Called after every line search (accepted or not), for progress lines.
  std::function<void(const NewtonReport& report, double merit,
                     bool accepted)>
      progress;
  // Asked before every step: a stop stops at the current point (kStopped).
  StopToken stop;
};

enum class NewtonStop {
  kConverged,          // max_norm <= tolerance
  kMaxSteps,           // max_steps accepted steps, tolerance not met
  kInfeasibleStart,    // the start point cannot be evaluated
  kAssemblyFailed,     // the Hessian / Jacobian cannot be assembled
  kLinearSolveFailed,  // H not positive definite / J singular
  kNotDescent,         // minimisation: slope reduced . p >= 0 (or p not finite)
  kLineSearchFailed,   // no step length accepted
  kRoundOffFloor,      // the round-off floor rule
  kNoProgress,         // the no-progress rule
  kHandedOver,         // the hand-over rule (hand_over_contraction)
  kOutsideBasin,       // the basin probe (tr_basin_ratio)
  kStopped,            // NewtonSettings::stop said stop
};

// The text of a stop reason (the same for every problem), e.g. "converged",
// "Hessian not positive definite" (minimisation) / "singular Jacobian".
std::string NewtonStopText(NewtonStop stop, NewtonMode mode);

// What a Newton solve did. Counts are deterministic; the seconds are wall
// clock, information only.
struct NewtonReport {
  int steps = 0;                // accepted Newton steps
  int iterations = 0;           // Hessian / Jacobian assemblies
  // Residual max_norm before / after (both +inf, and final_merit too, if
  // the start cannot be evaluated: stop kInfeasibleStart).
  double initial_gradient = 0;
  double final_gradient = 0;
  double final_merit = 0;       // minimisation: the merit at the end
  bool converged = false;       // final_gradient <= tolerance
  NewtonStop stop = NewtonStop::kMaxSteps;
  std::string stop_reason;      // NewtonStopText, or the caller's
  double seconds = 0;
  double assembly_seconds = 0;       // of which: Hessian / Jacobian assembly
  int factorizations = 0;            // of the linear solver, this solve
  int time_coupled_factorizations = 0;  // of which time-coupled (block CG)
  double factorization_seconds = 0;  // of which: factorisations
  int cg_iterations = 0;             // CG iterations on a reused factor
  double cg_seconds = 0;             // of which: CG
  int attempts = 0;                  // solves summed by Append
  std::string linear_solver;         // LinearSolver::name() of the last solve
  int cg_not_converged = 0;          // iterative solves short of tolerance
  int shifted_steps = 0;             // accepted steps from H + lambda I
  // kTrustRegion: accepted steps that ended on the trust region's boundary
  // (CG truncated), of which along negative curvature; rejected trials;
  // iterations whose preconditioner needed a diagonal shift.
  int boundary_steps = 0;
  int negative_curvature_steps = 0;
  int rejected_trials = 0;
  int shifted_preconditioners = 0;
  double max_shift = 0;              // largest lambda tried (0: none)
  // kLevenbergMarquardt: the lambda the next step would have started from
  // (lm_initial for a solve that continues this one).
  double final_damping = 0;
  // The caller put back an earlier iterate with a smaller residual max_norm
  // than the last one (final_gradient and final_merit are that iterate's).
  bool restored_best = false;

  // Adds a later solve: counts and times summed, the rest from `later`
  // (initial_gradient stays the first solve's).
  void Append(const NewtonReport& later);
};

// Newton's method on `problem` from its current point: at most max_steps
// times, residual G (or F) and H (or J) at x, p from linear_solver with the
// forcing tolerance, then the line search of `settings`; the problem is left
// at the last accepted point. linear_solver may be reused across solves
// (its factor as a CG preconditioner); the report counts this solve's work.
NewtonReport SolveNewton(NewtonProblem* problem, LinearSolver* linear_solver,
                         const NewtonSettings& settings);

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_NEWTON_SOLVER_H_
