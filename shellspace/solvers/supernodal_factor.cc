#include "shellspace/solvers/supernodal_factor.h"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <utility>

#include "shellspace/runtime/heap_reuse.h"

namespace shellspace {

namespace {

// Supernode s of a pattern: its columns [first, first + columns), the
// `below` rows under its triangle (row[0 .. below)), its column-major
// block of `rows` = columns + below rows starting at value_begin in
// CHOLMOD's layout, and its packed columns starting at packed_begin:
// column j (rows - j values, its diagonal first) at packed_begin +
// Column(j).
struct Supernode {
  int first, columns;
  long rows, below, value_begin, packed_begin;
  const int* row;
  Supernode(const SupernodalPattern& p, int s)
      : first(p.first_column[s]),
        columns(p.first_column[s + 1] - p.first_column[s]),
        rows(p.row_begin[s + 1] - p.row_begin[s]),
        below(rows - columns),
        value_begin(p.value_begin[s]),
        packed_begin(p.packed_begin.empty() ? 0 : p.packed_begin[s]),
        row(p.rows.data() + p.row_begin[s] + columns) {}
  // Offset of packed column j: sum over i < j of (rows - i).
  long Column(long j) const { return j * rows - j * (j - 1) / 2; }
  long PackedValues() const { return Column(columns); }
};

}  // namespace

SupernodalPattern SupernodalPattern::Of(const cholmod_factor& factor) {
  SupernodalPattern pattern;
  if (!factor.is_super || factor.itype != CHOLMOD_INT) return pattern;
  const int n = static_cast<int>(factor.n);
  const int supernodes = static_cast<int>(factor.nsuper);
  const int* perm = static_cast<const int*>(factor.Perm);
  const int* super = static_cast<const int*>(factor.super);
  const int* pi = static_cast<const int*>(factor.pi);
  const int* px = static_cast<const int*>(factor.px);
  const int* s = static_cast<const int*>(factor.s);
  pattern.size = n;
  pattern.perm.assign(perm, perm + n);
  pattern.first_column.assign(super, super + supernodes + 1);
  pattern.row_begin.assign(pi, pi + supernodes + 1);
  pattern.value_begin.assign(px, px + supernodes + 1);
  pattern.rows.assign(s, s + pi[supernodes]);
  pattern.packed_begin.assign(supernodes + 1, 0);
  // The solves take a supernode's first rows to be its own columns.
  for (int k = 0; k < supernodes; ++k) {
    for (int j = 0; j < super[k + 1] - super[k]; ++j) {
      if (s[pi[k] + j] != super[k] + j) return SupernodalPattern();
    }
    const Supernode node(pattern, k);
    pattern.longest_below = std::max(pattern.longest_below, node.below);
    pattern.packed_begin[k + 1] =
        pattern.packed_begin[k] + node.PackedValues();
  }
  return pattern;
}

template <typename Stored>
void SupernodalFactor<Stored>::Free::operator()(Stored* p) const {
  std::free(p);
}

template <typename Stored>
bool SupernodalFactor<Stored>::ChooseScale(const double* values) {
  const SupernodalPattern& p = *pattern_;
  // A power of two near the largest |L_ij| of the stored lower parts (the
  // strict upper part of each diagonal triangle is not L).
  // (Branch-free: the loops vectorise. A NaN fails the comparison with
  // the largest double, as an infinity exceeds it.)
  constexpr double kLargest = std::numeric_limits<double>::max();
  double largest = 0;
  bool finite = true;
  for (int s = 0; s < p.supernodes(); ++s) {
    const Supernode node(p, s);
    const double* block = values + node.value_begin;
    for (int j = 0; j < node.columns; ++j) {
      const double* column = block + j + j * node.rows;
      const long length = node.rows - j;
      double column_largest = 0;
      bool column_finite = true;
      for (long i = 0; i < length; ++i) {
        const double a = std::abs(column[i]);
        column_largest = a > column_largest ? a : column_largest;
        column_finite &= a <= kLargest;
      }
      largest = std::max(largest, column_largest);
      finite = finite && column_finite;
    }
  }
  if (!finite || !(largest > 0)) return false;
  int exponent = 0;
  std::frexp(largest, &exponent);
  scale_ = std::ldexp(1.0, exponent);
  return true;
}

template <typename Stored>
bool SupernodalFactor<Stored>::Pack(const unsigned char* values,
                                    Stored* out) const {
  const SupernodalPattern& p = *pattern_;
  const double inverse_scale = 1 / scale_;  // exact: a power of two
  // Where out aliases values, a column is copied out first (memcpy: its
  // bytes may be overwritten by the packed values).
  const bool aliased = static_cast<const void*>(out) == values;
  std::vector<double> copy;
  bool positive = true;
  for (int s = 0; s < p.supernodes(); ++s) {
    const Supernode node(p, s);
    for (int j = 0; j < node.columns; ++j) {
      // Rows j .. rows - 1 of column j.
      const long length = node.rows - j;
      const unsigned char* bytes =
          values + sizeof(double) * static_cast<size_t>(node.value_begin + j +
                                                        j * node.rows);
      const double* column;
      if (aliased) {
        copy.resize(static_cast<size_t>(length));
        std::memcpy(copy.data(), bytes,
                    sizeof(double) * static_cast<size_t>(length));
        column = copy.data();
      } else {
        column = reinterpret_cast<const double*>(bytes);
      }
      Stored* packed = out + node.packed_begin + node.Column(j);
      for (long i = 0; i < length; ++i) {
        packed[i] = static_cast<Stored>(column[i] * inverse_scale);
      }
      positive = positive && packed[0] > 0 && std::isnormal(packed[0]);
    }
  }
  return positive;
}

template <typename Stored>
SupernodalFactor<Stored> SupernodalFactor<Stored>::TakeOver(
    std::shared_ptr<const SupernodalPattern> pattern, double* values) {
  SupernodalFactor factor;
  factor.pattern_ = std::move(pattern);
  if (!factor.pattern_ || factor.pattern_->size == 0 || values == nullptr ||
      !factor.ChooseScale(values)) {
    std::free(values);
    return factor;
  }
  unsigned char* bytes = reinterpret_cast<unsigned char*>(values);
  factor.valid_ = factor.Pack(bytes, reinterpret_cast<Stored*>(bytes));
  factor.value_count_ = factor.pattern_->packed_values();
  const size_t kept = sizeof(Stored) * static_cast<size_t>(factor.value_count_);
  void* shrunk = std::realloc(bytes, std::max<size_t>(kept, 1));
  factor.values_.reset(static_cast<Stored*>(shrunk ? shrunk : bytes));
  return factor;
}

template <typename Stored>
SupernodalFactor<Stored>::SupernodalFactor(
    std::shared_ptr<const SupernodalPattern> pattern, const double* values)
    : pattern_(std::move(pattern)) {
  if (!pattern_ || pattern_->size == 0 || values == nullptr ||
      !ChooseScale(values)) {
    return;
  }
  value_count_ = pattern_->packed_values();
  values_.reset(static_cast<Stored*>(MallocOnHugePages(std::max<size_t>(
      sizeof(Stored) * static_cast<size_t>(value_count_), 1))));
  if (!values_) {
    value_count_ = 0;
    return;
  }
  valid_ = Pack(reinterpret_cast<const unsigned char*>(values), values_.get());
}

namespace {

// sum_i a_i b_i in four interleaved partial sums (independent chains the
// compiler can vectorise; a fixed order, so the same bits every time).
template <typename Stored>
double Dot(const Stored* a, const double* b, long n) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  long i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += a[i] * b[i];
    s1 += a[i + 1] * b[i + 1];
    s2 += a[i + 2] * b[i + 2];
    s3 += a[i + 3] * b[i + 3];
  }
  for (; i < n; ++i) s0 += a[i] * b[i];
  return (s0 + s1) + (s2 + s3);
}

}  // namespace

