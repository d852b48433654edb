// The trust-region subproblem of a Newton step by the truncated conjugate
// gradients of Steihaug and Toint: approximately
//   min_p  m(p) = g . p + 1/2 p^T H p   subject to  |p|_M <= radius,
// with H symmetric (possibly indefinite) and M an SPD preconditioner, the
// norm |p|_M = sqrt(p^T M p) of the preconditioner (Conn, Gould & Toint,
// "Trust-Region Methods", §7.5; Nocedal & Wright, Alg. 7.2).
#ifndef SHELLSPACE_SOLVERS_STEIHAUG_CG_H_
#define SHELLSPACE_SOLVERS_STEIHAUG_CG_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "shellspace/solvers/linear_solver.h"

namespace shellspace {

struct SteihaugResult {
  enum class Stop {
    kConverged,          // |H p + g|_2 <= tolerance |g|_2 inside the region
    kBoundary,           // the CG path left the region: p on its boundary
    kNegativeCurvature,  // d^T H d <= 0 for a CG direction d (see below)
    kMaxIterations,      // max_iterations first: p the last iterate
  };
  Eigen::VectorXd step;   // p
  Stop stop = Stop::kConverged;
  int iterations = 0;     // CG iterations (products with H)
  double model_decrease = 0;  // -m(p); >= 0 along the CG path
  double step_norm = 0;       // |p|_M
};

// CG on H p = -g from p = 0, preconditioned by M, stopped by the first of:
// the relative residual `tolerance`, max_iterations, the boundary
// |p|_M = radius (the step to it along the current direction), or a
// direction d of non-positive curvature d^T H d <= 0 -- then p moves along d
// to the boundary (the model decreases without bound along it). With
// radius = +infinity there is no boundary: negative curvature returns the
// CG iterate so far, or, in the first iteration, d = -M^-1 g itself (the
// preconditioned steepest-descent step, |d|_M = sqrt(g^T M^-1 g)), so the
// caller's trust region takes over from a finite length. `lower` is the
// lower triangle of H. Each iterate decreases m, and |p|_M grows along the
// path (Steihaug's theorem), so the result is never worse than the
// preconditioned Cauchy point. Deterministic: iteration counts only.
SteihaugResult SolveSteihaugCg(const Eigen::SparseMatrix<double>& lower,
                               const Eigen::VectorXd& g,
                               const Preconditioner& preconditioner,
                               double radius, double tolerance,
                               int max_iterations);

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_STEIHAUG_CG_H_
