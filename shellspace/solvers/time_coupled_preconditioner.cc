#include "shellspace/solvers/time_coupled_preconditioner.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cstdlib>
#include <random>

#include "shellspace/runtime/heap_reuse.h"
#include "shellspace/runtime/parallel_for.h"
#include "shellspace/solvers/supernodal_cholesky.h"
#include "shellspace/solvers/supernodal_factor.h"

namespace shellspace {

using SparseMatrix = Eigen::SparseMatrix<double>;

namespace {

// (H w)_j for a w that vanishes outside slice `from` = j - 1 or j + 1 (w_from
// its values there; slices of m rows): the coupling block between the two
// slices times w_from -- columns of the lower slice, rows of the upper one,
// in `lower`, H's lower triangle with rows ascending in each column. The
// same nonzero terms in the same order as BlockTridiagonalProduct's
// (whose other terms are products with the zeros of w): the same value.
Eigen::VectorXd CouplingProduct(const SparseMatrix& lower, int m, int j,
                                int from, const Eigen::VectorXd& w_from) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(m);
  const int column_slice = std::min(j, from);
  const int row_begin = (column_slice + 1) * m;
  const int row_end = row_begin + m;
  const int* outer = lower.outerIndexPtr();
  const int* inner = lower.innerIndexPtr();
  const int* nonzeros = lower.innerNonZeroPtr();  // null when compressed
  const double* value = lower.valuePtr();
  for (int c = 0; c < m; ++c) {
    const int column = column_slice * m + c;
    const int* first = inner + outer[column];
    const int* last = inner + (nonzeros ? outer[column] + nonzeros[column]
                                        : outer[column + 1]);
    // The column's rows in the other slice: a range of its ascending rows.
    const int* p = std::lower_bound(first, last, row_begin);
    const double* v = value + (p - inner);
    if (from < j) {  // H_{j, j-1} w_{j-1}: scatter column c into the rows
      const double wc = w_from(c);
      for (; p < last && *p < row_end; ++p, ++v) {
        out(*p - row_begin) += *v * wc;
      }
    } else {  // H_{j, j+1} w_{j+1} = (H_{j+1, j})^T w_{j+1}: gather
      double sum = 0;
      for (; p < last && *p < row_end; ++p, ++v) {
        sum += *v * w_from(*p - row_begin);
      }
      out(c) = sum;
    }
  }
  return out;
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


// The memory of the slices' factorisation (Factorize): a slice's packed
// factor keeps `kept` bytes, one in flight needs `in_flight`, and no wave
// needs more than `bound`, the last slice factorised alone.
struct WaveMemory {
  double kept = 0;
  double in_flight = 0;
  double bound = 0;
};

// The WaveMemory of `count` slices of `pattern`, packed in float if
// `single`.
WaveMemory WaveMemoryOf(const SupernodalPattern& pattern, bool single,
                        int count) {
  const double value_bytes = single ? sizeof(float) : sizeof(double);
  WaveMemory memory;
  memory.kept = value_bytes * static_cast<double>(pattern.packed_values());
  memory.in_flight = sizeof(double) * static_cast<double>(pattern.values());
  memory.bound = (count - 1) * memory.kept + memory.in_flight;
  return memory;
}

// The widths of the waves of up to `threads` slices: a wave of width w
// after `done` slices only if done kept + w in_flight <= bound.
std::vector<int> WaveWidths(int count, int threads, const WaveMemory& memory) {
  const double kept = memory.kept;
  const double in_flight = memory.in_flight;
  const double bound = memory.bound;
  std::vector<int> widths;
  for (int done = 0; done < count;) {
    int width = 1;
    while (width < threads && done + width < count &&
           done * kept + (width + 1) * in_flight <= bound) {
      ++width;
    }
    widths.push_back(width);
    done += width;
  }
  return widths;
}

// Whether no entry of `v` is 0.
bool AllSet(const std::vector<char>& v) {
  return std::all_of(v.begin(), v.end(), [](char c) { return c != 0; });
}

// A slice's double buffer in CHOLMOD's layout (MallocOnHugePages), freed
// with std::free.
struct FreeBuffer {
  void operator()(double* p) const { std::free(p); }
};
using Buffer = std::unique_ptr<double[], FreeBuffer>;

// The slices factorised on one analysed pattern, in the chosen precision:
// each slice's block from the source (slice 0 takes the analysed front
// over), factorised in a double buffer and packed; per slice, whether its
// block has the front's pattern and whether its factor is valid.
class SliceFactorization {
 public:
  SliceFactorization(int count, bool single,
                     const TimeCoupledPreconditioner::BlockSource& block_source,
                     const BlockPattern& front_pattern,
                     const SupernodalCholesky& cholesky,
                     const std::shared_ptr<const SupernodalPattern>& pattern,
                     SparseMatrix* front)
      : single_slices(single ? count : 0),
        full_slices(single ? 0 : count),
        valid(count, 0),
        same_pattern(count, 1),
        single_(single),
        block_source_(block_source),
        front_pattern_(front_pattern),
        cholesky_(cholesky),
        pattern_(pattern),
        front_(front),
        buffer_size_(sizeof(double) *
                     static_cast<size_t>(std::max(1L, pattern->values()))) {}

