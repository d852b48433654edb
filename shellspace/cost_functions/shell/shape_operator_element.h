// One face's bending residuals of the discrete shape operator (docs/math.md,
// "Bending energy: two models"), Jacobians w.r.t. both shells' vertices.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_SHAPE_OPERATOR_ELEMENT_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_SHAPE_OPERATOR_ELEMENT_H_

#include <Eigen/Core>

#include <cmath>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/geometry/element_geometry.h"
#include "shellspace/geometry/mid_edge_second_form.h"

namespace shellspace {

// The shape-operator bending term of one face T (docs/math.md, "Bending
// energy: two models"): e_T = abar (alpha (tr M)^2 + beta tr(M^2)) with
// M = Gbar^-1 (H - Hbar), H, Hbar the mid-edge second forms of the deformed
// and reference face (geometry/mid_edge_second_form.h), Gbar, abar the first
// fundamental form and area of the reference face. Residuals: with Gbar =
// L L^T (Cholesky) and K = L^-1 (H - Hbar) L^-T = [[k11, k12], [k12, k22]],
//   r = sqrt(eta) ( sqrt(2 abar (alpha + beta/2)) (k11 + k22),
//                   sqrt(abar beta) (k11 - k22),  2 sqrt(abar beta) k12 ),
// so 1/2 |r|^2 = eta e_T.
//
// Stencil (3 + kInterior vertices): the face's vertices X_0, X_1, X_2
// (counter-clockwise, rotated so that its kInterior interior edges are the
// edges 0 .. kInterior - 1, edge i opposite X_i) then P_0 .. P_{kInterior-1},
// the vertex across interior edge i. Jacobians are 3 x 3 (3 + kInterior),
// row-major, columns (X_0, X_1, X_2, P_0, ...) x (x, y, z).
//
// Derivatives: dK/dX = K(dH) (K(.) = L^-1 (.) L^-T is linear); w.r.t. the
// reference, with Omega = L^-1 dGbar L^-T and Phi(Omega) its lower triangle
// with halved diagonal (= L^-1 dL),
//   dK = -Phi K - K Phi^T - L^-1 dHbar L^-T,  d sqrt(abar) = dabar / (2
//   sqrt(abar)).
// An element type of the element set (element_set.h), one group per
// kInterior = 3, 2, 1, 0, weight eta (= this eta). Valid while the reference
// face has positive area and no interior edge is folded flat onto its
// neighbour (N + N_i = 0) in either shell.
template <int kInterior>
struct ShapeOperatorElement {
  static_assert(kInterior >= 0 && kInterior <= 3, "a face has 3 edges");
  static constexpr int kNumVertices = 3 + kInterior;
  static constexpr int kNumResiduals = 3;
  template <typename T>
  using Jacobian = Eigen::Matrix<T, 3, 3 * kNumVertices, Eigen::RowMajor>;

  double eta = 0.01;
  double alpha = 0;
  double beta = 1;

