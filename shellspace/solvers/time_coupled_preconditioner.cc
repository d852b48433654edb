#include "shellspace/solvers/time_coupled_preconditioner.h"

#include <cholmod.h>

#include <algorithm>
#include <cstring>
#include <random>

#include <Eigen/Cholesky>

#include "shellspace/runtime/parallel_for.h"
#include "shellspace/solvers/block_tridiagonal_product.h"
#include "shellspace/solvers/supernodal_factor.h"

namespace shellspace {

using SparseMatrix = Eigen::SparseMatrix<double>;

namespace {

// CHOLMOD's view of the lower triangle of a compressed, sorted block.
cholmod_sparse LowerView(const SparseMatrix& block) {
  cholmod_sparse view;
  std::memset(&view, 0, sizeof(view));
  view.nrow = block.rows();
  view.ncol = block.cols();
  view.nzmax = block.nonZeros();
  view.p = const_cast<int*>(block.outerIndexPtr());
  view.i = const_cast<int*>(block.innerIndexPtr());
  view.x = const_cast<double*>(block.valuePtr());
  view.stype = -1;  // symmetric, lower triangle stored
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  return view;
}

// The sparsity pattern of a compressed block, without its values.
struct BlockPattern {
  Eigen::Index rows = 0;
  std::vector<int> outer, inner;
  explicit BlockPattern(const SparseMatrix& a)
      : rows(a.rows()),
        outer(a.outerIndexPtr(), a.outerIndexPtr() + a.cols() + 1),
        inner(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros()) {}
  bool Of(const SparseMatrix& a) const {
    return a.rows() == rows &&
           a.cols() + 1 == static_cast<Eigen::Index>(outer.size()) &&
           a.nonZeros() == static_cast<Eigen::Index>(inner.size()) &&
           std::equal(outer.begin(), outer.end(), a.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), a.innerIndexPtr());
  }
};


// 2 T_theta^-1 for T_theta = tridiag(-theta, 2, -theta).
Eigen::MatrixXd TwiceInverseTimeMatrix(const std::vector<double>& theta) {
  const int slices = static_cast<int>(theta.size()) + 1;
  Eigen::MatrixXd t = 2 * Eigen::MatrixXd::Identity(slices, slices);
  for (int i = 0; i + 1 < slices; ++i) t(i, i + 1) = t(i + 1, i) = -theta[i];
  return 2 * t.ldlt().solve(Eigen::MatrixXd::Identity(slices, slices));
}

}  // namespace

// The slices' factors, sharing one pattern, in the chosen precision (the
// CHOLMOD factors are released as soon as they are copied), and the
// symbolic analysis they came from.
struct TimeCoupledPreconditioner::Factors {
  // The ordering and supernodes of one block pattern (cholmod_analyze),
  // kept for the next Factorize of the same pattern: a Newton or LM solve
  // factorises one pattern at every refactorisation, and a shifted retry
  // again (the analysis is a deterministic function of the pattern, so
  // the factors are the same as with a fresh one).
  struct Analysis {
    explicit Analysis(const SparseMatrix& front) : of(front) {
      cholmod_start(&common);
      common.print = 0;
      common.supernodal = CHOLMOD_SUPERNODAL;
      // The ordering with the least fill of AMD and METIS' nested
      // dissection (on the cactus x4 slices, 59,508 unknowns: nnz(L) 14.9M
      // AMD, 13.0M METIS, factorisation 1.12 s against 0.97 s; on small
      // slices AMD wins). Both are deterministic.
      common.nmethods = 2;
      common.method[0].ordering = CHOLMOD_AMD;
      common.method[1].ordering = CHOLMOD_METIS;
      cholmod_sparse first = LowerView(front);
      symbolic = cholmod_analyze(&first, &common);
      pattern = std::make_shared<const SupernodalPattern>(
          symbolic ? SupernodalPattern::Of(*symbolic) : SupernodalPattern());
    }
    ~Analysis() {
      if (symbolic) cholmod_free_factor(&symbolic, &common);
      cholmod_finish(&common);
    }
    Analysis(const Analysis&) = delete;
    Analysis& operator=(const Analysis&) = delete;
    bool valid() const {
      return symbolic != nullptr && pattern->size == static_cast<int>(of.rows);
    }

    const BlockPattern of;
    cholmod_common common;
    cholmod_factor* symbolic = nullptr;
    std::shared_ptr<const SupernodalPattern> pattern;
  };

  std::shared_ptr<const SupernodalPattern> pattern;
  std::vector<SupernodalFactor<float>> single;
  std::vector<SupernodalFactor<double>> full;
  std::unique_ptr<Analysis> analysis;  // kept by Clear
  void Clear() {
    single.clear();
    full.clear();
    pattern.reset();
  }
};

TimeCoupledPreconditioner::TimeCoupledPreconditioner()
    : factors_(std::make_unique<Factors>()) {}
TimeCoupledPreconditioner::~TimeCoupledPreconditioner() = default;

