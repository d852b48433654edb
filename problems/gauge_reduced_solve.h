// Solving H p = b for a Hessian H whose null space is the rigid motions of a
// shell (H = second derivative of a rigidly invariant energy).
#ifndef SHELLSPACE_PROBLEMS_GAUGE_REDUCED_SOLVE_H_
#define SHELLSPACE_PROBLEMS_GAUGE_REDUCED_SOLVE_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "geometry/mesh.h"

namespace shellspace {

// With the gauge vertices (a, b, c) of ChooseGaugeVertices(shape) and u =
// (X_b - X_a)/|.|, w the unit in-plane normal to u: p = T q, where T is the
// identity on every other coordinate, zero on a, u on b and [u w] on c (the
// 3n - 6 directions left by PinRigidMotions); solves (T^T H T) q = T^T rhs by
// sparse Cholesky (LDL^T). For rhs orthogonal to the rigid motions (a
// gradient of a rigidly invariant function) this is a solution of H p = rhs;
// p is unique up to a rigid motion. Throws InputError if the reduced matrix is
// not positive definite.
Eigen::VectorXd SolveModuloRigidMotions(const Eigen::SparseMatrix<double>& h,
                                        const Eigen::VectorXd& rhs,
                                        const Positions& shape);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_GAUGE_REDUCED_SOLVE_H_