  // The slices in waves of `widths`: each wave's slot keeps its buffer for
  // the next wave's slot while a packed copy also fits in the bound.
  void RunWaves(const std::vector<int>& widths, const WaveMemory& memory) {
    const double kept = memory.kept;
    const double in_flight = memory.in_flight;
    const double bound = memory.bound;
    std::vector<Buffer> buffers;
    for (size_t wave = 0, done = 0; wave < widths.size(); ++wave) {
      const int width = widths[wave];
      const int next = wave + 1 < widths.size() ? widths[wave + 1] : 0;
      const bool copies_fit = done * kept + width * (in_flight + kept) <= bound;
      buffers.resize(width);
      ParallelFor(width, width, [&](int t) {
        FactorizeSlice(static_cast<int>(done) + t, &buffers[t],
                       copies_fit && t < next);
      });
      done += width;
    }
    buffers.clear();
  }

  std::vector<SupernodalFactor<float>> single_slices;
  std::vector<SupernodalFactor<double>> full_slices;
  std::vector<char> valid, same_pattern;

 private:
  // Slice i in `buffer`; `keep`: pack a copy and keep the buffer.
  void FactorizeSlice(int i, Buffer* buffer, bool keep) {
    SparseMatrix own_block;
    if (i > 0) {
      block_source_(i, &own_block);
      if (!front_pattern_.Of(own_block)) {
        same_pattern[i] = 0;
        return;
      }
    }
    // Slice 0 takes the analysed block over (its values are not needed
    // after its factorisation; the others compare with its pattern).
    if (i == 0) own_block = std::move(*front_);
    if (!*buffer) {
      buffer->reset(static_cast<double*>(MallocOnHugePages(buffer_size_)));
      if (!*buffer) return;
    }
    const bool factorized = cholesky_.Factorize(own_block, buffer->get());
    own_block = SparseMatrix();  // not needed for the packing
    if (!factorized) return;
    if (single_) {
      single_slices[i] =
          keep ? SupernodalFactor<float>(pattern_, buffer->get())
               : SupernodalFactor<float>::TakeOver(pattern_, buffer->release());
      valid[i] = single_slices[i].valid();
    } else {
      full_slices[i] = keep ? SupernodalFactor<double>(pattern_, buffer->get())
                            : SupernodalFactor<double>::TakeOver(
                                  pattern_, buffer->release());
      valid[i] = full_slices[i].valid();
    }
  }

  const bool single_;
  const TimeCoupledPreconditioner::BlockSource& block_source_;
  const BlockPattern& front_pattern_;
  const SupernodalCholesky& cholesky_;
  const std::shared_ptr<const SupernodalPattern>& pattern_;
  SparseMatrix* const front_;
  const size_t buffer_size_;
};

// 2 T_theta^-1 for T_theta = tridiag(-theta, 2, -theta).
Eigen::MatrixXd TwiceInverseTimeMatrix(const std::vector<double>& theta) {
  const int slices = static_cast<int>(theta.size()) + 1;
  Eigen::MatrixXd t = 2 * Eigen::MatrixXd::Identity(slices, slices);
  for (int i = 0; i + 1 < slices; ++i) t(i, i + 1) = t(i + 1, i) = -theta[i];
  return 2 * t.ldlt().solve(Eigen::MatrixXd::Identity(slices, slices));
}

}  // namespace

// The slices' factors, sharing one pattern, in the chosen precision, and
// the analysis they came from.
struct TimeCoupledPreconditioner::Factors {
  // The ordering and supernodes of one block pattern and the numeric
  // factorisation on them (SupernodalCholesky, with its scatter map of the
  // pattern), kept for the next Factorize of the same pattern: a
  // Newton or LM solve factorises one pattern at every refactorisation,
  // and a shifted retry again (the analysis is a deterministic function of
  // the pattern, so the factors are the same as with a fresh one).
  struct Analysis {
    explicit Analysis(const SparseMatrix& front)
        : of(front),
          pattern(std::make_shared<const SupernodalPattern>(
              SupernodalCholesky::Analyse(front))),
          cholesky(std::make_unique<const SupernodalCholesky>(pattern, front)) {
    }
    bool valid() const {
      return pattern->size == static_cast<int>(of.rows) && cholesky->valid();
    }

    const BlockPattern of;
    std::shared_ptr<const SupernodalPattern> pattern;
    std::unique_ptr<const SupernodalCholesky> cholesky;
  };

