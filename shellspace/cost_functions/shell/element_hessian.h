// Second derivatives of one element's energy e = 1/2 |r|^2: the element's
// own hand-derived second derivatives where it provides them (an element
// method SecondDerivatives, see below: MembraneElement, BendingElement), else
// by differentiating the element's analytic gradient (J^T r, the same stencil
// as the cost functions) with forward-mode dual numbers (ceres::Jet). Both
// exact to round-off; no finite differences.
//
// The member templates below are defined in element_hessian-inl.h and
// compiled once per element type of the element set, in the cost_functions
// library (SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES at the end of this file):
// each element type's header declares them, so that a file using them does
// not compile them again (the dual numbers ceres::Jet<double, 3 kVertices>
// through the element's Evaluate and the fixed-size projections of
// psd_projection.h are minutes of compilation per file).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_HESSIAN_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_HESSIAN_H_

#include <Eigen/Core>
#include <type_traits>
#include <utility>

#include "shellspace/geometry/scalar_traits.h"

namespace shellspace {

// Which argument of W the derivatives are taken with respect to.
enum class ShellSide { kReference, kDeformed };

// The second-derivative model of an element's e = 1/2 |r|^2 (r its
// residuals, J = dr/dY):
//   kExact:       the Hessian J^T J + sum_i r_i d^2 r_i;
//   kGaussNewton: its Gauss-Newton part J^T J -- positive semidefinite, equal
//                 to the Hessian at r = 0 (the rest state, docs/math.md), the
//                 model Ceres' Levenberg-Marquardt minimises;
//   kProjected:   the exact Hessian of each element term projected onto the
//                 positive semidefinite cone (psd_projection.h): equal to the
//                 exact one wherever that is positive semidefinite, so the
//                 assembled matrix is positive semidefinite and keeps the
//                 exact curvature where it is positive (projected Newton).
//                 In a one-sided pass (ComputeModel) the active side's block
//                 D_active^2 e is projected, the mixed blocks stay exact; in
//                 a path the whole Hessian of each term e[s_{k-1}, s_k] in
//                 its free shapes (ElementTermSecondDerivatives).
enum class HessianModel { kExact, kGaussNewton, kProjected };

// For an element with kVertices vertices (3: membrane, 4: bending), with
// n = 3 kVertices:
//   grad_reference = d e / d Xbar   (n),  grad_deformed = d e / d X  (n),
//   d_grad_reference = d grad_reference / d Y  (n x n),
//   d_grad_deformed  = d grad_deformed  / d Y  (n x n),
// where Y is the `active` side. So with active = kDeformed, d_grad_deformed is
// the Hessian D_2^2 e and d_grad_reference the mixed block d_Xbar d_X e (rows
// Xbar, columns X); with active = kReference, d_grad_reference = D_1^2 e and
// d_grad_deformed = d_X d_Xbar e (rows X, columns Xbar). Returns false if the
// element is degenerate. With `rows` = kReference (kDeformed) only
// grad_reference and d_grad_reference (grad_deformed, d_grad_deformed) are
// computed -- one residual Jacobian fewer in dual numbers; the others are
// left unchanged.
//
// Analytic second derivatives: an element type E (element_set.h) may provide
//   bool SecondDerivatives(const double* reference, const double* deformed,
//       ShellSide active, double weight,
//       typename ElementSecondDerivatives<E::kNumVertices>::Rows rows,
//       ElementSecondDerivatives<E::kNumVertices>* out) const;
// filling exactly what Compute documents (same layout, same `rows` and
// `active` semantics, energy and gradients included, fields not asked for
// left unchanged) and returning false exactly when Evaluate would. Compute
// then uses it (detected at compile time, HasAnalyticSecondDerivatives);
// otherwise, and always in ComputeWithDualNumbers, it differentiates J^T r
// with dual numbers.
template <int kVertices>
struct ElementSecondDerivatives;

// The stencil's vertex positions Xbar_v = ref[v], X_v = def[v] (v <
// kVertices), read from the flat coordinates `reference`, `deformed`
// (3 kVertices doubles each, vertex after vertex): what every second-
// derivative computation below and every element's analytic
// SecondDerivatives starts from.
template <int kVertices>
struct StencilPositions {
  StencilPositions(const double* reference, const double* deformed) {
    for (int v = 0; v < kVertices; ++v) {
      ref[v] = Eigen::Map<const Vec3<double>>(reference + 3 * v);
      def[v] = Eigen::Map<const Vec3<double>>(deformed + 3 * v);
    }
  }
  Vec3<double> ref[kVertices], def[kVertices];
};

template <class Element, class = void>
struct HasAnalyticSecondDerivatives : std::false_type {};
template <class Element>
struct HasAnalyticSecondDerivatives<
    Element,
    std::void_t<decltype(std::declval<const Element&>().SecondDerivatives(
        std::declval<const double*>(), std::declval<const double*>(),
        ShellSide::kDeformed, 1.0,
        ElementSecondDerivatives<Element::kNumVertices>::Rows::kBoth,
        std::declval<ElementSecondDerivatives<Element::kNumVertices>*>()))>>
    : std::true_type {};

template <int kVertices>
struct ElementSecondDerivatives {
  static constexpr int n = 3 * kVertices;
  Eigen::Matrix<double, n, 1> grad_reference, grad_deformed;
  Eigen::Matrix<double, n, n, Eigen::RowMajor> d_grad_reference,
      d_grad_deformed;
  double energy = 0;