// Forward substitution, supernode after supernode: the triangle gives the
// supernode's x, then the rectangle below it t = R x_s (column after
// column, contiguous: vectorised) is subtracted from the rows it names.
template <typename Stored>
void SupernodalFactor<Stored>::SolveLower(double* x) const {
  const SupernodalPattern& p = *pattern_;
  std::vector<double> t(static_cast<size_t>(p.longest_below));
  for (int s = 0; s < p.supernodes(); ++s) {
    const Supernode node(p, s);
    const int columns = node.columns;
    const long below = node.below;
    const Stored* block = values_.get() + node.packed_begin;
    double* xs = x + node.first;
    for (int j = 0; j < columns; ++j) {
      const Stored* column = block + node.Column(j);  // rows j, j + 1, ...
      const double xj = xs[j] / column[0];
      xs[j] = xj;
      for (int i = j + 1; i < columns; ++i) xs[i] -= column[i - j] * xj;
    }
    if (below == 0) continue;
    std::fill(t.begin(), t.begin() + below, 0.0);
    for (int j = 0; j < columns; ++j) {
      const Stored* column = block + node.Column(j) + (columns - j);
      const double xj = xs[j];
      for (long i = 0; i < below; ++i) t[i] += column[i] * xj;
    }
    for (long i = 0; i < below; ++i) x[node.row[i]] -= t[i];
  }
}

// Backward substitution in the reverse order: the rows below a supernode
// are final, gathered once into t, and each column's dot product with them
// is independent of the others; then the triangle from its last column up
// (x_j: its right-hand side minus the dot products, over the diagonal).
template <typename Stored>
void SupernodalFactor<Stored>::SolveLowerTransposed(double* x) const {
  const SupernodalPattern& p = *pattern_;
  std::vector<double> t(static_cast<size_t>(p.longest_below));
  for (int s = p.supernodes() - 1; s >= 0; --s) {
    const Supernode node(p, s);
    const int columns = node.columns;
    const long below = node.below;
    const Stored* block = values_.get() + node.packed_begin;
    double* xs = x + node.first;
    for (long i = 0; i < below; ++i) t[i] = x[node.row[i]];
    for (int j = 0; j < columns; ++j) {
      xs[j] -= Dot(block + node.Column(j) + (columns - j), t.data(), below);
    }
    for (int j = columns - 1; j >= 0; --j) {
      const Stored* column = block + node.Column(j);  // rows j, j + 1, ...
      xs[j] = (xs[j] - Dot(column + 1, xs + j + 1, columns - j - 1)) /
              column[0];
    }
  }
}

template <typename Stored>
Eigen::VectorXd SupernodalFactor<Stored>::Whiten(
    const Eigen::VectorXd& r) const {
  const SupernodalPattern& p = *pattern_;
  Eigen::VectorXd y(p.size);
  for (int k = 0; k < p.size; ++k) y(k) = r(p.perm[k]);
  SolveLower(y.data());
  y /= scale_;  // L = scale L~: L^-1 = L~^-1 / scale
  return y;
}

template <typename Stored>
Eigen::VectorXd SupernodalFactor<Stored>::Colour(
    const Eigen::VectorXd& z) const {
  const SupernodalPattern& p = *pattern_;
  Eigen::VectorXd w = z / scale_;
  SolveLowerTransposed(w.data());
  Eigen::VectorXd x(p.size);
  for (int k = 0; k < p.size; ++k) x(p.perm[k]) = w(k);
  return x;
}

template class SupernodalFactor<double>;
template class SupernodalFactor<float>;

}  // namespace shellspace
