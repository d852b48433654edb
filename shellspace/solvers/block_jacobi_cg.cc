#include "shellspace/solvers/block_jacobi_cg.h"

#include <Eigen/CholmodSupport>

#include <algorithm>

#include "shellspace/runtime/parallel_for.h"
#include "shellspace/solvers/block_tridiagonal_product.h"

namespace shellspace {

using SparseMatrix = Eigen::SparseMatrix<double>;

struct BlockJacobiCg::Factors {
  std::vector<std::unique_ptr<
      Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>>>
      blocks;
};

BlockJacobiCg::BlockJacobiCg() : factors_(std::make_unique<Factors>()) {}
BlockJacobiCg::~BlockJacobiCg() = default;

namespace {

// The lower triangle of the diagonal block [begin, end) of `lower`
// (compressed columns, sorted rows), copied column by column into storage
// of the exact size (no triplets: on the cactus x16 a block has ~5M
// entries).
SparseMatrix DiagonalBlock(const SparseMatrix& lower, int begin, int end) {
  const int m = end - begin;
  const auto in_block = [&](int row, int c) { return row >= c && row < end; };
  SparseMatrix block(m, m);
  Eigen::Index count = 0;
  for (int c = begin; c < end; ++c) {
    for (SparseMatrix::InnerIterator it(lower, c); it; ++it) {
      count += in_block(static_cast<int>(it.row()), c);
    }
  }
  block.resizeNonZeros(count);
  int* outer = block.outerIndexPtr();
  int* inner = block.innerIndexPtr();
  double* values = block.valuePtr();
  int next = 0;
  for (int c = begin; c < end; ++c) {
    outer[c - begin] = next;
    for (SparseMatrix::InnerIterator it(lower, c); it; ++it) {
      if (!in_block(static_cast<int>(it.row()), c)) continue;
      inner[next] = static_cast<int>(it.row()) - begin;
      values[next] = it.value();
      ++next;
    }
  }
  outer[m] = next;
  return block;
}

}  // namespace

bool BlockJacobiCg::Factorize(const SparseMatrix& lower,
                              const std::vector<int>& offsets) {
  offsets_ = offsets;
  factors_->blocks.clear();
  time_coupled_ = false;
  const int blocks = static_cast<int>(offsets.size()) - 1;
  if (time_coupling_ && blocks > 0) {
    // Each block is copied out by the task that factorises it and freed
    // with it: at most `threads` copies at a time.
    const TimeCoupledPreconditioner::Status status = coupled_.Factorize(
        blocks,
        [&](int i, SparseMatrix* block) {
          *block = DiagonalBlock(lower, offsets[i], offsets[i + 1]);
        },
        threads_);
    if (status != TimeCoupledPreconditioner::Status::kDifferentPatterns) {
      stats_.factorizations += blocks;
      time_coupled_ = status == TimeCoupledPreconditioner::Status::kFactorized;
      if (time_coupled_) coupled_.FitCouplings(lower, threads_);
      return time_coupled_;
    }
  }
  std::vector<std::unique_ptr<
      Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>>>
      factors(std::max(blocks, 0));
  std::vector<char> positive(factors.size(), 0);
  ParallelFor(blocks, threads_, [&](int i) {
    auto llt = std::make_unique<
        Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>>();
    llt->cholmod().print = 0;  // an indefinite block is an answer
    llt->compute(DiagonalBlock(lower, offsets[i], offsets[i + 1]));
    positive[i] = llt->info() == Eigen::Success;
    factors[i] = std::move(llt);
  });
  stats_.factorizations += blocks;
  for (char p : positive) {
    if (!p) return false;
  }
  factors_->blocks = std::move(factors);
  return true;
}

Eigen::VectorXd BlockJacobiCg::ApplyPreconditioner(
    const Eigen::VectorXd& r) const {
  if (time_coupled_) return coupled_.Apply(r, threads_);
  Eigen::VectorXd z(r.size());
  ParallelFor(static_cast<int>(factors_->blocks.size()), threads_, [&](int i) {
    const int begin = offsets_[i], m = offsets_[i + 1] - offsets_[i];
    z.segment(begin, m) = factors_->blocks[i]->solve(r.segment(begin, m));
  });
  return z;
}

BlockJacobiCg::Status BlockJacobiCg::Solve(const SparseMatrix& lower,
                                           const Eigen::VectorXd& b,
                                           double tolerance,
                                           int max_iterations,
                                           Eigen::VectorXd* x,
                                           int* iterations, bool warm_start) {
  ++stats_.solves;
  int count = 0;
  if (iterations) *iterations = 0;
  if ((factors_->blocks.empty() && !time_coupled_) || offsets_.empty() ||
      offsets_.back() != lower.rows()) {
    return Status::kNotPositive;
  }
  // H d: in parallel over the slices (H couples neighbouring slices only).
  const auto h = [&](const Eigen::VectorXd& d) {
    return SymmetricProduct(lower, offsets_, d, threads_);
  };
  const double target = tolerance * b.norm();
  if (!warm_start || x->size() != b.size()) *x = ApplyPreconditioner(b);
  Eigen::VectorXd r = b - h(*x);
  Eigen::VectorXd z = ApplyPreconditioner(r);
  Eigen::VectorXd d = z;
  double rz = r.dot(z);
  Status status = r.norm() <= target ? Status::kSolved : Status::kNotConverged;
  while (status != Status::kSolved && count < max_iterations) {
    ++count;
    const Eigen::VectorXd hd = h(d);
    const double curvature = d.dot(hd);
    if (!(curvature > 0)) {
      status = Status::kNotPositive;
      break;
    }
    const double alpha = rz / curvature;
    *x += alpha * d;
    r -= alpha * hd;
    if (r.norm() <= target) {
      status = Status::kSolved;
      break;
    }
    z = ApplyPreconditioner(r);
    const double rz_next = r.dot(z);
    d = z + (rz_next / rz) * d;
    rz = rz_next;
  }
  stats_.cg_iterations += count;
  if (iterations) *iterations = count;
  return status;
}

}  // namespace shellspace
