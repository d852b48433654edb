// Fill-reducing ordering for the sparse Cholesky factorisation of path
// Hessians (block tridiagonal in time, each block a mesh stencil).
#ifndef SHELLSPACE_SOLVERS_SPACE_TIME_ORDERING_H_
#define SHELLSPACE_SOLVERS_SPACE_TIME_ORDERING_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace shellspace {

// A permutation (Eigen convention: indices()[old] = new) of the unknowns of
// a symmetric matrix whose unknown i lives on spatial vertex vertex_of[i].
// The vertex graph (vertices adjacent if any of their unknowns are coupled
// in `lower`, the lower triangle) is ordered by CHOLMOD's own choice
// (AMD / METIS nested dissection, whichever fills less), and the unknowns
// of each vertex, over all time slices, are numbered consecutively in that
// order.
//
// Why: ordering the scalar space-time graph directly lets the ordering
// cut through time, making a whole shape a dense separator (on the finger
// path, K = 8: 2.5e10 flops and 2.3e7 entries in L); cutting only in space
// keeps separators at (mesh separator) x (time slices).
Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>
SpaceTimeOrdering(const Eigen::SparseMatrix<double>& lower,
                  const std::vector<int>& vertex_of, int num_vertices);

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_SPACE_TIME_ORDERING_H_
