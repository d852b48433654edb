#include "shellspace/problems/calculus/path_hessian.h"

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "shellspace/cost_functions/shell/element_set.h"
#include "shellspace/geometry/locality_order.h"
#include "shellspace/runtime/parallel_for.h"

namespace shellspace {

namespace {

// The columns of T_k on one vertex: `count` consecutive columns starting at
// `first`, t = the 3 x count block (column-major).
struct VertexColumns {
  int first = -1;
  int count = 0;
  double t[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  bool identity = false;  // count 3 and t = I (a free vertex of a mask)
};

std::vector<VertexColumns> VertexLayout(const Eigen::SparseMatrix<double>& basis,
                                        int num_vertices, int offset) {
  std::vector<VertexColumns> layout(num_vertices);
  for (int c = 0; c < basis.outerSize(); ++c) {
    Eigen::SparseMatrix<double>::InnerIterator it(basis, c);
    if (!it) throw std::logic_error("PathHessianAssembler: empty basis column");
    VertexColumns& vc = layout[it.row() / 3];
    if (vc.first < 0) vc.first = offset + c;
    if (vc.first + vc.count != offset + c || vc.count == 3) {
      throw std::logic_error(
          "PathHessianAssembler: basis columns not grouped by vertex");
    }
    for (; it; ++it) vc.t[3 * vc.count + it.row() % 3] = it.value();
    ++vc.count;
  }
  for (VertexColumns& vc : layout) {
    vc.identity = vc.count == 3;
    for (int e = 0; e < 9; ++e) {
      vc.identity = vc.identity && vc.t[e] == (e % 4 == 0 ? 1.0 : 0.0);
    }
  }
  return layout;
}

// (T_v^T B T_w)(i, j) for a row-major 3 x 3 block B (B(i, j) itself where
// both are the identity: the same value as the sum below, whose other
// terms are exact zeros, for finite B).
double ReducedEntry(const VertexColumns& v, int i, const double* b,
                    const VertexColumns& w, int j) {
  if (v.identity && w.identity) return b[3 * i + j];
  double sum = 0;
  for (int r = 0; r < 3; ++r) {
    const double tv = v.t[3 * i + r];
    if (tv == 0) continue;
    for (int s = 0; s < 3; ++s) sum += tv * b[3 * r + s] * w.t[3 * j + s];
  }
  return sum;
}

// Builds a compressed column-major matrix from traversals of its columns:
// the columns come in parts, consecutive ranges [first_column[q],
// first_column[q + 1]), and walk(q, sink) visits part q's columns in order,
// calling sink.Column() at the start of every column and sink.Entry(row,
// value) for each of its entries. Every part is walked twice -- counting
// (Sink::kValues false: values are not needed, and `walk` may skip
// computing them), then filling storage allocated to the exact count (or
// the old storage of *out, if it is large enough) -- so the result is
// written in place, with no growing buffers and no copy (on the cactus x4
// one path Hessian is about 0.3 GB). The parts are walked in
// parallel (`threads` at a time), each into its own range of the storage:
// the result does not depend on the thread count.
struct CountingSink {
  static constexpr bool kValues = false;
  std::vector<int>* outer;
  int nonzeros = 0;
  void Column() { outer->push_back(nonzeros); }
  void Entry(int /*row*/, double /*value*/) { ++nonzeros; }
};
struct FillingSink {
  static constexpr bool kValues = true;
  int* inner;
  double* values;
  int next = 0;
  void Column() {}
  void Entry(int row, double value) {
    inner[next] = row;
    values[next] = value;
    ++next;
  }
};
template <typename Walk>
void BuildCompressed(int rows, const std::vector<int>& first_column,
                     int threads, const Walk& walk,
                     Eigen::SparseMatrix<double>* out) {
  const int parts = static_cast<int>(first_column.size()) - 1;
  const int cols = first_column.back();
  std::vector<std::vector<int>> starts(parts);  // per part, per column
  std::vector<long> counts(parts, 0);
  ParallelFor(parts, threads, [&](int q) {
    const int columns = first_column[q + 1] - first_column[q];
    starts[q].reserve(columns);
    CountingSink count{&starts[q]};
    walk(q, count);
    if (static_cast<int>(starts[q].size()) != columns) {
      throw std::logic_error("PathHessianAssembler: column count mismatch");
    }
    counts[q] = count.nonzeros;
  });
  long total = 0;
  for (long c : counts) total += c;
  if (total > std::numeric_limits<int>::max()) {
    throw std::length_error("PathHessianAssembler: more than 2^31 nonzeros");
  }
  // The old storage is reused where it is large enough (a Newton solve
  // assembles the same pattern every iteration: no fresh pages to fault in
  // and clear); otherwise it is released first, so that the old and the
  // new matrix never exist together.
  if (out->data().allocatedSize() < total) *out = Eigen::SparseMatrix<double>();
  out->resize(rows, cols);
  out->resizeNonZeros(static_cast<Eigen::Index>(total));
  int* outer = out->outerIndexPtr();
  int base = 0;
  for (int q = 0; q < parts; ++q) {
    for (size_t c = 0; c < starts[q].size(); ++c) {
      outer[first_column[q] + c] = base + starts[q][c];
    }
    base += static_cast<int>(counts[q]);
    std::vector<int>().swap(starts[q]);
  }
  outer[cols] = base;
  ParallelFor(parts, threads, [&](int q) {
    FillingSink fill{out->innerIndexPtr(), out->valuePtr(),
                     outer[first_column[q]]};
    walk(q, fill);
  });
}

// Starts column `column` of a BuildCompressed walk: the jw-th column of
// vertex w (its layout cw); the bases' columns must come in vertex order.
template <typename Sink>
void StartColumn(const VertexColumns& cw, int jw, int column, Sink& sink) {
  if (cw.first + jw != column) {
    throw std::logic_error(
        "PathHessianAssembler: basis columns not in vertex order");
  }
  sink.Column();
}

// One element's count x count vertex blocks of m (3 count square) added to
// the block array `out` at the element's pair slots slot[a count + b]:
// out[slot(a, b)](i, j) += m(3a + i, 3b + j), or with kTransposed
// out[slot(b, a)](j, i) += m(3a + i, 3b + j) (a mixed block with rows and
// columns swapped); with kLowerOnly only the pairs with stencil[a] >=
// stencil[b] (the only ones Compress reads of a diagonal block).
template <bool kTransposed, bool kLowerOnly, std::size_t count, class Matrix>
void ScatterBlocks(const Matrix& m, const std::array<int, count>& stencil,
                   const int* slot, std::vector<double>* out) {
  constexpr int c = static_cast<int>(count);
  for (int a = 0; a < c; ++a) {
    for (int b = 0; b < c; ++b) {
      if (kLowerOnly && stencil[a] < stencil[b]) continue;
      double* block =
          out->data() + 9 * slot[kTransposed ? b * c + a : a * c + b];
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          block[kTransposed ? 3 * j + i : 3 * i + j] +=
              m(3 * a + i, 3 * b + j);
        }
      }
    }
  }
}

[[noreturn]] void ThrowDegenerate(const ElementFailure& failure) {
  throw InputError("degenerate element while assembling a Hessian of W: " +
                   failure.description);
}

}  // namespace

