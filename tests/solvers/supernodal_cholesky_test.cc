// SupernodalCholesky: the factor's values, read back as a dense L, give
// L L^T = P A P^T for procedural symmetric positive definite matrices whose
// supernodes take both code paths (plain loops for small blocks, BLAS for
// large ones); pivots that are not positive are reported; the digits do
// not depend on the thread that computes them.
#include "shellspace/solvers/supernodal_cholesky.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <thread>
#include <vector>

namespace shellspace {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// The lower triangle of a vector Laplacian on an nx x ny grid (`dofs`
// unknowns per node, coupled inside the node) plus shift times the
// identity: SPD for shift > 0. Nested dissection of the grid gives
// separators of dofs x min(nx, ny) columns, the leaves a few.
SparseMatrix GridMatrix(int nx, int ny, int dofs, double shift) {
  const int n = nx * ny * dofs;
  std::vector<Eigen::Triplet<double>> entries;
  const auto node = [&](int x, int y) { return (y * nx + x) * dofs; };
  for (int y = 0; y < ny; ++y) {
    for (int x = 0; x < nx; ++x) {
      const int a = node(x, y);
      int degree = 0;
      for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (x + dx >= nx || y + dy >= ny) continue;
        const int b = node(x + dx, y + dy);
        for (int d = 0; d < dofs; ++d) {
          // A weight that varies over the grid and between the coordinates.
          const double w = 1 + 0.5 * std::sin(0.3 * a + d);
          entries.emplace_back(b + d, a + d, -w);
          entries.emplace_back(a + d, a + d, w);
          entries.emplace_back(b + d, b + d, w);
        }
        ++degree;
      }
      for (int d = 0; d < dofs; ++d) {
        entries.emplace_back(a + d, a + d, shift);
        for (int e = 0; e < d; ++e) {
          entries.emplace_back(a + d, a + e, 0.1 * shift);  // in-node coupling
        }
      }
    }
  }
  SparseMatrix lower(n, n);
  lower.setFromTriplets(entries.begin(), entries.end());
  lower.makeCompressed();
  return lower;
}

// L (dense) from values in CHOLMOD's supernodal layout.
Eigen::MatrixXd DenseFactor(const SupernodalPattern& p,
                            const std::vector<double>& values) {
  Eigen::MatrixXd l = Eigen::MatrixXd::Zero(p.size, p.size);
  for (int s = 0; s < p.supernodes(); ++s) {
    const int first = p.first_column[s];
    const int columns = p.first_column[s + 1] - first;
    const long height = p.row_begin[s + 1] - p.row_begin[s];
    for (int j = 0; j < columns; ++j) {
      for (long i = j; i < height; ++i) {
        l(p.rows[p.row_begin[s] + i], first + j) =
            values[p.value_begin[s] + i + j * height];
      }
    }
  }
  return l;
}

// max |L L^T - P A P^T| / max |A| for the factor in `values`.
double FactorResidual(const SupernodalPattern& p,
                      const std::vector<double>& values,
                      const SparseMatrix& lower) {
  const Eigen::MatrixXd a =
      Eigen::MatrixXd(lower).selfadjointView<Eigen::Lower>();
  Eigen::MatrixXd pap(p.size, p.size);
  for (int i = 0; i < p.size; ++i) {
    for (int j = 0; j < p.size; ++j) pap(i, j) = a(p.perm[i], p.perm[j]);
  }
  const Eigen::MatrixXd l = DenseFactor(p, values);
  return (l * l.transpose() - pap).cwiseAbs().maxCoeff() /
         a.cwiseAbs().maxCoeff();
}

struct Factored {
  std::shared_ptr<const SupernodalPattern> pattern;
  std::vector<double> values;
  bool ok = false;
};

Factored Factor(const SparseMatrix& lower) {
  Factored f;
  f.pattern = std::make_shared<const SupernodalPattern>(
      SupernodalCholesky::Analyse(lower));
  const SupernodalCholesky cholesky(f.pattern, lower);
  EXPECT_TRUE(cholesky.valid());
  f.values.assign(static_cast<size_t>(f.pattern->values()), 0.0);
  f.ok = cholesky.Factorize(lower, f.values.data());
  return f;
}

// The widest supernode of a pattern.
int WidestSupernode(const SupernodalPattern& p) {
  int widest = 0;
  for (int s = 0; s < p.supernodes(); ++s) {
    widest = std::max(widest, p.first_column[s + 1] - p.first_column[s]);
  }
  return widest;
}