TimeCoupledPreconditioner::Status TimeCoupledPreconditioner::Factorize(
    const std::vector<SparseMatrix>& blocks, int threads) {
  const BlockPattern first(blocks.empty() ? SparseMatrix() : blocks.front());
  for (const SparseMatrix& block : blocks) {
    if (!first.Of(block)) {
      factors_->Clear();
      mixing_.resize(0, 0);
      block_size_ = 0;
      return Status::kDifferentPatterns;
    }
  }
  return Factorize(
      static_cast<int>(blocks.size()),
      [&](int i, SparseMatrix* block) { *block = blocks[i]; }, threads);
}

TimeCoupledPreconditioner::Status TimeCoupledPreconditioner::Factorize(
    int count, const BlockSource& block_source, int threads) {
  factors_->Clear();
  mixing_.resize(0, 0);
  block_size_ = 0;
  if (count <= 0) return Status::kDifferentPatterns;
  SparseMatrix front;
  block_source(0, &front);
  // The ordering and the supernodes of the common pattern: once for all
  // slices, and kept while the pattern stays.
  std::unique_ptr<Factors::Analysis>& analysis = factors_->analysis;
  if (!analysis || !analysis->of.Of(front)) {
    analysis.reset();  // the old one is freed before the new one is made
    analysis = std::make_unique<Factors::Analysis>(front);
  }
  if (!analysis->valid()) {
    analysis.reset();
    return Status::kNotPositive;
  }
  const BlockPattern& front_pattern = analysis->of;
  const cholmod_factor* const symbolic = analysis->symbolic;
  const std::shared_ptr<const SupernodalPattern> pattern = analysis->pattern;
  // Each slice: a copy of the symbolic factor, factorised, converted, freed.
  // A cholmod_common is not shared between threads.
  const bool single = precision_ == FactorPrecision::kSingle;
  std::vector<SupernodalFactor<float>> single_slices(single ? count : 0);
  std::vector<SupernodalFactor<double>> full_slices(single ? 0 : count);
  std::vector<char> valid(count, 0), same_pattern(count, 1);
  const auto factorize_slice = [&](int i) {
    SparseMatrix own_block;
    if (i > 0) {
      block_source(i, &own_block);
      if (!front_pattern.Of(own_block)) {
        same_pattern[i] = 0;
        return;
      }
    }
    // Slice 0 takes the analysed block over (its values are not needed
    // after its factorisation; the others compare with its pattern).
    if (i == 0) own_block = std::move(front);
    const SparseMatrix& block = own_block;
    cholmod_common own;
    cholmod_start(&own);
    own.print = 0;  // an indefinite block is an answer
    own.supernodal = CHOLMOD_SUPERNODAL;
    own.final_asis = 1;  // keep the supernodal L L^T
    cholmod_factor* factor =
        cholmod_copy_factor(const_cast<cholmod_factor*>(symbolic), &own);
    cholmod_sparse view = LowerView(block);
    const bool factorized = factor && cholmod_factorize(&view, factor, &own);
    own_block = SparseMatrix();  // not needed for the copy
    if (factorized && own.status == CHOLMOD_OK && factor->minor == factor->n) {
      if (single) {
        single_slices[i] = SupernodalFactor<float>(pattern, factor);
        valid[i] = single_slices[i].valid();
      } else {
        full_slices[i] = SupernodalFactor<double>(pattern, factor);
        valid[i] = full_slices[i].valid();
      }
    }
    if (factor) cholmod_free_factor(&factor, &own);
    cholmod_finish(&own);
  };
  // In waves of up to `threads` slices. A slice in flight holds CHOLMOD's
  // factor (double, CHOLMOD's layout: `in_flight` bytes), which becomes its
  // packed copy in place (SupernodalFactor), `kept` bytes, when done. A
  // wave of width w starts after `done` slices only if done kept + w
  // in_flight <= (count - 1) kept + in_flight: the factorisation never
  // needs more memory than the last slice factorised alone (cactus x16, 7
  // slices, 2 threads: waves of 2, 2, 1, 1, 1). The factors do not depend
  // on the waves.
  const double value_bytes = single ? sizeof(float) : sizeof(double);
  const double kept =
      value_bytes * static_cast<double>(pattern->packed_values());
  const double in_flight =
      sizeof(double) * static_cast<double>(pattern->values());
  const double bound = (count - 1) * kept + in_flight;
  for (int done = 0; done < count;) {
    int width = 1;
    while (width < threads && done + width < count &&
           done * kept + (width + 1) * in_flight <= bound) {
      ++width;
    }
    ParallelFor(width, width, [&](int t) { factorize_slice(done + t); });
    done += width;
  }
  const auto all = [](const std::vector<char>& v) {
    return std::all_of(v.begin(), v.end(), [](char c) { return c != 0; });
  };
  if (!all(same_pattern)) return Status::kDifferentPatterns;
  if (!all(valid)) return Status::kNotPositive;
  factors_->pattern = std::move(pattern);
  factors_->single = std::move(single_slices);
  factors_->full = std::move(full_slices);
  block_size_ = static_cast<int>(front_pattern.rows);
  SetCouplings(std::vector<double>(count - 1, 1.0));
  return Status::kFactorized;
}