PathHessianAssembler::PathHessianAssembler(const ShellSpace& space,
                                           HessianModel model)
    : space_(space), model_(model) {
  // The vertex pairs of the elements of space.elements().
  const ElementSet& set = space.elements();
  const int n = space.num_vertices;
  std::vector<std::vector<int>> rows(n);
  set.ForEachGroup([&](const auto& group) {
    for (const auto& stencil : group.stencils) {
      for (int a : stencil) {
        for (int b : stencil) rows[b].push_back(a);
      }
    }
  });
  for (int w = 0; w < n; ++w) {
    std::sort(rows[w].begin(), rows[w].end());
    rows[w].erase(std::unique(rows[w].begin(), rows[w].end()), rows[w].end());
  }
  // Columns stored in the Cuthill-McKee order of the pair graph, elements
  // visited by their first vertex in it: an element's blocks lie in a few
  // neighbouring columns, near the previous element's.
  rank_ = CuthillMcKeeRanks(rows);
  std::vector<int> by_rank(n);
  for (int w = 0; w < n; ++w) by_rank[rank_[w]] = w;
  pair_start_.assign(n + 1, 0);
  for (int r = 0; r < n; ++r) {
    const std::vector<int>& column = rows[by_rank[r]];
    pair_start_[r + 1] = pair_start_[r] + static_cast<int>(column.size());
    pair_row_.insert(pair_row_.end(), column.begin(), column.end());
  }
  auto slot = [&](int v, int w) {
    const auto first = pair_row_.begin() + pair_start_[rank_[w]];
    const auto last = pair_row_.begin() + pair_start_[rank_[w] + 1];
    return static_cast<int>(std::lower_bound(first, last, v) -
                            pair_row_.begin());
  };
  set.ForEachGroup([&](const auto& group) {
    for (const auto& stencil : group.stencils) {
      for (int a : stencil) {
        for (int b : stencil) slots_.push_back(slot(a, b));
      }
    }
    std::vector<std::pair<int, int>> keys(group.size());
    for (int e = 0; e < group.size(); ++e) {
      int first = n;
      for (int v : group.stencils[e]) first = std::min(first, rank_[v]);
      keys[e] = {first, e};
    }
    std::sort(keys.begin(), keys.end());
    for (const auto& key : keys) visit_.push_back(key.second);
  });
}

