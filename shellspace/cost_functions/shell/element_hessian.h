// Second derivatives of one element's energy e = 1/2 |r|^2: the element's
// own hand-derived second derivatives where it provides them (an element
// method SecondDerivatives, see below: MembraneElement, BendingElement), else
// by differentiating the element's analytic gradient (J^T r, the same stencil
// as the cost functions) with forward-mode dual numbers (ceres::Jet). Both
// exact to round-off; no finite differences.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_HESSIAN_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_HESSIAN_H_

#include <ceres/jet.h>

#include <Eigen/Core>
#include <type_traits>
#include <utility>

#include "shellspace/cost_functions/shell/psd_projection.h"
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

  template <class Element>
  bool Compute(const Element& element, const double* reference,
               const double* deformed, ShellSide active, double weight,
               Rows rows = Rows::kBoth) {
    static_assert(Element::kNumVertices == kVertices,
                  "ElementSecondDerivatives: stencil size mismatch");
    if constexpr (HasAnalyticSecondDerivatives<Element>::value) {
      return element.SecondDerivatives(reference, deformed, active, weight,
                                       rows, this);
    } else {
      return ComputeWithDualNumbers(element, reference, deformed, active,
                                    weight, rows);
    }
  }

  // Compute for `model`: kExact as Compute, kGaussNewton the same layout
  // (energy and gradients exact) with every second-derivative block replaced
  // by its Gauss-Newton part, d_grad_X = weight J_X^T J_active.
  template <class Element>
  bool ComputeModel(HessianModel model, const Element& element,
                    const double* reference, const double* deformed,
                    ShellSide active, double weight, Rows rows = Rows::kBoth) {
    if (model == HessianModel::kExact) {
      return Compute(element, reference, deformed, active, weight, rows);
    }
    if (model == HessianModel::kProjected) {
      if (!Compute(element, reference, deformed, active, weight, rows)) {
        return false;
      }
      if (active == ShellSide::kDeformed && WantsDeformed(rows)) {
        ProjectToPositiveSemidefinite(&d_grad_deformed);
      }
      if (active == ShellSide::kReference && WantsReference(rows)) {
        ProjectToPositiveSemidefinite(&d_grad_reference);
      }
      return true;
    }
    static_assert(Element::kNumVertices == kVertices,
                  "ElementSecondDerivatives: stencil size mismatch");
    const StencilPositions<kVertices> x(reference, deformed);
    constexpr int m = Element::kNumResiduals;
    Eigen::Matrix<double, m, 1> r;
    typename Element::template Jacobian<double> jac_ref, jac_def;
    if (!element.Evaluate(x.ref, x.def, r.data(), &jac_ref, &jac_def)) {
      return false;
    }
    energy = 0.5 * weight * r.squaredNorm();
    const auto& jac_active =
        active == ShellSide::kReference ? jac_ref : jac_def;
    if (WantsReference(rows)) {
      grad_reference = weight * jac_ref.transpose() * r;
      d_grad_reference.noalias() = weight * jac_ref.transpose() * jac_active;
    }
    if (WantsDeformed(rows)) {
      grad_deformed = weight * jac_def.transpose() * r;
      d_grad_deformed.noalias() = weight * jac_def.transpose() * jac_active;
    }
    return true;
  }

  // The dual-number path for any element (the reference the analytic
  // second derivatives are tested against).
  template <class Element>
  bool ComputeWithDualNumbers(const Element& element, const double* reference,
                              const double* deformed, ShellSide active,
                              double weight, Rows rows = Rows::kBoth) {
    using J = ceres::Jet<double, n>;
    Vec3<J> ref[kVertices], def[kVertices];
    for (int v = 0; v < kVertices; ++v) {
      for (int c = 0; c < 3; ++c) {
        ref[v](c) = J(reference[3 * v + c]);
        def[v](c) = J(deformed[3 * v + c]);
        if (active == ShellSide::kReference) {
          ref[v](c).v[3 * v + c] = 1.0;
        } else {
          def[v](c).v[3 * v + c] = 1.0;
        }
      }
    }
    constexpr int m = Element::kNumResiduals;
    J residuals[m];
    typename Element::template Jacobian<J> jac_ref, jac_def;
    const bool want_ref = WantsReference(rows);
    const bool want_def = WantsDeformed(rows);
    if (!element.Evaluate(ref, def, residuals, want_ref ? &jac_ref : nullptr,
                          want_def ? &jac_def : nullptr)) {
      return false;
    }
    energy = 0;
    for (int i = 0; i < m; ++i)
      energy += 0.5 * weight * residuals[i].a * residuals[i].a;
    for (int col = 0; col < n; ++col) {
      if (want_ref) {
        J g(0.0);
        for (int i = 0; i < m; ++i) g += jac_ref(i, col) * residuals[i];
        grad_reference(col) = weight * g.a;
        d_grad_reference.row(col) = weight * g.v.transpose();
      }
      if (want_def) {
        J g(0.0);
        for (int i = 0; i < m; ++i) g += jac_def(i, col) * residuals[i];
        grad_deformed(col) = weight * g.a;
        d_grad_deformed.row(col) = weight * g.v.transpose();
      }
    }
    return true;
  }
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
               double weight, bool want_coupling) {
    if constexpr (HasSliceSecondDerivatives<Element>::value) {
      if (model == HessianModel::kExact) {
        element.SliceSecondDerivatives(previous, own, next, weight,
                                       want_coupling, this);
        return;
      }
    }
    ComputeBySides(model, element, previous, own, next, weight, want_coupling);
  }

  // The reference the element's SliceSecondDerivatives is tested against.
  template <class Element>
  void ComputeBySides(HessianModel model, const Element& element,
                      const double* previous, const double* own,
                      const double* next, double weight, bool want_coupling) {
    using D = ElementSecondDerivatives<kVertices>;
    before_ok =
        before_.ComputeModel(model, element, previous, own,
                             ShellSide::kDeformed, weight, D::Rows::kDeformed);
    after_ok = after_.ComputeModel(
        model, element, own, next, ShellSide::kReference, weight,
        want_coupling ? D::Rows::kBoth : D::Rows::kReference);
    if (before_ok && after_ok) {
      diagonal.noalias() = before_.d_grad_deformed + after_.d_grad_reference;
    }
    if (after_ok && want_coupling) coupling = after_.d_grad_deformed;
  }

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
               double weight, bool a_free, bool b_free) {
    using D = ElementSecondDerivatives<kVertices>;
    if (a_free && b_free) {
      if (!a_active_.ComputeModel(HessianModel::kExact, element, a, b,
                                  ShellSide::kReference, weight,
                                  D::Rows::kBoth) ||
          !b_active_.ComputeModel(HessianModel::kExact, element, a, b,
                                  ShellSide::kDeformed, weight,
                                  D::Rows::kDeformed)) {
        return false;
      }
      term_.template topLeftCorner<n, n>() = a_active_.d_grad_reference;
      term_.template bottomLeftCorner<n, n>() = a_active_.d_grad_deformed;
      term_.template topRightCorner<n, n>() =
          a_active_.d_grad_deformed.transpose();
      term_.template bottomRightCorner<n, n>() = b_active_.d_grad_deformed;
      projected =
          ProjectToPositiveSemidefiniteModuloTranslations<kVertices, 2>(
              &term_);
      aa = term_.template topLeftCorner<n, n>();
      bb = term_.template bottomRightCorner<n, n>();
      ba = term_.template bottomLeftCorner<n, n>();
      return true;
    }
    if (a_free) {
      if (!a_active_.ComputeModel(HessianModel::kExact, element, a, b,
                                  ShellSide::kReference, weight,
                                  D::Rows::kReference)) {
        return false;
      }
      aa = a_active_.d_grad_reference;
      projected =
          ProjectToPositiveSemidefiniteModuloTranslations<kVertices, 1>(&aa);
      return true;
    }
    if (!b_active_.ComputeModel(HessianModel::kExact, element, a, b,
                                ShellSide::kDeformed, weight,
                                D::Rows::kDeformed)) {
      return false;
    }
    bb = b_active_.d_grad_deformed;
    projected =
        ProjectToPositiveSemidefiniteModuloTranslations<kVertices, 1>(&bb);
    return true;
  }

 private:
  ElementSecondDerivatives<kVertices> a_active_, b_active_;
  Eigen::Matrix<double, 2 * n, 2 * n> term_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_HESSIAN_H_
