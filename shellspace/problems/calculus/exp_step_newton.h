// Newton's method for the root-finding problem of one EXP step.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_EXP_STEP_NEWTON_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_EXP_STEP_NEWTON_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/solvers/newton_solver.h"

namespace shellspace {

// The report of SolveExpStepNewton: a NewtonReport whose initial_gradient /
// final_gradient are max |F| over the unknown vertices (+inf both if F
// cannot be evaluated at the start: stop kInfeasibleStart).
using ExpNewtonReport = NewtonReport;

// The equation of one EXP step, F(s) = c + D_fixed W = 0 (see
// SolveExpStepNewton): the shell space, the fixed shell s_k, which side of
// W the unknown s is, the constant c (3 x #V) and the masked vertices. Holds
// references: the referents must outlive it.
struct ExpStepEquation {
  const ShellSpace& space;
  const Positions& fixed;
  ShellSide unknown_side;
  const Eigen::VectorXd& constant;
  const std::vector<int>& fixed_vertices;
};

// max |F(s)| over the vertices not in `fixed_vertices`; +inf if s has a
// degenerate triangle.
double ExpResidualMaxNorm(const ExpStepEquation& equation, const Positions& s);

// Solves F(s) = c + D_fixed W = 0 (gradient_field_residual.h: forward step
// unknown_side = kDeformed, F = D_2 W[s_{k-1}, s_k] + D_1 W[s_k, s]; backward
// unknown_side = kReference, F = D_2 W[s, s_k] + D_1 W[s_k, s_{k+1}]) for s,
// starting from *s, by Newton's method with the exact Jacobian J = dF/ds
// (the mixed block of W), solved by sparse LU (UMFPACK) on the reduced
// system: rows and columns restricted to the vertices not in
// `fixed_vertices`, or, without a mask, to RigidGaugeBasis of the fixed
// shell (rows: F is orthogonal to its rigid motions) and of s (columns: F
// ignores rigid motions of s). Least squares on |F|^2 (Gauss-Newton on
// J^T J, as Ceres' LM) squares the condition number of J, which for thin
// shells is already large; Newton works with J itself. The iteration is
// SolveNewton (solvers/newton_solver.h) in root-finding mode with SparseLu
// (UMFPACK); the rules below are its settings. A step is accepted if it
// lowers max |F| or |F|_2, halving it at most 20 times; stops at
// max |F| <= tolerance, after max_steps, when no step is accepted (*s is
// left at the best point reached), or at the round-off floor: an accepted
// step that leaves max |F| <= stall_tolerance but does not halve it (the
// quadratic convergence is over; on the cactus the floor is ~1.7e-11 of
// |c| and further steps only shuffle round-off, 0.5 s each), or when 8
// accepted steps have not halved max |F| (no root nearby). Masked
// vertices of *s are not touched.
struct ExpNewtonStopping {
  double tolerance = 0;        // stop at max |F| <= tolerance
  double stall_tolerance = 0;  // the round-off floor, absolute like tolerance
  int max_steps = 0;
};
ExpNewtonReport SolveExpStepNewton(const ExpStepEquation& equation,
                                   const ExpNewtonStopping& stopping,
                                   Positions* s);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_EXP_STEP_NEWTON_H_