void PathHessianAssembler::SliceStatus::Fail(const ElementSet& set,
                                             int element) {
  if (ok || element < failure.element) set.Fail(element, &failure);
  ok = false;
}

bool PathHessianAssembler::AddElementBlocks(const Positions& reference,
                                            const Positions& deformed,
                                            double weight, BlockArray* d22,
                                            BlockArray* mixed_transposed,
                                            BlockArray* mixed,
                                            ElementFailure* failure) const {
  const ElementSet& set = space_.elements();
  SliceStatus status;
  size_t group_slots = 0, group_visits = 0;
  set.ForEachGroup([&](const auto& group) {
    constexpr int count = std::decay_t<decltype(group)>::kVertices;
    ElementSecondDerivatives<count> d;
    using Rows = typename ElementSecondDerivatives<count>::Rows;
    // d_grad_reference (the mixed block) only where it is scattered.
    const Rows rows = mixed_transposed == nullptr && mixed == nullptr
                          ? Rows::kDeformed
                      : d22 == nullptr ? Rows::kReference
                                       : Rows::kBoth;
    double ref[3 * count], def[3 * count];
    for (int k = 0; k < group.size(); ++k) {
      const int e = visit_[group_visits + k];
      const auto& stencil = group.stencils[e];
      const int* slot = &slots_[group_slots + count * count * e];
      GatherCoordinates(reference, stencil, ref);
      GatherCoordinates(deformed, stencil, def);
      if (!d.ComputeModel(model_, group.element, ref, def, ShellSide::kDeformed,
                          weight, rows)) {
        status.Fail(set, group.first_element + e);
      }
      if (!status.ok) continue;  // the others only for the first failure
      if (d22 != nullptr) {
        ScatterBlocks<false, true>(d.d_grad_deformed, stencil, slot, d22);
      }
      if (mixed_transposed != nullptr) {
        ScatterBlocks<true, false>(d.d_grad_reference, stencil, slot,
                                   mixed_transposed);
      }
      if (mixed != nullptr) {
        ScatterBlocks<false, false>(d.d_grad_reference, stencil, slot, mixed);
      }
    }
    group_slots += static_cast<size_t>(count * count) * group.size();
    group_visits += group.size();
  });
  if (!status.ok && failure != nullptr) *failure = status.failure;
  return status.ok;
}

