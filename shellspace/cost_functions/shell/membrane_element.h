// One triangle's membrane residuals with Jacobians w.r.t. reference and
// deformed vertices: a membrane law (membrane_law.h) composed with the
// triangle distortion (geometry/triangle_distortion.h); its hand-derived
// second derivatives through the first fundamental forms
// (membrane_form_derivatives.h). One element type per registered law.
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
// abar W(G) of the law `Law` (membrane_law.h). Jacobians are 4 x 9, columns
// (i, j, k) x (x, y, z), row-major like Ceres' Jacobian blocks. An element
// type of the element set (element_set.h): stencil (i, j, k), weight 1.
template <class Law>
struct MembraneElementOf {
  static constexpr int kNumVertices = 3;
  static constexpr int kNumResiduals = 4;
  template <typename T>
  using Jacobian = Eigen::Matrix<T, 4, 9, Eigen::RowMajor>;

  Law law;

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
  // abar W(gbar^-1 g) = F(p, q) (membrane_form_derivatives.h), p, q the
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
                         ElementSecondDerivatives<3>* out) const;

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
                              ElementSliceSecondDerivatives<3>* out) const;

  // abar W(gbar^-1 g) in closed form from the first fundamental forms
  // (tr and det of gbar^-1 g = adj(gbar) g / det gbar), independently of the
  // residuals. False (energy unchanged) if either triangle is degenerate.
  bool Energy(const Vec3<double>* ref, const Vec3<double>* def,
              double* energy) const;
};

// J^T H J + sum_m G_m d2(form entry m)/dX2 for a first fundamental form
// with Jacobian J (3 x 9), its Hessian H and gradient G w.r.t. the entries.
Eigen::Matrix<double, 9, 9> MembraneFormHessian(
    const Eigen::Matrix<double, 3, 9>& j, const Eigen::Matrix3d& h,
    const Eigen::Vector3d& g);

// The element of the specification's law.
using MembraneElement = MembraneElementOf<NeoHookeanLaw>;

// Every registered law's element and its second derivatives are compiled
// once, in membrane_element.cc.
#define SHELLSPACE_MEMBRANE_ELEMENT_EXTERN(type, value, name) \
  extern template struct MembraneElementOf<type>;             \
  SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(extern template, MembraneElementOf<type>);
SHELLSPACE_MEMBRANE_LAWS(SHELLSPACE_MEMBRANE_ELEMENT_EXTERN)
#undef SHELLSPACE_MEMBRANE_ELEMENT_EXTERN

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_ELEMENT_H_
