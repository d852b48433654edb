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
#include <algorithm>
#include <cmath>

namespace shellspace {

// Relative shift of the positive-semidefiniteness test (see above).
inline constexpr double kPsdTestShift = 1e-12;

// Replaces the symmetric matrix m (both triangles set) by
// Q diag(max(lambda_i, 0)) Q^T, from its eigen-decomposition; false (m left
// as it is) if the eigen-solver fails. One compiled body for every size
// (psd_projection.cc): a fixed-size eigen-solver per size cost half a minute
// of compilation each, for no measurable speed.
bool ClampNegativeEigenvalues(Eigen::Ref<Eigen::MatrixXd> m);

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
  if (!ClampNegativeEigenvalues(m)) return false;
  *a = m;
  return true;
}

// The same projection for the Hessian of an element term, a function of
// `kShapes` shapes' stencils of kVertices vertices each (a is n x n, n =
// 3 kVertices kShapes, the shapes' coordinates one after the other, vertex
// after vertex) that does not change when any one shape is translated: a
// annihilates those 3 kShapes translations, so a = Z m Z^T with
// m = Z^T a Z and Z the orthonormal basis of their complement, and
// P(a) = Z P(m) Z^T. The eigen-decomposition is that of m, of size
// n - 3 kShapes (18 instead of 24 for a hinge term in both of its shapes:
// about 2.4 times less work; 12 instead of 18 for a triangle's). Z is
// block-diagonal, C (x) I_3 per shape, C the kVertices x (kVertices - 1)
// Helmert contrasts (orthonormal columns orthogonal to (1, ..., 1)).
// Returns true if *a was changed; a positive semidefinite m leaves *a
// exactly as it is.
template <int kVertices, int kShapes>
Eigen::Matrix<double, 3 * kVertices * kShapes, 3 * (kVertices - 1) * kShapes>
TranslationComplementBasis() {
  constexpr int n = 3 * kVertices, m = 3 * (kVertices - 1);
  Eigen::Matrix<double, 3 * kVertices * kShapes, m * kShapes> z;
  z.setZero();
  for (int shape = 0; shape < kShapes; ++shape) {
    for (int j = 1; j < kVertices; ++j) {
      const double norm = std::sqrt(double(j) * (j + 1));
      for (int i = 0; i <= j; ++i) {
        const double c = i < j ? 1.0 / norm : -double(j) / norm;
        for (int d = 0; d < 3; ++d) {
          z(shape * n + 3 * i + d, shape * m + 3 * (j - 1) + d) = c;
        }
      }
    }
  }
  return z;
}

template <int kVertices, int kShapes, class Matrix>
bool ProjectToPositiveSemidefiniteModuloTranslations(Matrix* a) {
  static const auto z = TranslationComplementBasis<kVertices, kShapes>();
  constexpr int m = 3 * (kVertices - 1) * kShapes;
  if (!a->allFinite()) return false;
  Eigen::Matrix<double, m, m> reduced = z.transpose() * (*a) * z;
  reduced = 0.5 * (reduced + reduced.transpose()).eval();
  if (!ProjectToPositiveSemidefinite(&reduced)) return false;
  *a = z * reduced * z.transpose();
  return true;
}

// The projections of the element set's matrices, for stencils of kVertices
// = 3 .. 6 vertices (n = 3 kVertices): the one-sided blocks (n x n,
// row-major: ElementSecondDerivatives::ComputeModel), the terms in one and
// in both shapes (ProjectToPositiveSemidefiniteModuloTranslations
// <kVertices, 1> of the n x n row-major block, <kVertices, 2> of the 2n x 2n
// matrix: ElementTermSecondDerivatives) and the reduced matrices these
// project (3 (kVertices - 1) kShapes square). With kind `extern template`
// their explicit instantiation declarations (below), with kind `template`
// their definitions, compiled once in psd_projection_<kVertices>.cc, each
// with the sizes of reduced matrix listed under it (one file each: in one
// file together they take twice as long to compile).
#define SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(kind, n) \
  kind bool ProjectToPositiveSemidefinite(Eigen::Matrix<double, n, n>*)
#define SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_STENCIL(kind, k)    \
  kind bool ProjectToPositiveSemidefinite(                         \
      Eigen::Matrix<double, 3 * k, 3 * k, Eigen::RowMajor>*);      \
  kind bool ProjectToPositiveSemidefiniteModuloTranslations<k, 1>( \
      Eigen::Matrix<double, 3 * k, 3 * k, Eigen::RowMajor>*);      \
  kind bool ProjectToPositiveSemidefiniteModuloTranslations<k, 2>( \
      Eigen::Matrix<double, 6 * k, 6 * k>*)

// psd_projection_3.cc
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_STENCIL(extern template, 3);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(extern template, 6);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(extern template, 9);
// psd_projection_4.cc
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_STENCIL(extern template, 4);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(extern template, 12);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(extern template, 18);
// psd_projection_5.cc
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_STENCIL(extern template, 5);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(extern template, 15);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(extern template, 24);
// psd_projection_6.cc
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_STENCIL(extern template, 6);
SHELLSPACE_PSD_PROJECTION_TEMPLATES_OF_SIZE(extern template, 30);

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_PSD_PROJECTION_H_
