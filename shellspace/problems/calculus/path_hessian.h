// The exact Hessian of the path energy with respect to the inner shapes,
// assembled directly into a fixed sparsity pattern.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_PATH_HESSIAN_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_PATH_HESSIAN_H_

#include <Eigen/SparseCore>
#include <functional>
#include <vector>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/cost_functions/shell/element_set.h"
#include "shellspace/cost_functions/shell/shell_space.h"

namespace shellspace {

// For a path (s_0, ..., s_K) and E_K = K sum_k W[s_{k-1}, s_k], the Hessian
// w.r.t. the inner shapes s_1..s_{K-1} is block tridiagonal:
//   H_kk     = K (D_2^2 W[s_{k-1}, s_k] + D_1^2 W[s_k, s_{k+1}]),
//   H_k+1,k  = K (D_1 D_2 W[s_k, s_{k+1}])^T   (rows s_{k+1}, columns s_k).
// With s_k = x_k + T_k q_k (T_k: 3n x m_k, each column supported on the
// three coordinates of one vertex, columns in vertex order -- as
// FreeVertexBasis and RigidGaugeBasis are), Assemble returns the lower
// triangle of T^T H T (sum_k m_k square, unknowns of slice k after those of
// slice k - 1), with sorted row indices.
//
// Layout: every element of space.elements() (element_set.h: today faces,
// membrane, and interior edge flaps, bending) adds, for each ordered pair
// (a, b) of its stencil's vertices, a 3 x 3 block to the vertex
// pair (v_a, v_b). The pairs of the mesh are enumerated once (CSR over the
// column vertex, the columns in a Cuthill-McKee order of the mesh, whatever
// the file's vertex numbering) and every element knows the slot of each of
// its pairs; the elements are visited in that order too, so
// one assembly is: per element, the second derivatives of its energy
// (ElementSecondDerivatives: the elements' hand-derived second derivatives,
// from the same stencil as the cost functions; dual numbers over the
// analytic gradient for an element without them) scattered into per-slice
// block arrays,
// then one pass T_v^T B T_w over the blocks into compressed columns. No
// triplets, no sparse products.
class PathHessianAssembler {
 public:
  // model: every element's second derivatives by `model` (element_hessian.h;
  // kGaussNewton: the Gauss-Newton matrix J^T J of the residuals, the
  // Levenberg-Marquardt model, positive semidefinite; kProjected: each
  // term's exact Hessian projected onto the positive semidefinite cone, the
  // projected-Newton model, positive semidefinite).
  explicit PathHessianAssembler(const ShellSpace& space,
                                HessianModel model = HessianModel::kExact);
  HessianModel model() const { return model_; }

  // `path` has K + 1 >= 3 shapes; `bases[k - 1]` is T_k. Elements of the
  // W[s_{k-1}, s_k] are processed in parallel over k. Throws InputError if an
  // element is degenerate.
  Eigen::SparseMatrix<double> Assemble(
      const std::vector<Positions>& path,
      const std::vector<Eigen::SparseMatrix<double>>& bases,
      int threads) const;
  // The same without exceptions for degenerate elements: false (and
  // *failure, if given, names the element of the lowest step k) instead --
  // the status for line searches. Invalid arguments (bases) still throw.
  bool TryAssemble(const std::vector<Positions>& path,
                   const std::vector<Eigen::SparseMatrix<double>>& bases,
                   int threads, Eigen::SparseMatrix<double>* hessian,
                   ElementFailure* failure = nullptr) const;

  // The lower triangle of T^T (sum_i D_2^2 W[references_i, deformed]) T for
  // one shape (the Hessian of the elastic-mean energy), T = `basis` (as
  // above). References are processed in parallel.
  Eigen::SparseMatrix<double> AssembleDeformedSum(
      const std::vector<Positions>& references, const Positions& deformed,
      const Eigen::SparseMatrix<double>& basis, int threads) const;
  // Its status twin (as TryAssemble; *failure names the lowest reference i).
  bool TryAssembleDeformedSum(const std::vector<Positions>& references,
                              const Positions& deformed,
                              const Eigen::SparseMatrix<double>& basis,
                              int threads, Eigen::SparseMatrix<double>* hessian,
                              ElementFailure* failure = nullptr) const;

  // R^T M C for the mixed second derivative of W[reference, deformed], R =
  // `row_basis`, C = `col_basis` (each as T above, possibly different):
  //   rows kReference: M = D_1 D_2 W (rows reference, columns deformed), the
  //     Jacobian of D_1 W[reference, .] w.r.t. the deformed shell;
  //   rows kDeformed:  M = (D_1 D_2 W)^T (rows deformed, columns reference),
  //     the Jacobian of D_2 W[., deformed] w.r.t. the reference.
  // The whole matrix (not symmetric), sorted row indices. Throws InputError
  // if an element is degenerate.
  Eigen::SparseMatrix<double> AssembleMixed(
      const Positions& reference, const Positions& deformed, ShellSide rows,
      const Eigen::SparseMatrix<double>& row_basis,
      const Eigen::SparseMatrix<double>& col_basis) const;
  // Its status twin (as TryAssemble).
  bool TryAssembleMixed(const Positions& reference, const Positions& deformed,
                        ShellSide rows,
                        const Eigen::SparseMatrix<double>& row_basis,
                        const Eigen::SparseMatrix<double>& col_basis,
                        Eigen::SparseMatrix<double>* mixed,
                        ElementFailure* failure = nullptr) const;

