// One triangle's membrane residuals with Jacobians w.r.t. reference and
// deformed vertices: the membrane law (membrane_law.h) composed with the
// triangle distortion (geometry/triangle_distortion.h).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_ELEMENT_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_ELEMENT_H_

#include <Eigen/Core>

#include <cmath>

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

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_ELEMENT_H_