bool PathHessianAssembler::AddSliceBlocks(
    const Positions& previous, const Positions& shape, const Positions& next,
    double weight, BlockArray* diagonal, BlockArray* coupling,
    SliceStatus* before, SliceStatus* after) const {
  const ElementSet& set = space_.elements();
  size_t group_slots = 0, group_visits = 0;
  set.ForEachGroup([&](const auto& group) {
    constexpr int count = std::decay_t<decltype(group)>::kVertices;
    constexpr int n = 3 * count;
    ElementSliceSecondDerivatives<count> d;
    double prev[n], own[n], succ[n];
    for (int k = 0; k < group.size(); ++k) {
      const int e = visit_[group_visits + k];
      const auto& stencil = group.stencils[e];
      const int* slot = &slots_[group_slots + count * count * e];
      GatherCoordinates(previous, stencil, prev);
      GatherCoordinates(shape, stencil, own);
      GatherCoordinates(next, stencil, succ);
      d.Compute(model_, group.element, prev, own, succ, weight,
                coupling != nullptr);
      if (!d.before_ok) before->Fail(set, group.first_element + e);
      if (!d.after_ok) after->Fail(set, group.first_element + e);
      // After a failure the slice fails; the other elements are still
      // evaluated, for each side's first failure in the set's order.
      if (!before->ok || !after->ok) continue;
      // D_2^2 W[previous, shape] + D_1^2 W[shape, next]: one scatter of
      // their sum, on and below the diagonal; D_2 D_1 W[shape, next] (rows
      // next, columns shape).
      ScatterBlocks<false, true>(d.diagonal, stencil, slot, diagonal);
      if (coupling != nullptr) {
        ScatterBlocks<false, false>(d.coupling, stencil, slot, coupling);
      }
    }
    group_slots += static_cast<size_t>(count * count) * group.size();
    group_visits += group.size();
  });
  return before->ok && after->ok;
}

bool PathHessianAssembler::AddTermBlocks(const Positions& a,
                                         const Positions& b, bool a_free,
                                         bool b_free, double weight,
                                         BlockArray* aa, BlockArray* bb,
                                         BlockArray* ba,
                                         SliceStatus* status) const {
  const ElementSet& set = space_.elements();
  size_t group_slots = 0, group_visits = 0;
  set.ForEachGroup([&](const auto& group) {
    constexpr int count = std::decay_t<decltype(group)>::kVertices;
    constexpr int n = 3 * count;
    ElementTermSecondDerivatives<count> d;
    double ref[n], def[n];
    for (int k = 0; k < group.size(); ++k) {
      const int e = visit_[group_visits + k];
      const auto& stencil = group.stencils[e];
      const int* slot = &slots_[group_slots + count * count * e];
      GatherCoordinates(a, stencil, ref);
      GatherCoordinates(b, stencil, def);
      if (!d.Compute(group.element, ref, def, weight, a_free, b_free)) {
        status->Fail(set, group.first_element + e);
      }
      if (!status->ok) continue;  // the others only for the first failure
      if (a_free) ScatterBlocks<false, true>(d.aa, stencil, slot, aa);
      if (b_free) ScatterBlocks<false, true>(d.bb, stencil, slot, bb);
      if (a_free && b_free) ScatterBlocks<false, false>(d.ba, stencil, slot, ba);
    }
    group_slots += static_cast<size_t>(count * count) * group.size();
    group_visits += group.size();
  });
  return status->ok;
}