  enum class Rows { kBoth, kReference, kDeformed };
  // Whether `rows` asks for grad_reference / d_grad_reference
  // (grad_deformed / d_grad_deformed).
  static bool WantsReference(Rows rows) { return rows != Rows::kDeformed; }
  static bool WantsDeformed(Rows rows) { return rows != Rows::kReference; }

  // The derivatives of `element` as documented above: its
  // SecondDerivatives if it has one, else ComputeWithDualNumbers.
  template <class Element>
  bool Compute(const Element& element, const double* reference,
               const double* deformed, ShellSide active, double weight,
               Rows rows = Rows::kBoth);

  // Compute for `model`: kExact as Compute, kGaussNewton the same layout
  // (energy and gradients exact) with every second-derivative block replaced
  // by its Gauss-Newton part, d_grad_X = weight J_X^T J_active.
  template <class Element>
  bool ComputeModel(HessianModel model, const Element& element,
                    const double* reference, const double* deformed,
                    ShellSide active, double weight, Rows rows = Rows::kBoth);

  // The dual-number path for any element (the reference the analytic
  // second derivatives are tested against).
  template <class Element>
  bool ComputeWithDualNumbers(const Element& element, const double* reference,
                              const double* deformed, ShellSide active,
                              double weight, Rows rows = Rows::kBoth);
};

template <int kVertices>
struct ElementSliceSecondDerivatives;

template <class Element, class = void>
struct HasSliceSecondDerivatives : std::false_type {};
template <class Element>
struct HasSliceSecondDerivatives<
    Element,
    std::void_t<decltype(std::declval<const Element&>().SliceSecondDerivatives(
        std::declval<const double*>(), std::declval<const double*>(),
        std::declval<const double*>(), 1.0, true,
        std::declval<
            ElementSliceSecondDerivatives<Element::kNumVertices>*>()))>>
    : std::true_type {};

// One element's share of one inner shape's blocks of a path Hessian
// (problems/calculus/path_hessian.h). With X = `own` (the shape's stencil
// positions, 3 kVertices doubles as in Compute), P = `previous` and N =
// `next` (its neighbours on the path), e[., .] the element's energy:
//   diagonal = weight (D_2^2 e[P, X] + D_1^2 e[X, N])         (n x n),
//   coupling = weight D_2 D_1 e[X, N]   (rows N, columns X; if wanted),
// for `model`. before_ok (after_ok) is false exactly when e[P, X] (e[X, N])
// is degenerate, ComputeModel's verdict; the blocks are set only when both
// are true (the coupling when after_ok is).
//
// An element type may provide, for the exact model,
//   void SliceSecondDerivatives(const double* previous, const double* own,
//       const double* next, double weight, bool want_coupling,
//       ElementSliceSecondDerivatives<kNumVertices>* out) const;
// computing what X's two terms share once -- the second derivatives of both
// terms w.r.t. X go through X's own geometry (its dihedral angle, its first
// fundamental form), so they are added before that last chain rule.
// Otherwise, and for the Gauss-Newton model, ComputeBySides: the two
// ComputeModel passes, added.
// (The projected model is not a slice computation: each term is projected
// as a whole, ElementTermSecondDerivatives.)
template <int kVertices>
struct ElementSliceSecondDerivatives {
  static constexpr int n = 3 * kVertices;
  using Matrix = Eigen::Matrix<double, n, n, Eigen::RowMajor>;
  Matrix diagonal, coupling;
  bool before_ok = false, after_ok = false;

