// The definitions of the member templates of element_hessian.h
// (ElementSecondDerivatives, ElementSliceSecondDerivatives,
// ElementTermSecondDerivatives). The element types of the element set have
// them compiled once, in the cost_functions library (membrane_element.cc,
// bending_element.cc, shape_operator_element_<m>.cc, declared there by
// SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(extern template, E) next to each
// type): include this file only to instantiate them for an element type of
// one's own.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_HESSIAN_INL_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_HESSIAN_INL_H_

#include <ceres/jet.h>

#include <Eigen/Core>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/cost_functions/shell/psd_projection.h"
#include "shellspace/geometry/scalar_traits.h"

namespace shellspace {

template <int kVertices>
template <class Element>
bool ElementSecondDerivatives<kVertices>::Compute(const Element& element,
                                                  const double* reference,
                                                  const double* deformed,
                                                  ShellSide active,
                                                  double weight, Rows rows) {
  static_assert(Element::kNumVertices == kVertices,
                "ElementSecondDerivatives: stencil size mismatch");
  if constexpr (HasAnalyticSecondDerivatives<Element>::value) {
    return element.SecondDerivatives(reference, deformed, active, weight, rows,
                                     this);
  } else {
    return ComputeWithDualNumbers(element, reference, deformed, active, weight,
                                  rows);
  }
}

template <int kVertices>
template <class Element>
bool ElementSecondDerivatives<kVertices>::ComputeModel(
    HessianModel model, const Element& element, const double* reference,
    const double* deformed, ShellSide active, double weight, Rows rows) {
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
  const auto& jac_active = active == ShellSide::kReference ? jac_ref : jac_def;
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

template <int kVertices>
template <class Element>
bool ElementSecondDerivatives<kVertices>::ComputeWithDualNumbers(
    const Element& element, const double* reference, const double* deformed,
    ShellSide active, double weight, Rows rows) {
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

template <int kVertices>
template <class Element>
void ElementSliceSecondDerivatives<kVertices>::Compute(
    HessianModel model, const Element& element, const double* previous,
    const double* own, const double* next, double weight, bool want_coupling) {
  if constexpr (HasSliceSecondDerivatives<Element>::value) {
    if (model == HessianModel::kExact) {
      element.SliceSecondDerivatives(previous, own, next, weight, want_coupling,
                                     this);
      return;
    }
  }
  ComputeBySides(model, element, previous, own, next, weight, want_coupling);
}

template <int kVertices>
template <class Element>
void ElementSliceSecondDerivatives<kVertices>::ComputeBySides(
    HessianModel model, const Element& element, const double* previous,
    const double* own, const double* next, double weight, bool want_coupling) {
  using D = ElementSecondDerivatives<kVertices>;
  before_ok =
      before_.ComputeModel(model, element, previous, own, ShellSide::kDeformed,
                           weight, D::Rows::kDeformed);
  after_ok = after_.ComputeModel(
      model, element, own, next, ShellSide::kReference, weight,
      want_coupling ? D::Rows::kBoth : D::Rows::kReference);
  if (before_ok && after_ok) {
    diagonal.noalias() = before_.d_grad_deformed + after_.d_grad_reference;
  }
  if (after_ok && want_coupling) coupling = after_.d_grad_deformed;
}

template <int kVertices>
template <class Element>
bool ElementTermSecondDerivatives<kVertices>::Compute(
    const Element& element, const double* a, const double* b, double weight,
    bool a_free, bool b_free) {
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
        ProjectToPositiveSemidefiniteModuloTranslations<kVertices, 2>(&term_);
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

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_HESSIAN_INL_H_