bool PathHessianAssembler::TryAssembleProjected(
    const std::vector<Positions>& path,
    const std::vector<Eigen::SparseMatrix<double>>& bases, int threads,
    Eigen::SparseMatrix<double>* hessian, ElementFailure* failure) const {
  const int K = static_cast<int>(path.size()) - 1;
  const int inner = K - 1;
  const size_t block_values = 9 * pair_row_.size();
  // Term t = W[s_t, s_{t+1}] (t = 0 .. K - 1), each projected once: its
  // (A, A) blocks go to slice t - 1 (s_t), its (B, B) blocks to slice t
  // (s_{t+1}), its (B, A) blocks below the diagonal between them.
  std::vector<BlockArray> aa(K), bb(K), ba(K);
  std::vector<SliceStatus> status(K);
  std::vector<char> ok(K, 1);
  ParallelFor(K, threads, [&](int t) {
    const bool a_free = t >= 1, b_free = t + 1 <= inner;
    if (a_free) aa[t].assign(block_values, 0.0);
    if (b_free) bb[t].assign(block_values, 0.0);
    if (a_free && b_free) ba[t].assign(block_values, 0.0);
    ok[t] = AddTermBlocks(path[t], path[t + 1], a_free, b_free, K, &aa[t],
                          &bb[t], &ba[t], &status[t]);
  });
  for (int t = 0; t < K; ++t) {
    if (ok[t]) continue;
    if (failure) {
      *failure = status[t].failure;
      failure->description = "W[s_" + std::to_string(t) + ", s_" +
                             std::to_string(t + 1) + "]: " +
                             failure->description;
    }
    *hessian = Eigen::SparseMatrix<double>();
    return false;
  }
  std::vector<std::vector<const BlockArray*>> diagonal(inner);
  std::vector<const BlockArray*> below(inner, nullptr);
  for (int i = 0; i < inner; ++i) {  // slice i: s_{i+1}
    diagonal[i] = {&bb[i], &aa[i + 1]};
    if (i + 1 < inner) below[i] = &ba[i + 1];
  }
  Compress(diagonal, below, bases, threads, hessian);
  return true;
}

bool PathHessianAssembler::TryAssemble(
    const std::vector<Positions>& path,
    const std::vector<Eigen::SparseMatrix<double>>& bases, int threads,
    Eigen::SparseMatrix<double>* hessian, ElementFailure* failure) const {
  const int K = static_cast<int>(path.size()) - 1;
  const int inner = K - 1;
  if (inner < 1 || static_cast<int>(bases.size()) != inner) {
    throw std::invalid_argument("PathHessianAssembler: need K >= 2 and K - 1 bases");
  }
  if (model_ == HessianModel::kProjected) {
    return TryAssembleProjected(path, bases, threads, hessian, failure);
  }
  const size_t block_values = 9 * pair_row_.size();
  // One task per inner shape s_k (slice i = k - 1), inside the filling pass
  // of Compress (slice_ready): it computes its diagonal block
  // D_2^2 W[s_{k-1}, s_k] + D_1^2 W[s_k, s_{k+1}] into one array and, for
  // k < K - 1, the coupling below it, D_2 D_1 W[s_k, s_{k+1}] (rows slice
  // i + 1, columns slice i), from the same reference-active pass as
  // D_1^2 W; then it writes the slice's columns and releases both arrays.
  // Every array has one writer, and only `threads` slices' arrays exist at
  // a time (on the cactus x16 a slice's two arrays are about 0.2 GB).
  std::vector<BlockArray> diagonal_blocks(inner), lower(inner);
  // Per term W[s_{k-1}, s_k] (index k - 1): its deformed side (slice k -
  // 1's task) and its reference side (slice k - 2's task). A failed side
  // names the first degenerate element of its term.
  std::vector<SliceStatus> deformed(K), reference(K);
  std::vector<std::vector<const BlockArray*>> diagonal(inner);
  std::vector<const BlockArray*> below(inner, nullptr);
  for (int i = 0; i < inner; ++i) {
    diagonal[i] = {&diagonal_blocks[i]};
    if (i + 1 < inner) below[i] = &lower[i];
  }
  const auto compute_slice = [&](int i) {
    const int k = i + 1;
    diagonal_blocks[i].assign(block_values, 0.0);
    BlockArray* coupling = nullptr;
    if (i + 1 < inner) (coupling = &lower[i])->assign(block_values, 0.0);
    return AddSliceBlocks(path[k - 1], path[k], path[k + 1], K,
                          &diagonal_blocks[i], coupling, &deformed[k - 1],
                          &reference[k]);
  };
  const auto release_slice = [&](int i) {
    BlockArray().swap(diagonal_blocks[i]);
    BlockArray().swap(lower[i]);
  };
  Compress(diagonal, below, bases, threads, hessian, release_slice,
           compute_slice);
  for (int term = 0; term < K; ++term) {
    const SliceStatus& side =
        !deformed[term].ok ? deformed[term] : reference[term];
    if (!side.ok) {
      if (failure) {
        *failure = side.failure;
        failure->description = "W[s_" + std::to_string(term) + ", s_" +
                               std::to_string(term + 1) + "]: " +
                               failure->description;
      }
      *hessian = Eigen::SparseMatrix<double>();  // values partly unwritten
      return false;
    }
  }
  return true;
}

