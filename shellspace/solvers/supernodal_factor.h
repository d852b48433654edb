// A supernodal Cholesky factor in CHOLMOD's pattern, stored in double or in
// single precision and solved in double precision: in single precision half
// the memory and half the memory traffic of CHOLMOD's factor (the solves of
// a preconditioner are bound by reading the factor).
#ifndef SHELLSPACE_SOLVERS_SUPERNODAL_FACTOR_H_
#define SHELLSPACE_SOLVERS_SUPERNODAL_FACTOR_H_

#include <Eigen/Core>
#include <memory>
#include <vector>

struct cholmod_factor_struct;  // CHOLMOD stays out of the public headers

namespace shellspace {

// The pattern of a supernodal factor P A P^T = L L^T (CHOLMOD's layout):
// supernode s holds the columns c = [first_column[s], first_column[s + 1])
// of L, nonzero in the rows rows[row_begin[s] .. row_begin[s + 1]) (the
// first |c| of them are c itself: a lower triangle on top of a rectangle),
// in CHOLMOD as one dense column-major block with one column per element of
// c, starting at value_begin[s]; in a SupernodalFactor packed: column j of
// the supernode holds its rows from j on only (its diagonal first), so the
// unused upper half of each diagonal triangle is not stored (13.7 % of the
// values on the cactus x16 slices), starting at packed_begin[s]. perm:
// (P b)_k = b_perm[k]. Every factor of one symbolic analysis shares it.
struct SupernodalPattern {
  int size = 0;
  std::vector<int> perm;
  std::vector<int> first_column;  // supernodes + 1
  std::vector<long> row_begin;    // supernodes + 1
  std::vector<long> value_begin;  // supernodes + 1 (CHOLMOD's layout)
  std::vector<long> packed_begin;  // supernodes + 1 (packed columns)
  std::vector<int> rows;
  long longest_below = 0;  // the most rows under one supernode's triangle

  int supernodes() const { return static_cast<int>(first_column.size()) - 1; }
  // Values in CHOLMOD's layout, and packed.
  long values() const { return value_begin.empty() ? 0 : value_begin.back(); }
  long packed_values() const {
    return packed_begin.empty() ? 0 : packed_begin.back();
  }
  // The pattern of a supernodal CHOLMOD factor (symbolic or numeric; int
  // indices); empty (size 0) for any other kind of factor.
  static SupernodalPattern Of(const cholmod_factor_struct& factor);
};

// L~ = scale * Stored(L / scale): L stored as `Stored` (double or float)
// after scaling by a power of two (the largest |L_ij| becomes O(1): in
// float nothing overflows and no diagonal underflows). The solves read the
// stored values and compute in double: Whiten(r) = L~^-1 P r and
// Colour(z) = P^T L~^-T z exactly up to double round-off, so P^T L~ L~^T P
// is symmetric positive definite (L~ lower triangular with a positive
// diagonal) whatever the rounding. In float, |L~ - L| <= 2^-24 |L| entrywise:
// a preconditioner that close to the double one. Deterministic: the order
// of the operations is fixed by the pattern.
template <typename Stored>
class SupernodalFactor {
 public:
  SupernodalFactor() = default;
  // Takes `values` over: pattern->values() doubles in CHOLMOD's layout (a
  // numeric L L^T of this pattern, e.g. SupernodalCholesky's) allocated with
  // std::malloc. They are converted in place and the buffer shrunk to this
  // factor's packed storage, so a slice never holds the double values and
  // their copy at once. valid() is false (the buffer freed) for a value not
  // finite or a diagonal entry not positive.
  static SupernodalFactor TakeOver(
      std::shared_ptr<const SupernodalPattern> pattern, double* values);
  // A copy of values in CHOLMOD's layout (pattern->values() of them).
  SupernodalFactor(std::shared_ptr<const SupernodalPattern> pattern,
                   const double* values);

  bool valid() const { return valid_; }
  int size() const { return pattern_ ? pattern_->size : 0; }
  // L~^-1 P r.
  Eigen::VectorXd Whiten(const Eigen::VectorXd& r) const;
  // P^T L~^-T z.
  Eigen::VectorXd Colour(const Eigen::VectorXd& z) const;
  // Bytes of the values (the pattern is shared).
  long value_bytes() const {
    return static_cast<long>(value_count_ * sizeof(Stored));
  }

 private:
  void SolveLower(double* x) const;            // x := L~^-1 x (unscaled)
  void SolveLowerTransposed(double* x) const;  // x := L~^-T x (unscaled)

  // The scale from values in CHOLMOD's layout; false if one is not finite
  // or all are zero.
  bool ChooseScale(const double* values);
  // values (CHOLMOD's layout, read through bytes) / scale_ into out
  // (packed); `out` may start at `values`: a column is read before its
  // packed copy is written, and packed positions never pass the unpacked
  // ones. False if a diagonal entry is not positive.
  bool Pack(const unsigned char* values, Stored* out) const;

  struct Free {
    void operator()(Stored* p) const;
  };
  std::shared_ptr<const SupernodalPattern> pattern_;
  std::unique_ptr<Stored[], Free> values_;  // L / scale_, packed columns
  long value_count_ = 0;
  double scale_ = 1;
  bool valid_ = false;
};

extern template class SupernodalFactor<double>;
extern template class SupernodalFactor<float>;

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_SUPERNODAL_FACTOR_H_
