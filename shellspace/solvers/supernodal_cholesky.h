// The numeric supernodal Cholesky factorisation P A P^T = L L^T of a
// symmetric matrix on the pattern of a symbolic analysis (a
// SupernodalPattern: CHOLMOD's fill-reducing ordering and supernodes).
//
// Left-looking, supernode after supernode in the pattern's order (a
// postorder of the supernodal elimination tree). Supernode s, columns c_s
// and rows R_s (c_s first), is one dense block B_s = L(R_s, c_s):
//   1. assembled: zero, then A's entries of its columns (a scatter map
//      computed once per input pattern);
//   2. updated by every descendant d with rows in c_s (the supernodes whose
//      next unprocessed rows fall in c_s, kept in one linked list per
//      supernode): with R = the rows of d from the first one in c_s on and
//      c = those of them in c_s,
//        B_s(R, c) -= L_d(R, :) L_d(c, :)^T,
//      one dense product per descendant, scattered through R's positions
//      in R_s;
//   3. factorised: its triangle L_ss L_ss^T = B_s(c_s, c_s) (dpotrf), the
//      rows below it B_s(below, c_s) L_ss^-T (dtrsm).
// Small blocks use plain loops instead of BLAS calls (whose overhead
// dominates a product of a few columns).
//
// The values go into a caller's buffer in CHOLMOD's layout (each
// supernode's block column-major from pattern.value_begin[s], the upper
// half of its triangle unused), which SupernodalFactor packs. Computed in
// double, without OpenMP and in a fixed order: the same bits for the same
// input, however many factorisations run at once in other threads.
#ifndef SHELLSPACE_SOLVERS_SUPERNODAL_CHOLESKY_H_
#define SHELLSPACE_SOLVERS_SUPERNODAL_CHOLESKY_H_

#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "shellspace/solvers/supernodal_factor.h"

namespace shellspace {

class SupernodalCholesky {
 public:
  // The symbolic analysis of `lower` (the lower triangle, compressed
  // columns, sorted): CHOLMOD's supernodal analysis with the ordering of
  // least fill among AMD and METIS' nested dissection (both
  // deterministic). Size 0 if it fails.
  static SupernodalPattern Analyse(const Eigen::SparseMatrix<double>& lower);

  // `lower`: the lower triangle (compressed columns, sorted) of a matrix
  // whose symbolic analysis is `pattern`; only its pattern is read, and
  // every matrix factorised later must have exactly that pattern. valid()
  // is false if an entry of it falls outside the analysed L.
  SupernodalCholesky(std::shared_ptr<const SupernodalPattern> pattern,
                     const Eigen::SparseMatrix<double>& lower);

  bool valid() const { return valid_; }
  const SupernodalPattern& pattern() const { return *pattern_; }

  // Factorises `lower` (the pattern given at construction) into `values`
  // (pattern().values() doubles, CHOLMOD's layout). Returns true if every
  // pivot was positive and finite; false at the first that is not (the
  // values are then unfinished). Thread-safe: the workspace is per call.
  bool Factorize(const Eigen::SparseMatrix<double>& lower,
                 double* values) const;

 private:
  std::shared_ptr<const SupernodalPattern> pattern_;
  std::vector<int> supernode_of_column_;
  // The input's entries grouped by supernode: entry source_[e] of the
  // input's values goes to values[target_[e]], for e in
  // [entry_begin_[s], entry_begin_[s + 1]) while supernode s is assembled.
  std::vector<long> entry_begin_;
  std::vector<long> target_;
  std::vector<int> source_;
  long input_nonzeros_ = 0;
  long largest_update_ = 0;  // the most values of one descendant's product
  bool valid_ = false;
};

}  // namespace shellspace

#endif  // SHELLSPACE_SOLVERS_SUPERNODAL_CHOLESKY_H_
