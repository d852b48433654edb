#include "shellspace/solvers/supernodal_cholesky.h"

#include <cholmod.h>

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

// The reference BLAS / LAPACK interface (OpenBLAS where it is installed,
// linked ahead; see cmake/shellspaceSystemLibraries.cmake).
extern "C" {
void dgemm_(const char* transa, const char* transb, const int* m, const int* n,
            const int* k, const double* alpha, const double* a, const int* lda,
            const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc);
void dtrsm_(const char* side, const char* uplo, const char* transa,
            const char* diag, const int* m, const int* n, const double* alpha,
            const double* a, const int* lda, double* b, const int* ldb);
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda,
             int* info);
}

namespace shellspace {

namespace {

// Below these sizes (multiply-adds of a product, columns of a triangle)
// plain loops beat a BLAS call's overhead.
constexpr long kBlasProductSize = 4096;
constexpr int kBlasTriangleColumns = 24;

// c (m x q, leading dimension m) = a (m x k) b (q x k)^T, a and b with
// leading dimension ld.
void Product(const double* a, const double* b, int m, int q, int k, int ld,
             double* c) {
  if (static_cast<long>(m) * q * k >= kBlasProductSize) {
    const double one = 1, zero = 0;
    dgemm_("N", "T", &m, &q, &k, &one, a, &ld, b, &ld, &zero, c, &m);
    return;
  }
  for (int j = 0; j < q; ++j) {
    double* cj = c + static_cast<long>(j) * m;
    std::fill(cj, cj + m, 0.0);
    for (int l = 0; l < k; ++l) {
      const double bjl = b[j + static_cast<long>(l) * ld];
      const double* al = a + static_cast<long>(l) * ld;
      for (int i = 0; i < m; ++i) cj[i] += al[i] * bjl;
    }
  }
}

// The lower triangle of the n x n block at a (leading dimension ld) becomes
// its Cholesky factor; false if a pivot is not positive and finite.
bool FactorTriangle(double* a, int n, int ld) {
  if (n >= kBlasTriangleColumns) {
    int info = 0;
    dpotrf_("L", &n, a, &ld, &info);
    return info == 0 && std::isfinite(a[0]);
  }
  for (int j = 0; j < n; ++j) {
    double* aj = a + static_cast<long>(j) * ld;
    // Column j minus the contributions of the columns before it.
    for (int l = 0; l < j; ++l) {
      const double* al = a + static_cast<long>(l) * ld;
      const double ajl = al[j];
      for (int i = j; i < n; ++i) aj[i] -= al[i] * ajl;
    }
    const double pivot = aj[j];
    if (!(pivot > 0) || !std::isfinite(pivot)) return false;
    const double root = std::sqrt(pivot);
    aj[j] = root;
    for (int i = j + 1; i < n; ++i) aj[i] /= root;
  }
  return true;
}

// b (m x n, leading dimension ld) := b l^-T for the n x n lower triangle l
// (leading dimension ld).
void SolveBelow(const double* l, int n, int ld, double* b, int m) {
  if (static_cast<long>(m) * n * n >= 2 * kBlasProductSize) {
    const double one = 1;
    dtrsm_("R", "L", "T", "N", &m, &n, &one, l, &ld, b, &ld);
    return;
  }
  for (int j = 0; j < n; ++j) {
    double* bj = b + static_cast<long>(j) * ld;
    for (int k = 0; k < j; ++k) {
      const double ljk = l[j + static_cast<long>(k) * ld];
      const double* bk = b + static_cast<long>(k) * ld;
      for (int i = 0; i < m; ++i) bj[i] -= bk[i] * ljk;
    }
    const double inverse = 1 / l[j + static_cast<long>(j) * ld];
    for (int i = 0; i < m; ++i) bj[i] *= inverse;
  }
}

}  // namespace

SupernodalPattern SupernodalCholesky::Analyse(
    const Eigen::SparseMatrix<double>& lower) {
  if (lower.rows() != lower.cols() || !lower.isCompressed()) {
    return SupernodalPattern();
  }
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  common.supernodal = CHOLMOD_SUPERNODAL;
  // On the cactus x4 slices (59,508 unknowns) METIS gives nnz(L) 13.0M
  // against AMD's 14.9M, a factorisation 0.97 s against 1.12 s; on small
  // slices AMD wins.
  common.nmethods = 2;
  common.method[0].ordering = CHOLMOD_AMD;
  common.method[1].ordering = CHOLMOD_METIS;
  cholmod_sparse view =
      Eigen::viewAsCholmod(lower.selfadjointView<Eigen::Lower>());
  cholmod_factor* symbolic = cholmod_analyze(&view, &common);
  SupernodalPattern pattern =
      symbolic ? SupernodalPattern::Of(*symbolic) : SupernodalPattern();
  if (symbolic) cholmod_free_factor(&symbolic, &common);
  cholmod_finish(&common);
  return pattern;
}

SupernodalCholesky::SupernodalCholesky(
    std::shared_ptr<const SupernodalPattern> pattern,
    const Eigen::SparseMatrix<double>& lower)
    : pattern_(std::move(pattern)) {
  if (!pattern_ || pattern_->size == 0 || lower.rows() != pattern_->size ||
      lower.cols() != pattern_->size || !lower.isCompressed()) {
    return;
  }
  const SupernodalPattern& p = *pattern_;
  const int n = p.size;
  const int supernodes = p.supernodes();
  supernode_of_column_.assign(n, -1);
  int widest = 0;
  for (int s = 0; s < supernodes; ++s) {
    for (int c = p.first_column[s]; c < p.first_column[s + 1]; ++c) {
      supernode_of_column_[c] = s;
    }
    widest = std::max(widest, p.first_column[s + 1] - p.first_column[s]);
  }
  largest_update_ = std::max<long>(1, p.longest_below * widest);
  std::vector<int> position(n);  // perm[position[i]] = i
  for (int k = 0; k < n; ++k) position[p.perm[k]] = k;
  // Each entry's place in L: column c = min, row r = max of the permuted
  // indices, in supernode s = supernode_of_column_[c].
  input_nonzeros_ = lower.nonZeros();
  std::vector<int> supernode_of_entry(input_nonzeros_);
  std::vector<long> target(input_nonzeros_);
  for (int j = 0; j < n; ++j) {
    for (int e = lower.outerIndexPtr()[j]; e < lower.outerIndexPtr()[j + 1];
         ++e) {
      const int a = position[lower.innerIndexPtr()[e]], b = position[j];
      const int r = std::max(a, b), c = std::min(a, b);
      const int s = supernode_of_column_[c];
      if (s < 0) return;
      const int* rows_begin = p.rows.data() + p.row_begin[s];
      const int* rows_end = p.rows.data() + p.row_begin[s + 1];
      const int* found = std::lower_bound(rows_begin, rows_end, r);
      if (found == rows_end || *found != r) return;  // not in L's pattern
      const long height = p.row_begin[s + 1] - p.row_begin[s];
      supernode_of_entry[e] = s;
      target[e] = p.value_begin[s] + (found - rows_begin) +
                  static_cast<long>(c - p.first_column[s]) * height;
    }
  }
  // Grouped by supernode (a counting sort: within a supernode, input order).
  entry_begin_.assign(supernodes + 1, 0);
  for (int s : supernode_of_entry) ++entry_begin_[s + 1];
  std::partial_sum(entry_begin_.begin(), entry_begin_.end(),
                   entry_begin_.begin());
  std::vector<long> next(entry_begin_.begin(), entry_begin_.end() - 1);
  target_.resize(input_nonzeros_);
  source_.resize(input_nonzeros_);
  for (long e = 0; e < input_nonzeros_; ++e) {
    const long slot = next[supernode_of_entry[e]]++;
    target_[slot] = target[e];
    source_[slot] = static_cast<int>(e);
  }
  valid_ = true;
}

bool SupernodalCholesky::Factorize(const Eigen::SparseMatrix<double>& lower,
                                   double* values) const {
  if (!valid_ || lower.nonZeros() != input_nonzeros_) return false;
  const SupernodalPattern& p = *pattern_;
  const int supernodes = p.supernodes();
  const double* input = lower.valuePtr();
  // Per call: where each row of the supernode being formed sits in it,
  // the descendants waiting for each supernode (head / link), the next
  // unprocessed row of each (as an index into its rows), and the product.
  std::vector<int> place(p.size, 0);
  std::vector<int> head(supernodes, -1), link(supernodes, -1);
  std::vector<long> next_row(supernodes, 0);
  std::vector<double> product(static_cast<size_t>(largest_update_));
  for (int s = 0; s < supernodes; ++s) {
    const int first = p.first_column[s];
    const int columns = p.first_column[s + 1] - first;
    const long begin = p.row_begin[s];
    const int height = static_cast<int>(p.row_begin[s + 1] - begin);
    const int* rows = p.rows.data() + begin;
    double* block = values + p.value_begin[s];
    // 1. Assembly.
    std::fill(block, block + static_cast<long>(height) * columns, 0.0);
    for (long e = entry_begin_[s]; e < entry_begin_[s + 1]; ++e) {
      values[target_[e]] = input[source_[e]];
    }
    for (int i = 0; i < height; ++i) place[rows[i]] = i;
    // 2. Updates from the descendants waiting for s.
    for (int d = head[s]; d >= 0;) {
      const int following = link[d];
      const long d_begin = p.row_begin[d];
      const int d_height = static_cast<int>(p.row_begin[d + 1] - d_begin);
      const int d_columns = p.first_column[d + 1] - p.first_column[d];
      const int* d_rows = p.rows.data() + d_begin;
      const int from = static_cast<int>(next_row[d]);
      int in_s = from;  // d's rows in s's columns: [from, in_s)
      while (in_s < d_height && d_rows[in_s] < first + columns) ++in_s;
      const int m = d_height - from, q = in_s - from;
      const double* d_block = values + p.value_begin[d] + from;
      Product(d_block, d_block, m, q, d_columns, d_height, product.data());
      for (int j = 0; j < q; ++j) {
        double* column =
            block + static_cast<long>(d_rows[from + j] - first) * height;
        const double* update = product.data() + static_cast<long>(j) * m;
        for (int i = j; i < m; ++i)
          column[place[d_rows[from + i]]] -= update[i];
      }
      next_row[d] = in_s;
      if (in_s < d_height) {  // on to the supernode of its next row
        const int t = supernode_of_column_[d_rows[in_s]];
        link[d] = head[t];
        head[t] = d;
      }
      d = following;
    }
    // 3. The triangle, then the rows below it.
    if (!FactorTriangle(block, columns, height)) return false;
    if (height > columns) {
      SolveBelow(block, columns, height, block + columns, height - columns);
      const int t = supernode_of_column_[rows[columns]];
      next_row[s] = columns;
      link[s] = head[t];
      head[t] = s;
    }
  }
  return true;
}

}  // namespace shellspace
