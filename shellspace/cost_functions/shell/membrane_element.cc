// MembraneElementOf's closed-form energy and second derivatives, and its
// element_hessian.h instantiations, compiled once for every registered law.
#include "shellspace/cost_functions/shell/membrane_element.h"

#include <cmath>

#include "shellspace/cost_functions/shell/element_hessian-inl.h"

namespace shellspace {

template <class Law>
bool MembraneElementOf<Law>::SecondDerivatives(
    const double* reference, const double* deformed, ShellSide active,
    double weight, ElementSecondDerivatives<3>::Rows rows,
    ElementSecondDerivatives<3>* out) const {
  using D = ElementSecondDerivatives<3>;
  using Mat39 = Eigen::Matrix<double, 3, 9>;
  using Mat9 = Eigen::Matrix<double, 9, 9>;
  const StencilPositions<3> x(reference, deformed);
  const FirstFundamentalForm<double> gbar(x.ref[0], x.ref[1], x.ref[2]);
  const FirstFundamentalForm<double> g(x.def[0], x.def[1], x.def[2]);
  const double p[3] = {gbar.g11, gbar.g12, gbar.g22};
  const double q[3] = {g.g11, g.g12, g.g22};
  const bool want_ref = D::WantsReference(rows);
  const bool want_def = D::WantsDeformed(rows);
  const bool deformed_active = active == ShellSide::kDeformed;
  MembraneFormDerivatives f;
  if (!f.Compute(law, p, q, want_ref && !deformed_active,
                 want_def && deformed_active,
                 deformed_active ? want_ref : want_def)) {
    return false;
  }
  Mat39 jp, jq;
  for (int m = 0; m < 3; ++m) {
    for (int v = 0; v < 3; ++v) {
      jp.block<1, 3>(m, 3 * v) = gbar.grad[m][v].transpose();
      jq.block<1, 3>(m, 3 * v) = g.grad[m][v].transpose();
    }
  }
  out->energy = weight * f.energy;
  if (want_ref) {
    out->grad_reference = weight * (jp.transpose() * f.grad_p);
    if (deformed_active) {
      out->d_grad_reference = weight * (jp.transpose() * f.h_pq * jq);
    } else {
      out->d_grad_reference = weight * MembraneFormHessian(jp, f.h_pp, f.grad_p);
    }
  }
  if (want_def) {
    out->grad_deformed = weight * (jq.transpose() * f.grad_q);
    if (deformed_active) {
      out->d_grad_deformed = weight * MembraneFormHessian(jq, f.h_qq, f.grad_q);
    } else {
      out->d_grad_deformed =
          weight * Mat9(jq.transpose() * f.h_pq.transpose() * jp);
    }
  }
  return true;
}

template <class Law>
void MembraneElementOf<Law>::SliceSecondDerivatives(
    const double* previous, const double* own, const double* next,
    double weight, bool want_coupling,
    ElementSliceSecondDerivatives<3>* out) const {
  using Mat39 = Eigen::Matrix<double, 3, 9>;
  const StencilPositions<3> px(previous, own), xn(own, next);
  const FirstFundamentalForm<double> gp(px.ref[0], px.ref[1], px.ref[2]);
  const FirstFundamentalForm<double> gx(px.def[0], px.def[1], px.def[2]);
  const FirstFundamentalForm<double> gn(xn.def[0], xn.def[1], xn.def[2]);
  const double p[3] = {gp.g11, gp.g12, gp.g22};
  const double x[3] = {gx.g11, gx.g12, gx.g22};
  const double n[3] = {gn.g11, gn.g12, gn.g22};
  MembraneFormDerivatives before, after;
  out->before_ok = before.Compute(law, p, x, false, true, false);
  out->after_ok =
      after.Compute(law, x, n, true, false, want_coupling);
  if (!out->after_ok) return;
  Mat39 jx;
  for (int m = 0; m < 3; ++m) {
    for (int v = 0; v < 3; ++v)
      jx.block<1, 3>(m, 3 * v) = gx.grad[m][v].transpose();
  }
  if (want_coupling) {
    Mat39 jn;
    for (int m = 0; m < 3; ++m) {
      for (int v = 0; v < 3; ++v) {
        jn.block<1, 3>(m, 3 * v) = gn.grad[m][v].transpose();
      }
    }
    out->coupling = weight * (jn.transpose() * after.h_pq.transpose() * jx);
  }
  if (!out->before_ok) return;
  out->diagonal = weight * MembraneFormHessian(jx, before.h_qq + after.h_pp,
                                       before.grad_q + after.grad_p);
}

Eigen::Matrix<double, 9, 9> MembraneFormHessian(
    const Eigen::Matrix<double, 3, 9>& j, const Eigen::Matrix3d& h,
    const Eigen::Vector3d& g) {
  Eigen::Matrix<double, 9, 9> out = j.transpose() * h * j;
  const Eigen::Vector3d a(-1, 1, 0), b(-1, 0, 1);
  const Eigen::Matrix3d ab = a * b.transpose();
  const Eigen::Matrix3d s = 2 * g(0) * a * a.transpose() +
                            g(1) * (ab + ab.transpose()) +
                            2 * g(2) * b * b.transpose();
  for (int v = 0; v < 3; ++v) {
    for (int w = 0; w < 3; ++w) {
      for (int c = 0; c < 3; ++c) out(3 * v + c, 3 * w + c) += s(v, w);
    }
  }
  return out;
}

template <class Law>
bool MembraneElementOf<Law>::Energy(const Vec3<double>* ref, const Vec3<double>* def,
                             double* energy) const {
  const FirstFundamentalForm<double> gbar(ref[0], ref[1], ref[2]);
  const FirstFundamentalForm<double> g(def[0], def[1], def[2]);
  const double det_gbar = gbar.g11 * gbar.g22 - gbar.g12 * gbar.g12;
  const double det_g = g.g11 * g.g22 - g.g12 * g.g12;
  if (!(det_gbar > 0) || !(det_g > 0)) return false;
  const double tr =
      (gbar.g22 * g.g11 - 2 * gbar.g12 * g.g12 + gbar.g11 * g.g22) / det_gbar;
  const double det = det_g / det_gbar;
  const double area = 0.5 * std::sqrt(det_gbar);
  return law.Energy(tr, det, area, energy);
}

#define SHELLSPACE_MEMBRANE_ELEMENT_INSTANCE(type, value, name) \
  template struct MembraneElementOf<type>;                      \
  SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(template, MembraneElementOf<type>);
SHELLSPACE_MEMBRANE_LAWS(SHELLSPACE_MEMBRANE_ELEMENT_INSTANCE)
#undef SHELLSPACE_MEMBRANE_ELEMENT_INSTANCE

}  // namespace shellspace
