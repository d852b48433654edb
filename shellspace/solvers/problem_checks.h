// Checks of a ceres::Problem that Ceres itself does not make.
#ifndef SHELLSPACE_SOLVERS_PROBLEM_CHECKS_H_
#define SHELLSPACE_SOLVERS_PROBLEM_CHECKS_H_

#include <ceres/problem.h>

#include <string>

namespace shellspace {

// Throws InputError("WHAT acts only on constant parameter blocks ...") if
// every parameter block of residual block `id` is constant: such a residual
// cannot move the solution (Ceres evaluates it and reports CONVERGENCE after
// 0 iterations), which is almost always a residual placed on vertices a
// mask holds fixed. Call it after the blocks' constancy is set. (The
// element residuals of W legitimately touch only fixed vertices inside a
// masked region; check your own residuals, not those.)
void RequireVariableResidual(const ceres::Problem& problem,
                             ceres::ResidualBlockId id, const std::string& what);

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_PROBLEM_CHECKS_H_