Eigen::SparseMatrix<double> PathHessianAssembler::Assemble(
    const std::vector<Positions>& path,
    const std::vector<Eigen::SparseMatrix<double>>& bases, int threads) const {
  Eigen::SparseMatrix<double> hessian;
  ElementFailure failure;
  if (!TryAssemble(path, bases, threads, &hessian, &failure)) {
    ThrowDegenerate(failure);
  }
  return hessian;
}

bool PathHessianAssembler::TryAssembleDeformedSum(
    const std::vector<Positions>& references, const Positions& deformed,
    const Eigen::SparseMatrix<double>& basis, int threads,
    Eigen::SparseMatrix<double>* hessian, ElementFailure* failure) const {
  const int parts = std::max(1, std::min<int>(threads, references.size()));
  const size_t block_values = 9 * pair_row_.size();
  std::vector<BlockArray> sums(parts);
  std::vector<ElementFailure> failures(references.size());
  std::vector<char> ok(references.size(), 1);
  ParallelFor(parts, parts, [&](int part) {
    sums[part].assign(block_values, 0.0);
    for (size_t i = part; i < references.size(); i += parts) {
      ok[i] = AddElementBlocks(references[i], deformed, 1.0, &sums[part],
                               nullptr, nullptr, &failures[i]);
      if (!ok[i]) return;
    }
  });
  for (size_t i = 0; i < references.size(); ++i) {
    if (!ok[i]) {
      if (failure) {
        *failure = failures[i];
        failure->description = "W[reference " + std::to_string(i) +
                               ", deformed]: " + failure->description;
      }
      return false;
    }
  }
  std::vector<std::vector<const BlockArray*>> diagonal(1);
  for (const BlockArray& sum : sums) diagonal[0].push_back(&sum);
  Compress(diagonal, {nullptr}, {basis}, 1, hessian);
  return true;
}

Eigen::SparseMatrix<double> PathHessianAssembler::AssembleDeformedSum(
    const std::vector<Positions>& references, const Positions& deformed,
    const Eigen::SparseMatrix<double>& basis, int threads) const {
  Eigen::SparseMatrix<double> hessian;
  ElementFailure failure;
  if (!TryAssembleDeformedSum(references, deformed, basis, threads, &hessian,
                              &failure)) {
    ThrowDegenerate(failure);
  }
  return hessian;
}

Eigen::SparseMatrix<double> PathHessianAssembler::AssembleMixed(
    const Positions& reference, const Positions& deformed, ShellSide rows,
    const Eigen::SparseMatrix<double>& row_basis,
    const Eigen::SparseMatrix<double>& col_basis) const {
  Eigen::SparseMatrix<double> mixed;
  ElementFailure failure;
  if (!TryAssembleMixed(reference, deformed, rows, row_basis, col_basis,
                        &mixed, &failure)) {
    ThrowDegenerate(failure);
  }
  return mixed;
}

