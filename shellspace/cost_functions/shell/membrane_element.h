// One triangle's membrane residuals with Jacobians w.r.t. reference and
// deformed vertices: the membrane law (membrane_law.h) composed with the
// triangle distortion (geometry/triangle_distortion.h); its hand-derived
// second derivatives through the first fundamental forms
// (membrane_form_derivatives.h).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_ELEMENT_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_ELEMENT_H_

#include <Eigen/Core>

#include <cmath>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/cost_functions/shell/membrane_form_derivatives.h"
#include "shellspace/cost_functions/shell/membrane_law.h"
#include "shellspace/geometry/element_geometry.h"
#include "shellspace/geometry/triangle_distortion.h"

namespace shellspace {

// r(Xbar_i, Xbar_j, Xbar_k, X_i, X_j, X_k) in R^4 with 1/2 |r|^2 =
// abar W_m(G) (membrane_law.h). Jacobians are 4 x 9, columns (i, j, k) x (x,
// y, z), row-major like Ceres' Jacobian blocks. An element type of the
// element set (element_set.h): stencil (i, j, k), weight 1.
struct MembraneElement {
  static constexpr int kNumVertices = 3;
  static constexpr int kNumResiduals = 4;
  template <typename T>
  using Jacobian = Eigen::Matrix<T, 4, 9, Eigen::RowMajor>;

  MembraneLaw law;

  template <typename T>
  bool Evaluate(const Vec3<T>* ref, const Vec3<T>* def, T* residuals,
                Jacobian<T>* jacobian_reference,
                Jacobian<T>* jacobian_deformed) const {
    const bool derivatives = jacobian_reference || jacobian_deformed;
    const TriangleDistortion<T> dist(ref, def, derivatives);
    if (!(ScalarValue(dist.reference_area) > 0.0)) return false;
    T dr[4][4];
    if (!law.Evaluate(dist.a, dist.b, dist.c, dist.reference_area, residuals,
                      derivatives ? dr : nullptr)) {
      return false;
    }
    for (int m = 0; m < 4; ++m) {
      for (int v = 0; v < 3; ++v) {
        if (jacobian_deformed) {
          jacobian_deformed->template block<1, 3>(m, 3 * v) =
              (dr[m][0] * dist.d_deformed[0][v] +
               dr[m][1] * dist.d_deformed[1][v] +
               dr[m][2] * dist.d_deformed[2][v])
                  .transpose();
        }
        if (jacobian_reference) {
          jacobian_reference->template block<1, 3>(m, 3 * v) =
              (dr[m][0] * dist.d_reference[0][v] +
               dr[m][1] * dist.d_reference[1][v] +
               dr[m][2] * dist.d_reference[2][v] + dr[m][3] * dist.d_area[v])
                  .transpose();
        }
      }
    }
    return true;
  }

  // Energy, gradients and second derivatives (element_hessian.h) of e =
  // abar W_m(gbar^-1 g) = F(p, q) (membrane_form_derivatives.h), p, q the
  // entries of gbar, g (FirstFundamentalForm), chained to the 9 coordinates
  // of each triangle with J_p = dp/dXbar, J_q = dq/dX (3 x 9):
  //   d_X e = J_q^T F_q,  d_Xbar e = J_p^T F_p,
  //   D_2^2 e = J_q^T F_qq J_q + sum_m F_q,m d2q_m/dX2,
  //   D_1^2 e = J_p^T F_pp J_p + sum_m F_p,m d2p_m/dXbar2,
  //   d_Xbar d_X e = J_p^T F_pq J_q   (rows Xbar, columns X),
  // where d2g11/dX2 = 2 a a^T (x) I, d2g12/dX2 = (a b^T + b a^T) (x) I,
  // d2g22/dX2 = 2 b b^T (x) I with a = (-1, 1, 0), b = (-1, 0, 1) over the
  // vertices (i, j, k). The energy is the closed form (as Energy), the
  // gradients equal J^T r of Evaluate up to round-off. False exactly for a
  // degenerate triangle (det gbar or det g not positive and finite).
  bool SecondDerivatives(const double* reference, const double* deformed,
                         ShellSide active, double weight,
                         ElementSecondDerivatives<3>::Rows rows,
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
    if (!f.Compute(law.mu, law.lambda, p, q, want_ref && !deformed_active,
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
        out->d_grad_reference = weight * FormHessian(jp, f.h_pp, f.grad_p);
      }
    }
    if (want_def) {
      out->grad_deformed = weight * (jq.transpose() * f.grad_q);
      if (deformed_active) {
        out->d_grad_deformed = weight * FormHessian(jq, f.h_qq, f.grad_q);
      } else {
        out->d_grad_deformed =
            weight * Mat9(jq.transpose() * f.h_pq.transpose() * jp);
      }
    }
    return true;
  }

  // ElementSliceSecondDerivatives (element_hessian.h) for the exact model.
  // Both second derivatives w.r.t. X go through X's form x = (g11, g12, g22)
  // (J_x = dx/dX): D_2^2 e[P, X] = FormHessian(J_x, F_qq^A, F_q^A) and
  // D_1^2 e[X, N] = FormHessian(J_x, F_pp^B, F_p^B), and FormHessian is
  // linear in its last two arguments, so
  //   diagonal = weight FormHessian(J_x, F_qq^A + F_pp^B, F_q^A + F_p^B),
  //   coupling = weight J_n^T (F_pq^B)^T J_x     (rows N, columns X).
  void SliceSecondDerivatives(const double* previous, const double* own,
                              const double* next, double weight,
                              bool want_coupling,
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
    out->before_ok =
        before.Compute(law.mu, law.lambda, p, x, false, true, false);
    out->after_ok =
        after.Compute(law.mu, law.lambda, x, n, true, false, want_coupling);
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
    out->diagonal = weight * FormHessian(jx, before.h_qq + after.h_pp,
                                         before.grad_q + after.grad_p);
  }

  // J^T H J + sum_m G_m d2(form entry m)/dX2 for a first fundamental form
  // with Jacobian J (3 x 9), its Hessian H and gradient G w.r.t. the entries.
  static Eigen::Matrix<double, 9, 9> FormHessian(
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

  // abar W_m(gbar^-1 g) in closed form from the first fundamental forms
  // (tr and det of gbar^-1 g = adj(gbar) g / det gbar), independently of the
  // residuals. False (energy unchanged) if either triangle is degenerate.
  bool Energy(const Vec3<double>* ref, const Vec3<double>* def,
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
    const double mu = law.mu, lambda = law.lambda;
    *energy = area * (mu / 2 * tr + lambda / 4 * det -
                      (mu / 2 + lambda / 4) * std::log(det) - mu - lambda / 4);
    return true;
  }
};

// Its second derivatives are compiled once, in membrane_element.cc.
SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(extern template, MembraneElement);

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_ELEMENT_H_