TEST(SupernodalCholeskyTest, TheFactorReproducesThePermutedMatrix) {
  for (const auto& [nx, ny, dofs] :
       {std::array{3, 2, 1}, std::array{12, 9, 3}, std::array{30, 24, 3}}) {
    const SparseMatrix lower = GridMatrix(nx, ny, dofs, 0.05);
    const Factored f = Factor(lower);
    ASSERT_TRUE(f.ok) << nx;
    ASSERT_EQ(f.pattern->size, nx * ny * dofs);
    EXPECT_LT(FactorResidual(*f.pattern, f.values, lower), 1e-13) << nx;
    if (nx == 30) {
      // Its top separators take the BLAS path, its leaves the loops.
      EXPECT_GE(WidestSupernode(*f.pattern), 48);
      EXPECT_GT(f.pattern->supernodes(), 100);
    }
  }
}

// The twin of the check above: the same helper sees a factor with one
// value below a diagonal off by 1e-6.
TEST(SupernodalCholeskyTest, TheResidualCheckSeesAWrongValue) {
  const SparseMatrix lower = GridMatrix(12, 9, 3, 0.05);
  Factored f = Factor(lower);
  ASSERT_TRUE(f.ok);
  const SupernodalPattern& p = *f.pattern;
  // The last value of the first supernode with rows below its triangle.
  int s = 0;
  while (p.row_begin[s + 1] - p.row_begin[s] ==
         p.first_column[s + 1] - p.first_column[s]) {
    ++s;
  }
  f.values[p.value_begin[s + 1] - 1] += 1e-6;
  EXPECT_GT(FactorResidual(p, f.values, lower), 1e-8);
}

TEST(SupernodalCholeskyTest, AFailedPivotIsReported) {
  // A negative shift makes the grid matrix indefinite: the factorisation
  // stops at a pivot (in the large separators or in the leaves).
  for (double shift : {-0.05, -3.0}) {
    const SparseMatrix lower = GridMatrix(30, 24, 3, shift);
    EXPECT_FALSE(Factor(lower).ok) << shift;
  }
  // Not a number in the matrix.
  SparseMatrix lower = GridMatrix(12, 9, 3, 0.05);
  lower.valuePtr()[lower.nonZeros() / 2] = std::nan("");
  EXPECT_FALSE(Factor(lower).ok);
}

TEST(SupernodalCholeskyTest, TheSameDigitsInAnyThread) {
  const SparseMatrix lower = GridMatrix(30, 24, 3, 0.05);
  const auto pattern = std::make_shared<const SupernodalPattern>(
      SupernodalCholesky::Analyse(lower));
  const SupernodalCholesky cholesky(pattern, lower);
  ASSERT_TRUE(cholesky.valid());
  const size_t size = static_cast<size_t>(pattern->values());
  std::vector<double> here(size), first(size), second(size);
  ASSERT_TRUE(cholesky.Factorize(lower, here.data()));
  // Two at once in other threads, the same object: the same bits.
  bool ok_first = false, ok_second = false;
  std::thread a([&] { ok_first = cholesky.Factorize(lower, first.data()); });
  std::thread b([&] { ok_second = cholesky.Factorize(lower, second.data()); });
  a.join();
  b.join();
  ASSERT_TRUE(ok_first && ok_second);
  // The unused upper halves of the triangles are zero in all three.
  EXPECT_EQ(first, here);
  EXPECT_EQ(second, here);
}

TEST(SupernodalCholeskyTest, AnotherPatternIsRejected) {
  const SparseMatrix lower = GridMatrix(12, 9, 3, 0.05);
  const auto pattern = std::make_shared<const SupernodalPattern>(
      SupernodalCholesky::Analyse(lower));
  const SupernodalPattern& p = *pattern;
  EXPECT_TRUE(SupernodalCholesky(pattern, lower).valid());
  // An entry outside the analysed L: in the permuted order, column c and a
  // row r > c that its supernode does not have; added to A at the
  // original indices.
  int r = -1, c = -1;
  for (int s = 0; s < p.supernodes() && r < 0; ++s) {
    const int* rows = p.rows.data() + p.row_begin[s];
    const long height = p.row_begin[s + 1] - p.row_begin[s];
    for (int candidate = p.first_column[s + 1]; candidate < p.size;
         ++candidate) {
      if (!std::binary_search(rows, rows + height, candidate)) {
        r = candidate;
        c = p.first_column[s];
        break;
      }
    }
  }
  ASSERT_GE(r, 0);
  const int i = p.perm[r], j = p.perm[c];
  SparseMatrix wider = lower;
  wider.coeffRef(std::max(i, j), std::min(i, j)) = 1e-3;
  wider.makeCompressed();
  EXPECT_FALSE(SupernodalCholesky(pattern, wider).valid());
  // Another size.
  EXPECT_FALSE(SupernodalCholesky(pattern, GridMatrix(12, 8, 3, 0.05)).valid());
}

}  // namespace
}  // namespace shellspace