bool PathHessianAssembler::TryAssembleMixed(
    const Positions& reference, const Positions& deformed, ShellSide rows,
    const Eigen::SparseMatrix<double>& row_basis,
    const Eigen::SparseMatrix<double>& col_basis,
    Eigen::SparseMatrix<double>* out, ElementFailure* failure) const {
  const int n = space_.num_vertices;
  BlockArray blocks(9 * pair_row_.size(), 0.0);
  const bool ok = rows == ShellSide::kReference
                      ? AddElementBlocks(reference, deformed, 1.0, nullptr,
                                         nullptr, &blocks, failure)
                      : AddElementBlocks(reference, deformed, 1.0, nullptr,
                                         &blocks, nullptr, failure);
  if (!ok) return false;
  const std::vector<VertexColumns> row_layout = VertexLayout(row_basis, n, 0);
  const std::vector<VertexColumns> col_layout = VertexLayout(col_basis, n, 0);
  const auto walk = [&](int /*part*/, auto& sink) {
    int column = 0;
    for (int w = 0; w < n; ++w) {
      const VertexColumns& cw = col_layout[w];
      for (int jw = 0; jw < cw.count; ++jw, ++column) {
        StartColumn(cw, jw, column, sink);
        for (int p = pair_start_[rank_[w]]; p < pair_start_[rank_[w] + 1];
             ++p) {
          const VertexColumns& cv = row_layout[pair_row_[p]];
          for (int iv = 0; iv < cv.count; ++iv) {
            double value = 0;
            if constexpr (std::decay_t<decltype(sink)>::kValues) {
              value = ReducedEntry(cv, iv, blocks.data() + 9 * p, cw, jw);
            }
            sink.Entry(cv.first + iv, value);
          }
        }
      }
    }
  };
  BuildCompressed(static_cast<int>(row_basis.cols()),
                  {0, static_cast<int>(col_basis.cols())}, 1, walk, out);
  return true;
}

void PathHessianAssembler::Compress(
    const std::vector<std::vector<const BlockArray*>>& diagonal,
    const std::vector<const BlockArray*>& lower,
    const std::vector<Eigen::SparseMatrix<double>>& bases,
    int threads, Eigen::SparseMatrix<double>* out,
    const std::function<void(int)>& slice_done,
    const std::function<bool(int)>& slice_ready) const {
  const int n = space_.num_vertices;
  const int inner = static_cast<int>(bases.size());
  std::vector<std::vector<VertexColumns>> layout(inner);
  std::vector<int> offset(inner + 1, 0);
  for (int i = 0; i < inner; ++i) {
    layout[i] = VertexLayout(bases[i], n, offset[i]);
    offset[i + 1] = offset[i] + static_cast<int>(bases[i].cols());
  }
  const auto walk = [&](int i, auto& sink) {
    constexpr bool kValues = std::decay_t<decltype(sink)>::kValues;
    if constexpr (kValues) {
      if (slice_ready && !slice_ready(i)) {
        if (slice_done) slice_done(i);
        return;
      }
    }
    double diagonal_block[9];
    int column = offset[i];
    for (int w = 0; w < n; ++w) {
      const VertexColumns& cw = layout[i][w];
      for (int jw = 0; jw < cw.count; ++jw, ++column) {
        StartColumn(cw, jw, column, sink);
        for (int p = pair_start_[rank_[w]]; p < pair_start_[rank_[w] + 1];
             ++p) {
          const VertexColumns& cv = layout[i][pair_row_[p]];
          if (cv.count == 0 || cv.first + cv.count <= column) continue;
          if constexpr (kValues) {
            for (int e = 0; e < 9; ++e) {
              diagonal_block[e] = 0;
              for (const BlockArray* part : diagonal[i]) {
                diagonal_block[e] += (*part)[9 * p + e];
              }
            }
          }
          for (int iv = 0; iv < cv.count; ++iv) {
            if (cv.first + iv < column) continue;
            double value = 0;
            if constexpr (kValues) {
              value = ReducedEntry(cv, iv, diagonal_block, cw, jw);
            }
            sink.Entry(cv.first + iv, value);
          }
        }
        if (lower[i] == nullptr) continue;
        for (int p = pair_start_[rank_[w]]; p < pair_start_[rank_[w] + 1];
             ++p) {
          const VertexColumns& cv = layout[i + 1][pair_row_[p]];
          for (int iv = 0; iv < cv.count; ++iv) {
            double value = 0;
            if constexpr (kValues) {
              value = ReducedEntry(cv, iv, lower[i]->data() + 9 * p, cw, jw);
            }
            sink.Entry(cv.first + iv, value);
          }
        }
      }
    }
    if constexpr (kValues) {
      if (slice_done) slice_done(i);
    }
  };
  BuildCompressed(offset[inner], offset, threads, walk, out);
}

}  // namespace shellspace
