// The product of a symmetric block-tridiagonal matrix (a path Hessian: each
// time slice coupled to its neighbours only) with a vector, in parallel over
// the slices.
#ifndef SHELLSPACE_SOLVERS_BLOCK_TRIDIAGONAL_PRODUCT_H_
#define SHELLSPACE_SOLVERS_BLOCK_TRIDIAGONAL_PRODUCT_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace shellspace {

// y = H d, H symmetric, given by its lower triangle `lower` (compressed
// columns, rows ascending in each column as Eigen keeps them; entries
// above the diagonal are ignored, as by Eigen's selfadjointView<Lower>),
// whose rows and columns fall into the slices
// [offsets[c], offsets[c + 1]). Slice c's columns write y's rows of slice c
// and a spill into slice c + 1's rows, added afterwards slice by slice: the
// slices run in parallel (`threads` at a time) and the result does not
// depend on the thread count (deterministic; its round-off differs from
// Eigen's serial product).
// Returns false -- y untouched -- if an entry of `lower` couples slices
// further apart than neighbours, or the offsets do not cover `lower`.
bool BlockTridiagonalProduct(const Eigen::SparseMatrix<double>& lower,
                             const std::vector<int>& offsets,
                             const Eigen::VectorXd& d, int threads,
                             Eigen::VectorXd* y);

// BlockTridiagonalProduct, or Eigen's serial product where it returns false.
Eigen::VectorXd SymmetricProduct(const Eigen::SparseMatrix<double>& lower,
                                 const std::vector<int>& offsets,
                                 const Eigen::VectorXd& d, int threads);

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_BLOCK_TRIDIAGONAL_PRODUCT_H_
