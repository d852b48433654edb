// Projection of a small symmetric matrix onto the cone of positive
// semidefinite matrices: the building block of projected Newton, where every
// element's Hessian is replaced by its nearest positive semidefinite matrix
// before assembly, so that the assembled matrix is positive semidefinite
// whatever the state (a sum of positive semidefinite terms is).
//
// For symmetric A = Q diag(lambda) Q^T, the nearest positive semidefinite
// matrix in the Frobenius norm is
//   P(A) = Q diag(max(lambda_i, 0)) Q^T.
// A matrix that is already positive semidefinite is its own projection; the
// projection is exact in that case (returned unchanged, not recomputed from
// its eigen-decomposition). Which case holds is decided by a Cholesky
// factorisation of A + tau I, tau = kPsdTestShift x the largest diagonal
// entry: a success certifies lambda_min(A) >= -tau, which is taken as
// positive semidefinite (the eigenvalues in [-tau, 0) are round-off of the
// rigid and other null directions of an element at rest); a failure costs the
// eigen-decomposition. Shapes: A is n x n (n = 9 for a membrane triangle, 12
// for a bending flap, 2n for a term W[s_{k-1}, s_k] with both shapes free).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_PSD_PROJECTION_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_PSD_PROJECTION_H_

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>

namespace shellspace {

// Relative shift of the positive-semidefiniteness test (see above).
inline constexpr double kPsdTestShift = 1e-12;

// Replaces the symmetric matrix *a (only its lower triangle is read) by its
// projection onto the positive semidefinite cone. Returns true if *a was
// changed (it had an eigenvalue below -tau), false if it was left as it
// is. A matrix with a non-finite entry is left unchanged (false): the
// caller's evaluation reports it.
template <class Matrix>
bool ProjectToPositiveSemidefinite(Matrix* a) {
  constexpr int n = Matrix::RowsAtCompileTime;
  using Square = Eigen::Matrix<double, n, n>;
  if (!a->allFinite()) return false;
  Square m = a->template selfadjointView<Eigen::Lower>();
  const double tau =
      kPsdTestShift * std::max(m.diagonal().cwiseAbs().maxCoeff(), 1e-300);
  Square shifted = m;
  shifted.diagonal().array() += tau;
  Eigen::LLT<Square> cholesky(shifted);
  if (cholesky.info() == Eigen::Success) return false;
  Eigen::SelfAdjointEigenSolver<Square> eigen(m);
  if (eigen.info() != Eigen::Success) return false;
  const auto clamped = eigen.eigenvalues().cwiseMax(0.0);
  *a = eigen.eigenvectors() * clamped.asDiagonal() *
       eigen.eigenvectors().transpose();
  return true;
}

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_PSD_PROJECTION_H_
