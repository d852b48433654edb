#include "tests/testing/kronecker_model.h"

#include "shellspace/geometry/topology.h"
#include "tests/testing/test_support.h"

namespace shellspace::testing {

using SparseMatrix = Eigen::SparseMatrix<double>;

SparseMatrix PlateLaplacianMetric(double shift) {
  const Mesh m = LoadData("plate/plate121.ply");
  const Topology topology = Topology::Build(m);
  std::vector<Eigen::Triplet<double>> t;
  const int n = m.num_vertices();
  for (const auto& e : topology.edges) {
    for (int c = 0; c < 3; ++c) {
      t.emplace_back(3 * e[0] + c, 3 * e[0] + c, 1.0);
      t.emplace_back(3 * e[1] + c, 3 * e[1] + c, 1.0);
      t.emplace_back(3 * e[0] + c, 3 * e[1] + c, -1.0);
      t.emplace_back(3 * e[1] + c, 3 * e[0] + c, -1.0);
    }
  }
  for (int i = 0; i < 3 * n; ++i) t.emplace_back(i, i, shift);
  SparseMatrix g(3 * n, 3 * n);
  g.setFromTriplets(t.begin(), t.end());
  return g;
}

SparseMatrix KroneckerPathModel(const SparseMatrix& g, int K,
                                double diagonal_scale) {
  const int m = static_cast<int>(g.rows());
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < K - 1; ++i) {
    for (int c = 0; c < m; ++c) {
      for (SparseMatrix::InnerIterator it(g, c); it; ++it) {
        if (it.row() >= c) {
          t.emplace_back(i * m + it.row(), i * m + c,
                         2.0 * K * diagonal_scale * it.value());
        }
        if (i + 1 < K - 1) {
          t.emplace_back((i + 1) * m + it.row(), i * m + c,
                         -1.0 * K * it.value());
        }
      }
    }
  }
  SparseMatrix h((K - 1) * m, (K - 1) * m);
  h.setFromTriplets(t.begin(), t.end());
  return h;
}

std::vector<int> SliceOffsets(int blocks, int m) {
  std::vector<int> offsets;
  for (int i = 0; i <= blocks; ++i) offsets.push_back(i * m);
  return offsets;
}

}  // namespace shellspace::testing
