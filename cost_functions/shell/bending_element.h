// One interior edge's bending residual (Discrete Shells) with Jacobians w.r.t.
// reference and deformed vertices of the edge flap.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_BENDING_ELEMENT_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_BENDING_ELEMENT_H_

#include <Eigen/Core>

#include "shellspace/geometry/element_geometry.h"

namespace shellspace {

// For the flap (i, j, k, l) of geometry/topology.h:
//   r = sqrt(2 eta wbar) (theta - thetabar),  wbar = 3 |Ebar|^2 / (abar_0 +
//   abar_1),
// so 1/2 r^2 = eta (theta - thetabar)^2 |Ebar|^2 / dbar_E (shells.md). theta
// is the signed dihedral angle (geometry/element_geometry.h). Jacobians are
// 1 x 12, columns (i, j, k, l) x (x, y, z). An element type of the element
// set (element_set.h): stencil (i, j, k, l), weight eta (= this eta).
struct BendingElement {
  static constexpr int kNumVertices = 4;
  static constexpr int kNumResiduals = 1;
  template <typename T>
  using Jacobian = Eigen::Matrix<T, 1, 12>;

  double eta = 0.01;

  template <typename T>
  bool Evaluate(const Vec3<T>* ref, const Vec3<T>* def, T* residual,
                Jacobian<T>* jacobian_reference,
                Jacobian<T>* jacobian_deformed) const {
    const TriangleArea<T> area0(ref[0], ref[1], ref[2]);
    const TriangleArea<T> area1(ref[1], ref[0], ref[3]);
    const T area_sum = area0.area + area1.area;
    if (!(ScalarValue(area0.area) > 0.0 && ScalarValue(area1.area) > 0.0)) {
      return false;
    }
    const Vec3<T> edge = ref[1] - ref[0];
    const T edge_sq = edge.squaredNorm();
    const T weight = T(3) * edge_sq / area_sum;
    const T scale = sqrt(T(2.0 * eta) * weight);
    const DihedralAngle<T> angle(def[0], def[1], def[2], def[3]);
    const DihedralAngle<T> angle_bar(ref[0], ref[1], ref[2], ref[3]);
    const T delta = angle.theta - angle_bar.theta;
    if (!std::isfinite(ScalarValue(delta))) return false;
    residual[0] = scale * delta;
    if (jacobian_deformed) {
      for (int v = 0; v < 4; ++v) {
        jacobian_deformed->template segment<3>(3 * v) =
            scale * angle.grad[v].transpose();
      }
    }
    if (jacobian_reference) {
      // d scale = eta d weight / scale,
      // d weight = 3 d|Ebar|^2 / A - 3 |Ebar|^2 dA / A^2, A = abar_0 + abar_1.
      Vec3<T> d_area[4];
      d_area[0] = area0.grad[0] + area1.grad[1];
      d_area[1] = area0.grad[1] + area1.grad[0];
      d_area[2] = area0.grad[2];
      d_area[3] = area1.grad[2];
      const Vec3<T> zero = Vec3<T>::Zero();
      const Vec3<T> d_edge_sq[4] = {T(-2) * edge, T(2) * edge, zero, zero};
      for (int v = 0; v < 4; ++v) {
        const Vec3<T> d_weight =
            T(3) * d_edge_sq[v] / area_sum -
            (T(3) * edge_sq / (area_sum * area_sum)) * d_area[v];
        const Vec3<T> d_scale = T(eta) * d_weight / scale;
        jacobian_reference->template segment<3>(3 * v) =
            (d_scale * delta - scale * angle_bar.grad[v]).transpose();
      }
    }
    return true;
  }

  // The unweighted term (theta - thetabar)^2 |Ebar|^2 / dbar_E, dbar_E =
  // (abar_0 + abar_1) / 3, in closed form (without eta). False if it is not
  // finite.
  bool Energy(const Vec3<double>* ref, const Vec3<double>* def,
              double* energy) const {
    const DihedralAngle<double> theta(def[0], def[1], def[2], def[3]);
    const DihedralAngle<double> theta_bar(ref[0], ref[1], ref[2], ref[3]);
    const TriangleArea<double> a0(ref[0], ref[1], ref[2]);
    const TriangleArea<double> a1(ref[1], ref[0], ref[3]);
    const double edge_sq = (ref[1] - ref[0]).squaredNorm();
    const double delta = theta.theta - theta_bar.theta;
    const double e = delta * delta * edge_sq / ((a0.area + a1.area) / 3);
    if (!std::isfinite(e)) return false;
    *energy = e;
    return true;
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_BENDING_ELEMENT_H_
