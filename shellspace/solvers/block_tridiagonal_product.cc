#include "shellspace/solvers/block_tridiagonal_product.h"

#include <atomic>

#include "shellspace/runtime/parallel_for.h"

namespace shellspace {

bool BlockTridiagonalProduct(const Eigen::SparseMatrix<double>& lower,
                             const std::vector<int>& offsets,
                             const Eigen::VectorXd& d, int threads,
                             Eigen::VectorXd* y) {
  const int slices = static_cast<int>(offsets.size()) - 1;
  const int n = static_cast<int>(lower.rows());
  if (slices < 1 || offsets.front() != 0 || offsets.back() != n ||
      lower.cols() != n || d.size() != n) {
    return false;
  }
  for (int c = 0; c < slices; ++c) {
    if (offsets[c + 1] < offsets[c]) return false;
  }
  const int* outer = lower.outerIndexPtr();
  const int* inner = lower.innerIndexPtr();
  const int* nonzeros = lower.innerNonZeroPtr();  // null when compressed
  const double* value = lower.valuePtr();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
  // spill[c]: slice c's contribution to the rows of slice c + 1.
  std::vector<Eigen::VectorXd> spill(slices);
  std::atomic<bool> coupled_further(false);
  ParallelFor(slices, threads, [&](int c) {
    const int begin = offsets[c], end = offsets[c + 1];
    const int next_end = c + 1 < slices ? offsets[c + 2] : end;
    spill[c] = Eigen::VectorXd::Zero(next_end - end);
    double* own = out.data();
    double* next = spill[c].data();  // row i at next[i - end]
    for (int j = begin; j < end; ++j) {
      const double dj = d(j);
      double sum = 0;
      const int stop = nonzeros ? outer[j] + nonzeros[j] : outer[j + 1];
      // The column's rows ascend: above the diagonal (skipped), the
      // diagonal, rows of this slice, rows of the next.
      int p = outer[j];
      while (p < stop && inner[p] < j) ++p;
      if (p < stop && inner[p] == j) sum += value[p++] * dj;
      for (; p < stop && inner[p] < end; ++p) {
        const int i = inner[p];
        const double v = value[p];
        sum += v * d(i);
        own[i] += v * dj;
      }
      for (; p < stop && inner[p] < next_end; ++p) {
        const int i = inner[p];
        const double v = value[p];
        sum += v * d(i);
        next[i - end] += v * dj;
      }
      if (p < stop) {
        coupled_further = true;
        return;
      }
      own[j] += sum;
    }
  });
  if (coupled_further) return false;
  ParallelFor(slices - 1, threads, [&](int c) {
    out.segment(offsets[c + 1], offsets[c + 2] - offsets[c + 1]) += spill[c];
  });
  *y = std::move(out);
  return true;
}

Eigen::VectorXd SymmetricProduct(const Eigen::SparseMatrix<double>& lower,
                                 const std::vector<int>& offsets,
                                 const Eigen::VectorXd& d, int threads) {
  Eigen::VectorXd y;
  if (BlockTridiagonalProduct(lower, offsets, d, threads, &y)) return y;
  return lower.selfadjointView<Eigen::Lower>() * d;
}

}  // namespace shellspace