void TimeCoupledPreconditioner::SetCouplings(const std::vector<double>& theta) {
  theta_ = theta;
  mixing_ = TwiceInverseTimeMatrix(theta_);
}

Eigen::VectorXd TimeCoupledPreconditioner::Whiten(
    int slice, const Eigen::VectorXd& r) const {
  return factors_->single.empty() ? factors_->full[slice].Whiten(r)
                                  : factors_->single[slice].Whiten(r);
}

Eigen::VectorXd TimeCoupledPreconditioner::Colour(
    int slice, const Eigen::VectorXd& z) const {
  return factors_->single.empty() ? factors_->full[slice].Colour(z)
                                  : factors_->single[slice].Colour(z);
}

void TimeCoupledPreconditioner::FitCouplings(const SparseMatrix& lower,
                                             int threads, int probes) {
  const int count = slices();
  const int m = block_size_;
  if (count < 2 || lower.rows() != static_cast<Eigen::Index>(count) * m) {
    return;
  }
  // Each probe z is used in three colourings: w = C^-T z on the slices
  // i = c (mod 3), zero elsewhere. A slice next to a coloured one has only
  // that neighbour coloured, so z^T C_j^-1 (H w)_j is the probe of the
  // single coupling between j and its coloured neighbour.
  std::vector<double> trace(count - 1, 0.0);
  std::vector<int> samples(count - 1, 0);
  std::vector<double> frobenius(count - 1, 0.0);
  std::vector<int> offsets(count + 1);
  for (int i = 0; i <= count; ++i) offsets[i] = i * m;
  std::mt19937 generator(20261202u);
  for (int probe = 0; probe < probes; ++probe) {
    Eigen::VectorXd z(m);
    for (int k = 0; k < m; ++k) z(k) = (generator() & 1u) ? 1.0 : -1.0;
    for (int colour = 0; colour < 3 && colour < count; ++colour) {
      Eigen::VectorXd w = Eigen::VectorXd::Zero(lower.rows());
      std::vector<int> coloured;
      for (int i = colour; i < count; i += 3) coloured.push_back(i);
      ParallelFor(static_cast<int>(coloured.size()), threads, [&](int c) {
        const int i = coloured[c];
        w.segment(static_cast<Eigen::Index>(i) * m, m) = Colour(i, z);
      });
      const Eigen::VectorXd hw = SymmetricProduct(lower, offsets, w, threads);
      std::vector<double> value(count, 0.0), square(count, 0.0);
      std::vector<int> pair(count, -1);  // coupling index of slice j's probe
      for (int j = 0; j < count; ++j) {
        if (j % 3 == colour) continue;
        if (j > 0 && (j - 1) % 3 == colour) pair[j] = j - 1;
        if (j + 1 < count && (j + 1) % 3 == colour) pair[j] = j;
      }
      ParallelFor(count, threads, [&](int j) {
        if (pair[j] < 0) return;
        const Eigen::VectorXd ez =
            Whiten(j, hw.segment(static_cast<Eigen::Index>(j) * m, m));
        value[j] = z.dot(ez);
        square[j] = ez.squaredNorm();
      });
      for (int j = 0; j < count; ++j) {
        if (pair[j] < 0) continue;
        trace[pair[j]] += value[j];
        frobenius[pair[j]] += square[j];
        ++samples[pair[j]];
      }
    }
  }
  std::vector<double> theta(count - 1, 1.0);
  for (int i = 0; i + 1 < count; ++i) {
    if (samples[i] == 0) continue;
    const double mean_trace = trace[i] / samples[i];
    theta[i] = std::clamp(-2.0 * mean_trace / m, 0.0, 1.0);
    // The part of the coupling the model does not explain, relative to
    // the model: |E_i + theta_i I / 2|_F^2 / |theta_i I / 2|_F^2.
    const double model = theta[i] * theta[i] / 4;
    const double misfit = frobenius[i] / samples[i] / m - model;
    if (!(misfit <= kMaxCouplingMisfit * model)) theta[i] = 0;
  }
  SetCouplings(theta);
}

Eigen::VectorXd TimeCoupledPreconditioner::Apply(const Eigen::VectorXd& r,
                                                 int threads) const {
  const int count = slices();
  const int m = block_size_;
  Eigen::MatrixXd y(m, count);  // column i: L_i^-1 P r_i
  ParallelFor(count, threads, [&](int i) {
    y.col(i) = Whiten(i, r.segment(static_cast<Eigen::Index>(i) * m, m));
  });
  const Eigen::MatrixXd z = y * mixing_;  // z_i = sum_j (2 T^-1)_ji y_j
  Eigen::VectorXd x(r.size());
  ParallelFor(count, threads, [&](int i) {
    x.segment(static_cast<Eigen::Index>(i) * m, m) = Colour(i, z.col(i));
  });
  return x;
}

}  // namespace shellspace
