// The parallel product of a block-tridiagonal symmetric matrix: Eigen's
// serial product to round-off, the same bits on any thread count, refused
// where the matrix couples slices further apart.
#include "shellspace/solvers/block_tridiagonal_product.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/testing/kronecker_model.h"

namespace shellspace {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

Eigen::VectorXd TestVector(int size) {
  Eigen::VectorXd v(size);
  for (int i = 0; i < size; ++i) v(i) = std::cos(0.23 * i) - 0.2;
  return v;
}

// max |y - Eigen's H d| / max |Eigen's H d|.
double ProductError(const SparseMatrix& lower, const std::vector<int>& offsets,
                    int threads, Eigen::VectorXd* y) {
  const Eigen::VectorXd d = TestVector(static_cast<int>(lower.rows()));
  const Eigen::VectorXd expected = lower.selfadjointView<Eigen::Lower>() * d;
  if (!BlockTridiagonalProduct(lower, offsets, d, threads, y)) return -1;
  return (*y - expected).cwiseAbs().maxCoeff() /
         expected.cwiseAbs().maxCoeff();
}

TEST(BlockTridiagonalProductTest, IsEigensProductOnEveryThreadCount) {
  const SparseMatrix g = testing::PlateLaplacianMetric(0.1);
  const int m = static_cast<int>(g.rows());
  for (int K : {2, 3, 8}) {
    // Entries that differ from slice to slice: the model times a ramp.
    SparseMatrix lower = testing::KroneckerPathModel(g, K, 1.3);
    for (int c = 0; c < lower.outerSize(); ++c) {
      for (SparseMatrix::InnerIterator it(lower, c); it; ++it) {
        it.valueRef() *= 1 + 0.01 * it.row() + 0.003 * c;
      }
    }
    const std::vector<int> offsets = testing::SliceOffsets(K - 1, m);
    Eigen::VectorXd one, two, three;
    EXPECT_LT(ProductError(lower, offsets, 1, &one), 1e-14) << K;
    EXPECT_GE(ProductError(lower, offsets, 1, &one), 0) << K;
    ProductError(lower, offsets, 2, &two);
    ProductError(lower, offsets, 3, &three);
    EXPECT_EQ(one, two) << K;
    EXPECT_EQ(one, three) << K;
  }
}

TEST(BlockTridiagonalProductTest, RefusesCouplingsBeyondNeighbours) {
  const SparseMatrix g = testing::PlateLaplacianMetric(0.1);
  const int m = static_cast<int>(g.rows());
  const SparseMatrix lower = testing::KroneckerPathModel(g, 8);
  Eigen::VectorXd y;
  // Slices a third as long (m = 3 x 121): the couplings now skip slices.
  ASSERT_EQ(m % 3, 0);
  EXPECT_EQ(ProductError(lower, testing::SliceOffsets(21, m / 3), 2, &y), -1);
  // Offsets that do not cover the matrix.
  EXPECT_EQ(ProductError(lower, testing::SliceOffsets(6, m - 1), 2, &y), -1);
  // SymmetricProduct falls back to Eigen's product there.
  const Eigen::VectorXd d = TestVector(static_cast<int>(lower.rows()));
  EXPECT_EQ(SymmetricProduct(lower, testing::SliceOffsets(21, m / 3), d, 2),
            Eigen::VectorXd(lower.selfadjointView<Eigen::Lower>() * d));
}

}  // namespace
}  // namespace shellspace