  int num_vertex_pairs() const { return static_cast<int>(pair_row_.size()); }

 private:
  // 3 x 3 blocks (row-major), one per vertex pair, for one slice.
  using BlockArray = std::vector<double>;
  // Adds weight times the blocks of W[reference, deformed] (the pass with
  // the deformed side active) to the non-null arrays: D_2^2 W (d22), the
  // mixed block with rows deformed (mixed_transposed) and with rows
  // reference (mixed), element by element in the set's order. False
  // (arrays partly filled) at the first degenerate element, named in
  // *failure if given. d22 receives the blocks on and below the diagonal
  // only (row vertex >= column vertex: the only ones Compress reads of a
  // diagonal block); the mixed arrays receive all.
  bool AddElementBlocks(const Positions& reference, const Positions& deformed,
                        double weight, BlockArray* d22,
                        BlockArray* mixed_transposed, BlockArray* mixed,
                        ElementFailure* failure) const;

  // Whether one side of a term W[s_{k-1}, s_k] was assembled, and if not,
  // its first degenerate element.
  struct SliceStatus {
    bool ok = true;
    ElementFailure failure;
    // Records a failing element (enumeration index): the lowest one is kept.
    void Fail(const ElementSet& set, int element);
  };
  // One inner shape's part of the path Hessian, element by element in the
  // set's order: weight times D_2^2 W[previous, shape] + D_1^2 W[shape,
  // next] into `diagonal` (one scatter of the two elements' sum, on and
  // below the diagonal), and, if `coupling` is not null, weight times
  // D_2 D_1 W[shape, next] (rows next, columns shape), from the same
  // reference-active pass as D_1^2 W. A side that is not ok on entry is
  // skipped; a side's first degenerate element makes it not ok (*before:
  // W[previous, shape], *after: W[shape, next]), and its status names it;
  // the other side goes on, so each status names its term's first
  // degenerate element. True if both sides are ok (then the arrays hold
  // the slice's sums).
  bool AddSliceBlocks(const Positions& previous, const Positions& shape,
                      const Positions& next, double weight,
                      BlockArray* diagonal, BlockArray* coupling,
                      SliceStatus* before, SliceStatus* after) const;

  // The projected model (HessianModel::kProjected): weight times the blocks
  // of the term W[a, b] with its Hessian in its free arguments projected as
  // a whole (ElementTermSecondDerivatives): (a, a) into *aa if a_free,
  // (b, b) into *bb if b_free (on and below the diagonal), (rows b,
  // columns a) into *ba if both are free. False at the first degenerate
  // element, named in *status.
  bool AddTermBlocks(const Positions& a, const Positions& b, bool a_free,
                     bool b_free, double weight, BlockArray* aa,
                     BlockArray* bb, BlockArray* ba,
                     SliceStatus* status) const;
  // TryAssemble for the projected model: the K terms in parallel, each
  // projected once, then compressed (memory: three block arrays per term).
  bool TryAssembleProjected(const std::vector<Positions>& path,
                            const std::vector<Eigen::SparseMatrix<double>>& bases,
                            int threads, Eigen::SparseMatrix<double>* hessian,
                            ElementFailure* failure) const;

  // *out = T^T H T (lower triangle) from the diagonal blocks of each slice
  // (the sum of the arrays diagonal[i]) and the blocks below the diagonal
  // (lower[i]: rows slice i + 1, columns slice i), written in place (its old
  // storage released first), the slices in parallel (`threads` at a time).
  // slice_ready(i), if given, is called (from the thread that will write
  // them) before slice i's columns are filled: it may compute the slice's
  // arrays there (the counting pass does not read them), so that only
  // `threads` slices' arrays exist at a time; if it returns false the
  // slice's values are left unwritten (the caller discards *out).
  // slice_done(i), if given, is called (from the same thread) once slice
  // i's columns are written: its arrays are not read again.
  void Compress(const std::vector<std::vector<const BlockArray*>>& diagonal,
                const std::vector<const BlockArray*>& lower,
                const std::vector<Eigen::SparseMatrix<double>>& bases,
                int threads, Eigen::SparseMatrix<double>* out,
                const std::function<void(int)>& slice_done = nullptr,
                const std::function<bool(int)>& slice_ready = nullptr) const;

  const ShellSpace& space_;
  HessianModel model_ = HessianModel::kExact;
  // Vertex w's position in the Cuthill-McKee order of the pair graph
  // (geometry/locality_order.h): the columns' order in the block arrays.
  std::vector<int> rank_;
  // The pairs with column vertex w: [pair_start_[rank_[w]],
  // pair_start_[rank_[w] + 1]).
  std::vector<int> pair_start_;
  std::vector<int> pair_row_;  // their row vertices, ascending
  std::vector<int> slots_;     // per element (set order), count^2 slots
                               // (a, b) -> pair
  // Per group (set order), the order its elements are visited in: by their
  // first vertex in rank_ (then by index), so consecutive elements scatter
  // into nearby blocks. A sum over elements is taken in this order; a
  // failure still names the first failing element of the set's order.
  std::vector<int> visit_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_PATH_HESSIAN_H_
