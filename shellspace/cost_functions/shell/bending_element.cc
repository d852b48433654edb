// BendingElement's closed-form energy and second derivatives, and its
// element_hessian.h instantiations, compiled once.
#include "shellspace/cost_functions/shell/bending_element.h"

#include <cmath>

#include "shellspace/cost_functions/shell/element_hessian-inl.h"

namespace shellspace {

bool BendingElement::SecondDerivatives(const double* reference,
                                       const double* deformed, ShellSide active,
                                       double weight,
                                       ElementSecondDerivatives<4>::Rows rows,
                                       ElementSecondDerivatives<4>* out) const {
  using D = ElementSecondDerivatives<4>;
  using Vec12 = Eigen::Matrix<double, 12, 1>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;
  const StencilPositions<4> x(reference, deformed);
  const Stencil<double> s(x.ref, x.def, eta);
  if (!s.ok) return false;
  const bool want_ref = D::WantsReference(rows);
  const bool want_def = D::WantsDeformed(rows);
  const bool deformed_active = active == ShellSide::kDeformed;
  const double r = s.scale * s.delta;
  out->energy = 0.5 * weight * r * r;
  Vec12 d_theta, d_theta_bar, d_wbar;
  for (int v = 0; v < 4; ++v) {
    d_theta.segment<3>(3 * v) = s.angle.grad[v];
    d_theta_bar.segment<3>(3 * v) = s.angle_bar.grad[v];
  }
  if (want_def) {
    out->grad_deformed = weight * ((s.scale * d_theta) * r);
  }
  Vec3<double> d_area[4], d_weight[4];
  if (want_ref) {
    s.WeightGradient(d_area, d_weight);
    for (int v = 0; v < 4; ++v) {
      d_wbar.segment<3>(3 * v) = d_weight[v];
      const Vec3<double> d_scale = eta * d_weight[v] / s.scale;
      out->grad_reference.segment<3>(3 * v) =
          weight * ((d_scale * s.delta - s.scale * s.angle_bar.grad[v]) * r);
    }
  }
  // (delta dwbar - wbar dthetabar): the mixed block is 2 eta (this) dtheta^T.
  auto mixed_left = [&]() {
    if (!want_ref) {
      s.WeightGradient(d_area, d_weight);
      for (int v = 0; v < 4; ++v) d_wbar.segment<3>(3 * v) = d_weight[v];
    }
    return Vec12(s.delta * d_wbar - s.weight * d_theta_bar);
  };
  if (deformed_active) {
    if (want_def) {
      Mat12 h;
      s.angle.Hessian(&h);
      out->d_grad_deformed = (weight * 2 * eta * s.weight) *
                             (d_theta * d_theta.transpose() + s.delta * h);
    }
    if (want_ref) {
      out->d_grad_reference =
          (weight * 2 * eta) * (mixed_left() * d_theta.transpose());
    }
  } else {
    if (want_def) {
      out->d_grad_deformed =
          (weight * 2 * eta) * (d_theta * mixed_left().transpose());
    }
    if (want_ref) {
      const Mat12 d2_wbar = s.WeightHessian(d_area);
      Mat12 h_bar;
      s.angle_bar.Hessian(&h_bar);
      const Mat12 wt = d_wbar * d_theta_bar.transpose();
      out->d_grad_reference =
          (weight * eta) *
          (s.delta * s.delta * d2_wbar - 2 * s.delta * (wt + wt.transpose()) +
           2 * s.weight * d_theta_bar * d_theta_bar.transpose() -
           2 * s.weight * s.delta * h_bar);
    }
  }
  return true;
}

void BendingElement::SliceSecondDerivatives(
    const double* previous, const double* own, const double* next,
    double weight, bool want_coupling,
    ElementSliceSecondDerivatives<4>* out) const {
  using Vec12 = Eigen::Matrix<double, 12, 1>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;
  const StencilPositions<4> px(previous, own), xn(own, next);
  const Vec3<double>*p = px.ref, *x = px.def, *n = xn.def;
  const DihedralAngle<double> angle_p(p[0], p[1], p[2], p[3]);
  const DihedralAngle<double> angle_x(x[0], x[1], x[2], x[3]);
  const DihedralAngle<double> angle_n(n[0], n[1], n[2], n[3]);
  const Stencil<double> before(p, angle_x, angle_p, eta);
  const Stencil<double> after(x, angle_n, angle_x, eta);
  out->before_ok = before.ok;
  out->after_ok = after.ok;
  if (!after.ok) return;
  Vec12 d_x, d_wbar;
  Vec3<double> d_area[4], d_weight[4];
  after.WeightGradient(d_area, d_weight);
  for (int v = 0; v < 4; ++v) {
    d_x.segment<3>(3 * v) = angle_x.grad[v];
    d_wbar.segment<3>(3 * v) = d_weight[v];
  }
  if (want_coupling) {
    Vec12 d_n;
    for (int v = 0; v < 4; ++v) d_n.segment<3>(3 * v) = angle_n.grad[v];
    out->coupling =
        (weight * 2 * eta) *
        (d_n * (after.delta * d_wbar - after.weight * d_x).transpose());
  }
  if (!before.ok) return;
  Mat12 h;
  angle_x.Hessian(&h);
  const Mat12 wt = d_wbar * d_x.transpose();
  out->diagonal =
      (weight * eta) *
      (2 * (before.weight + after.weight) * d_x * d_x.transpose() +
       2 * (before.weight * before.delta - after.weight * after.delta) * h +
       after.delta * after.delta * after.WeightHessian(d_area) -
       2 * after.delta * (wt + wt.transpose()));
}

bool BendingElement::Energy(const Vec3<double>* ref, const Vec3<double>* def,
                            double* energy) const {
  const DihedralAngle<double> theta(def[0], def[1], def[2], def[3]);
  const DihedralAngle<double> theta_bar(ref[0], ref[1], ref[2], ref[3]);
  const TriangleArea<double> a0(ref[0], ref[1], ref[2]);
  const TriangleArea<double> a1(ref[1], ref[0], ref[3]);
  const double edge_sq = (ref[1] - ref[0]).squaredNorm();
  const double delta = DihedralAngleChange(theta.theta, theta_bar.theta);
  const double e = delta * delta * edge_sq / ((a0.area + a1.area) / 3);
  if (!std::isfinite(e)) return false;
  *energy = e;
  return true;
}

SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(template, BendingElement);

}  // namespace shellspace