  template <typename T>
  bool Evaluate(const Vec3<T>* ref, const Vec3<T>* def, T* residuals,
                Jacobian<T>* jacobian_reference,
                Jacobian<T>* jacobian_deformed) const {
    const TriangleArea<T> area(ref[0], ref[1], ref[2]);
    if (!(ScalarValue(area.area) > 0.0)) return false;
    const FirstFundamentalForm<T> gbar(ref[0], ref[1], ref[2]);
    const MidEdgeSecondForm<T, kInterior> h(def, jacobian_deformed != nullptr);
    const MidEdgeSecondForm<T, kInterior> hbar(ref,
                                               jacobian_reference != nullptr);
    if (!h.valid || !hbar.valid) return false;
    // L^-1 = [[p, 0], [q, s]].
    const T l11 = sqrt(gbar.g11);
    const T l21 = gbar.g12 / l11;
    const T l22_sq = gbar.g22 - l21 * l21;
    if (!(ScalarValue(l22_sq) > 0.0)) return false;
    const T l22 = sqrt(l22_sq);
    const T p = T(1) / l11, q = -l21 / (l11 * l22), s = T(1) / l22;
    // K(A) = L^-1 A L^-T for symmetric A = (a11, a12, a22).
    auto congruence = [&](const T& a11, const T& a12, const T& a22, T* k) {
      k[0] = p * p * a11;
      k[1] = p * (q * a11 + s * a12);
      k[2] = q * q * a11 + T(2) * q * s * a12 + s * s * a22;
    };
    T k[3];
    congruence(h.h11 - hbar.h11, h.h12 - hbar.h12, h.h22 - hbar.h22, k);
    const T sqrt_area = sqrt(area.area);
    const T scale_trace = T(std::sqrt(2 * eta * (alpha + beta / 2))) * sqrt_area;
    const T scale_dev = T(std::sqrt(eta * beta)) * sqrt_area;
    residuals[0] = scale_trace * (k[0] + k[2]);
    residuals[1] = scale_dev * (k[0] - k[2]);
    residuals[2] = T(2) * scale_dev * k[1];
    for (int m = 0; m < 3; ++m) {
      if (!std::isfinite(ScalarValue(residuals[m]))) return false;
    }
    auto residual_change = [&](const T* dk, const T& d_log_sqrt_area, T* dr) {
      dr[0] = d_log_sqrt_area * residuals[0] + scale_trace * (dk[0] + dk[2]);
      dr[1] = d_log_sqrt_area * residuals[1] + scale_dev * (dk[0] - dk[2]);
      dr[2] = d_log_sqrt_area * residuals[2] + T(2) * scale_dev * dk[1];
    };
    if (jacobian_deformed) {
      for (int v = 0; v < kNumVertices; ++v) {
        for (int c = 0; c < 3; ++c) {
          T dk[3], dr[3];
          congruence(h.grad[0][v](c), h.grad[1][v](c), h.grad[2][v](c), dk);
          residual_change(dk, T(0), dr);
          for (int m = 0; m < 3; ++m) (*jacobian_deformed)(m, 3 * v + c) = dr[m];
        }
      }
    }
    if (jacobian_reference) {
      for (int v = 0; v < kNumVertices; ++v) {
        for (int c = 0; c < 3; ++c) {
          T omega[3] = {T(0), T(0), T(0)};
          T d_log_sqrt_area(0);
          if (v < 3) {
            congruence(gbar.grad[0][v](c), gbar.grad[1][v](c),
                       gbar.grad[2][v](c), omega);
            d_log_sqrt_area = area.grad[v](c) / (T(2) * area.area);
          }
          T dhbar[3];
          congruence(hbar.grad[0][v](c), hbar.grad[1][v](c),
                     hbar.grad[2][v](c), dhbar);
          // Phi K + K Phi^T, Phi = [[w11/2, 0], [w12, w22/2]].
          const T sym11 = omega[0] * k[0];
          const T sym12 = T(0.5) * (omega[0] + omega[2]) * k[1] + omega[1] * k[0];
          const T sym22 = T(2) * omega[1] * k[1] + omega[2] * k[2];
          const T dk[3] = {-sym11 - dhbar[0], -sym12 - dhbar[1],
                           -sym22 - dhbar[2]};
          T dr[3];
          residual_change(dk, d_log_sqrt_area, dr);
          for (int m = 0; m < 3; ++m) {
            (*jacobian_reference)(m, 3 * v + c) = dr[m];
          }
        }
      }
    }
    return true;
  }

  // The unweighted e_T = abar (alpha (tr M)^2 + beta tr(M^2)) in closed form
  // from M = adj(Gbar) (H - Hbar) / det Gbar (no Cholesky, not the
  // residuals). False if the reference face is degenerate or an H is
  // undefined.
  bool Energy(const Vec3<double>* ref, const Vec3<double>* def,
              double* energy) const {
    const FirstFundamentalForm<double> g(ref[0], ref[1], ref[2]);
    const double det = g.g11 * g.g22 - g.g12 * g.g12;
    if (!(det > 0)) return false;
    const MidEdgeSecondForm<double, kInterior> h(def, false);
    const MidEdgeSecondForm<double, kInterior> hbar(ref, false);
    if (!h.valid || !hbar.valid) return false;
    const double d11 = h.h11 - hbar.h11, d12 = h.h12 - hbar.h12,
                 d22 = h.h22 - hbar.h22;
    // M = [[g22, -g12], [-g12, g11]] D / det.
    const double m11 = (g.g22 * d11 - g.g12 * d12) / det;
    const double m12 = (g.g22 * d12 - g.g12 * d22) / det;
    const double m21 = (g.g11 * d12 - g.g12 * d11) / det;
    const double m22 = (g.g11 * d22 - g.g12 * d12) / det;
    const double tr = m11 + m22;
    const double tr_sq = m11 * m11 + 2 * m12 * m21 + m22 * m22;
    const double e = 0.5 * std::sqrt(det) * (alpha * tr * tr + beta * tr_sq);
    if (!std::isfinite(e)) return false;
    *energy = e;
    return true;
  }
};

// Their second derivatives are compiled once, in
// shape_operator_element_<kInterior>.cc.
SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(extern template, ShapeOperatorElement<3>);
SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(extern template, ShapeOperatorElement<2>);
SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(extern template, ShapeOperatorElement<1>);
SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(extern template, ShapeOperatorElement<0>);

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_SHAPE_OPERATOR_ELEMENT_H_
