// Solving H p = b for a Hessian H whose null space is the rigid motions of a
// shell (H = second derivative of a rigidly invariant energy).
#ifndef SHELLSPACE_SOLVERS_GAUGE_REDUCED_SOLVE_H_
#define SHELLSPACE_SOLVERS_GAUGE_REDUCED_SOLVE_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include <array>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// Basis T (3n x (3n - 6)) of the coordinates left free by PinRigidMotions:
// with the gauge vertices (a, b, c) of ChooseGaugeVertices(shape), u =
// (X_b - X_a)/|.| and w the unit in-plane normal to u, T is the identity on
// every other coordinate, zero on a, u on b and [u w] on c. A rigidly
// invariant energy restricted to x + T q has no rigid null space.
Eigen::SparseMatrix<double> RigidGaugeBasis(const Positions& shape);
// The same with given gauge vertices (a, b, c), not collinear in `shape`:
// the bases of several shapes with one choice have the same sparsity
// pattern (the time-coupled preconditioner of a path needs that).
Eigen::SparseMatrix<double> RigidGaugeBasis(
    const Positions& shape, const std::array<int, 3>& vertices);

// The same for a shell of several connected components: one gauge triple
// (a, b, c) per component (ChooseGaugeVertices(shape, components)), 6
// coordinates removed in each.
Eigen::SparseMatrix<double> RigidGaugeBasis(
    const Positions& shape, const std::vector<std::array<int, 3>>& triples);

// The mesh vertex of each column of such a basis (columns are supported on
// the three coordinates of one vertex).
std::vector<int> BasisColumnVertices(const Eigen::SparseMatrix<double>& basis);

// Basis T (3n x 3m) selecting the coordinates of the m vertices not listed in
// `fixed_vertices` (Dirichlet mask), in vertex order.
Eigen::SparseMatrix<double> FreeVertexBasis(int num_vertices,
                                            const std::vector<int>& fixed_vertices);

// The step of Newton's method on a rigidly invariant energy of one shell
// (H its Hessian at `shape`, singular along the rigid motions): p = T q with
// T = RigidGaugeBasis(shape) (the 3n - 6 coordinates left by pinning the
// gauge vertices of ChooseGaugeVertices(shape)) and (T^T H T + shift I) q =
// T^T rhs by sparse LDL^T. For rhs orthogonal to the rigid motions (a
// gradient of a rigidly invariant function) and shift 0 this solves H p =
// rhs; p is unique up to a rigid motion. positive_definite: the
// factorisation succeeded, every pivot is > 0 and p is finite; p is zero if
// the factorisation failed.
struct GaugeReducedStep {
  Eigen::VectorXd p;
  bool positive_definite = false;
};
GaugeReducedStep SolveModuloRigidMotions(const Eigen::SparseMatrix<double>& h,
                                         const Eigen::VectorXd& rhs,
                                         const Positions& shape,
                                         double shift = 0);

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_GAUGE_REDUCED_SOLVE_H_