  template <class Element>
  void Compute(HessianModel model, const Element& element,
               const double* previous, const double* own, const double* next,
               double weight, bool want_coupling);

  // The reference the element's SliceSecondDerivatives is tested against.
  template <class Element>
  void ComputeBySides(HessianModel model, const Element& element,
                      const double* previous, const double* own,
                      const double* next, double weight, bool want_coupling);

 private:
  ElementSecondDerivatives<kVertices> before_, after_;
};

// One element term e[A, B] of a path (A = s_{k-1}, B = s_k) with its Hessian
// in the shapes that are free projected onto the positive semidefinite cone
// (HessianModel::kProjected, psd_projection.h): with both free the
// 2n x 2n matrix
//   [D_1^2 e     D_1 D_2 e]
//   [D_2 D_1 e   D_2^2 e  ]   (rows and columns A, then B)
// is projected as a whole and split into aa (A, A), bb (B, B) and ba (rows B,
// columns A); with A an end of the path (a_free false) only bb = P(D_2^2 e),
// with B an end only aa = P(D_1^2 e). The path Hessian assembled from these
// blocks is the sum of the projected terms: positive semidefinite, and the
// exact Hessian wherever every term is convex. Compute returns false exactly
// when the element is degenerate (ComputeModel's verdict); `projected` says
// whether the projection changed the matrix. The projection works in the
// complement of each shape's translations, which every term's Hessian
// annihilates (ProjectToPositiveSemidefiniteModuloTranslations).
template <int kVertices>
struct ElementTermSecondDerivatives {
  static constexpr int n = 3 * kVertices;
  using Matrix = Eigen::Matrix<double, n, n, Eigen::RowMajor>;
  Matrix aa, bb, ba;
  bool projected = false;

  template <class Element>
  bool Compute(const Element& element, const double* a, const double* b,
               double weight, bool a_free, bool b_free);

 private:
  ElementSecondDerivatives<kVertices> a_active_, b_active_;
  Eigen::Matrix<double, 2 * n, 2 * n> term_;
};

// The specializations of the member templates above for the element type E:
// with kind `extern template` their explicit instantiation declarations (in
// E's header, after E), with kind `template` their definitions (in one .cc
// of the library that includes element_hessian-inl.h).
#define SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(kind, E)                         \
  kind bool ElementSecondDerivatives<E::kNumVertices>::Compute<E>(            \
      const E&, const double*, const double*, ShellSide, double,              \
      ElementSecondDerivatives<E::kNumVertices>::Rows);                       \
  kind bool ElementSecondDerivatives<E::kNumVertices>::ComputeModel<E>(       \
      HessianModel, const E&, const double*, const double*, ShellSide,        \
      double, ElementSecondDerivatives<E::kNumVertices>::Rows);               \
  kind bool                                                                   \
      ElementSecondDerivatives<E::kNumVertices>::ComputeWithDualNumbers<E>(   \
          const E&, const double*, const double*, ShellSide, double,          \
          ElementSecondDerivatives<E::kNumVertices>::Rows);                   \
  kind void ElementSliceSecondDerivatives<E::kNumVertices>::Compute<E>(       \
      HessianModel, const E&, const double*, const double*, const double*,    \
      double, bool);                                                          \
  kind void ElementSliceSecondDerivatives<E::kNumVertices>::ComputeBySides<E>( \
      HessianModel, const E&, const double*, const double*, const double*,    \
      double, bool);                                                          \
  kind bool ElementTermSecondDerivatives<E::kNumVertices>::Compute<E>(        \
      const E&, const double*, const double*, double, bool, bool)

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_HESSIAN_H_