  std::shared_ptr<const SupernodalPattern> pattern;
  std::vector<SupernodalFactor<float>> single;
  std::vector<SupernodalFactor<double>> full;
  std::unique_ptr<Analysis> analysis;  // kept by Clear
  // The analysis of `front`'s pattern: the kept one if it is of that
  // pattern, else a fresh one; null (and none kept) if it is not valid.
  const Analysis* AnalysisOf(const SparseMatrix& front) {
    if (!analysis || !analysis->of.Of(front)) {
      analysis.reset();  // the old one is freed before the new one is made
      analysis = std::make_unique<Analysis>(front);
    }
    if (!analysis->valid()) {
      analysis.reset();
      return nullptr;
    }
    return analysis.get();
  }
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
  const Factors::Analysis* const analysis = factors_->AnalysisOf(front);
  if (analysis == nullptr) return Status::kNotPositive;
  const BlockPattern& front_pattern = analysis->of;
  std::shared_ptr<const SupernodalPattern> pattern = analysis->pattern;
  // Memory. A slice in flight needs a double buffer in CHOLMOD's layout
  // (`in_flight` bytes) and its packed factor `kept` bytes. The slices go
  // in waves of up to `threads`, a wave of width w after `done` slices only
  // if done kept + w in_flight <= (count - 1) kept + in_flight: the
  // factorisation never needs more memory than the last slice factorised
  // alone (cactus x16, 7 slices, 2 threads: waves of 2, 2, 1, 1, 1). Each
  // wave's slot keeps its buffer for the next wave's slot (fresh pages are
  // costly to touch: on the cactus 10-ring problem, zeroing them took a
  // third of the factorisation) and packs a copy, while that also fits in
  // the bound; a buffer not needed again is packed in place, its packed
  // factor taking it over (SupernodalFactor::TakeOver). The factors do not
  // depend on the waves.
  const bool single = precision_ == FactorPrecision::kSingle;
  const WaveMemory memory = WaveMemoryOf(*pattern, single, count);
  SliceFactorization slice_factors(count, single, block_source, front_pattern,
                                   *analysis->cholesky, pattern, &front);
  slice_factors.RunWaves(WaveWidths(count, threads, memory), memory);
  if (!AllSet(slice_factors.same_pattern)) return Status::kDifferentPatterns;
  if (!AllSet(slice_factors.valid)) return Status::kNotPositive;
  factors_->pattern = std::move(pattern);
  factors_->single = std::move(slice_factors.single_slices);
  factors_->full = std::move(slice_factors.full_slices);
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

int FitProbes(int block_size) {
  return block_size >= kOneFitProbeFromUnknowns ? 1 : 2;
}

void TimeCoupledPreconditioner::FitCouplings(const SparseMatrix& lower,
                                             int threads, int probes) {
  const int count = slices();
  const int m = block_size_;
  if (count < 2 || lower.rows() != static_cast<Eigen::Index>(count) * m) {
    return;
  }
  if (probes <= 0) probes = FitProbes(m);
  // Each probe z is used in three colourings: w = C^-T z on the slices
  // i = c (mod 3), zero elsewhere. A slice next to a coloured one has only
  // that neighbour coloured, so z^T C_j^-1 (H w)_j is the probe of the
  // single coupling between j and its coloured neighbour.
  std::vector<double> trace(count - 1, 0.0);
  std::vector<int> samples(count - 1, 0);
  std::vector<double> frobenius(count - 1, 0.0);
  std::mt19937 generator(20261202u);
  for (int probe = 0; probe < probes; ++probe) {
    Eigen::VectorXd z(m);
    for (int k = 0; k < m; ++k) z(k) = (generator() & 1u) ? 1.0 : -1.0;
    for (int colour = 0; colour < 3 && colour < count; ++colour) {
      std::vector<Eigen::VectorXd> w(count);  // C_i^-T z on coloured slices
      std::vector<int> coloured;
      for (int i = colour; i < count; i += 3) coloured.push_back(i);
      ParallelFor(static_cast<int>(coloured.size()), threads, [&](int c) {
        const int i = coloured[c];
        w[i] = Colour(i, z);
      });
      std::vector<double> value(count, 0.0), square(count, 0.0);
      std::vector<int> pair(count, -1);  // coupling index of slice j's probe
      for (int j = 0; j < count; ++j) {
        if (j % 3 == colour) continue;
        if (j > 0 && (j - 1) % 3 == colour) pair[j] = j - 1;
        if (j + 1 < count && (j + 1) % 3 == colour) pair[j] = j;
      }
      ParallelFor(count, threads, [&](int j) {
        if (pair[j] < 0) return;
        // (H w)_j: only the coupling to the coloured neighbour.
        const int from = pair[j] == j ? j + 1 : j - 1;
        const Eigen::VectorXd ez =
            Whiten(j, CouplingProduct(lower, m, j, from, w[from]));
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
