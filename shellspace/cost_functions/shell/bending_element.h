// One interior edge's bending residual (Discrete Shells) with Jacobians w.r.t.
// reference and deformed vertices of the edge flap.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_BENDING_ELEMENT_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_BENDING_ELEMENT_H_

#include <Eigen/Core>

#include <cmath>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/geometry/element_geometry.h"

namespace shellspace {

// For the flap (i, j, k, l) of geometry/topology.h:
//   r = sqrt(2 eta wbar) (theta - thetabar),  wbar = 3 |Ebar|^2 / (abar_0 +
//   abar_1),
// so 1/2 r^2 = eta (theta - thetabar)^2 |Ebar|^2 / dbar_E (docs/math.md,
// "Bending energy: two models"). theta is the signed dihedral angle
// (geometry/element_geometry.h), in (-pi, pi]; theta - thetabar is taken in
// [-pi, pi) (DihedralAngleChange), smooth across the branch cut for a flap
// folded to nearly +-pi. Jacobians: 1 x 12, columns (i, j, k, l) x (x, y, z).
// Element type of element_set.h: stencil (i, j, k, l), weight eta (= this eta).
struct BendingElement {
  static constexpr int kNumVertices = 4;
  static constexpr int kNumResiduals = 1;
  template <typename T>
  using Jacobian = Eigen::Matrix<T, 1, 12>;

  double eta = 0.01;

  // The stencil quantities of one flap, shared by Evaluate and
  // SecondDerivatives: the reference areas, the dihedral angles of both
  // sides, wbar, scale = sqrt(2 eta wbar), delta = theta - thetabar. `ok` is
  // false for a degenerate flap (then the angles are not computed).
  template <typename T>
  struct Stencil {
    TriangleArea<T> area0, area1;
    T area_sum, edge_sq, weight, scale, delta;
    Vec3<T> edge;
    DihedralAngle<T> angle, angle_bar;
    bool ok = false;

    Stencil(const Vec3<T>* ref, const Vec3<T>* def, double eta)
        : area0(ref[0], ref[1], ref[2]),
          area1(ref[1], ref[0], ref[3]),
          angle(def[0], def[1], def[2], def[3]),
          angle_bar(ref[0], ref[1], ref[2], ref[3]) {
      Finish(ref, eta);
    }
    // The same with the two dihedral angles already computed (of def and of
    // ref; a shape's angle is shared by the two terms it is part of).
    Stencil(const Vec3<T>* ref, const DihedralAngle<T>& angle_def,
            const DihedralAngle<T>& angle_ref, double eta)
        : area0(ref[0], ref[1], ref[2]),
          area1(ref[1], ref[0], ref[3]),
          angle(angle_def),
          angle_bar(angle_ref) {
      Finish(ref, eta);
    }

    // d2 wbar / dXbar2 (12 x 12) from d_area (WeightGradient):
    //   3 d2|Ebar|^2 / A - 3 (d|Ebar|^2 dA^T + dA d|Ebar|^2^T) / A^2
    //   + 6 |Ebar|^2 dA dA^T / A^3 - 3 |Ebar|^2 d2A / A^2.
    Eigen::Matrix<T, 12, 12> WeightHessian(const Vec3<T>* d_area) const {
      using Mat12 = Eigen::Matrix<T, 12, 12>;
      using Vec12 = Eigen::Matrix<T, 12, 1>;
      Eigen::Matrix<T, 9, 9> h0, h1;
      area0.Hessian(&h0);
      area1.Hessian(&h1);
      Mat12 d2_area = Mat12::Zero();
      const int map0[3] = {0, 1, 2}, map1[3] = {1, 0, 3};
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          d2_area.template block<3, 3>(3 * map0[a], 3 * map0[b]) +=
              h0.template block<3, 3>(3 * a, 3 * b);
          d2_area.template block<3, 3>(3 * map1[a], 3 * map1[b]) +=
              h1.template block<3, 3>(3 * a, 3 * b);
        }
      }
      Vec12 d_a = Vec12::Zero(), d_edge_sq = Vec12::Zero();
      for (int v = 0; v < 4; ++v) d_a.template segment<3>(3 * v) = d_area[v];
      d_edge_sq.template segment<3>(0) = T(-2) * edge;
      d_edge_sq.template segment<3>(3) = T(2) * edge;
      const T area = area_sum;
      const T area2 = area * area;
      const Mat12 cross = d_edge_sq * d_a.transpose();
      Mat12 d2_wbar =
          (T(6) * edge_sq / (area2 * area)) * d_a * d_a.transpose() -
          (T(3) / area2) * (cross + cross.transpose()) -
          (T(3) * edge_sq / area2) * d2_area;
      for (int c = 0; c < 3; ++c) {
        d2_wbar(c, c) += T(6) / area;
        d2_wbar(3 + c, 3 + c) += T(6) / area;
        d2_wbar(c, 3 + c) -= T(6) / area;
        d2_wbar(3 + c, c) -= T(6) / area;
      }
      return d2_wbar;
    }

    void Finish(const Vec3<T>* ref, double eta) {
      area_sum = area0.area + area1.area;
      if (!(ScalarValue(area0.area) > 0.0 && ScalarValue(area1.area) > 0.0)) {
        return;
      }
      edge = ref[1] - ref[0];
      edge_sq = edge.squaredNorm();
      weight = T(3) * edge_sq / area_sum;
      scale = sqrt(T(2.0 * eta) * weight);
      delta = DihedralAngleChange(angle.theta, angle_bar.theta);
      ok = std::isfinite(ScalarValue(delta));
    }

    // d_weight[v] = d wbar / d Xbar_v:
    // d wbar = 3 d|Ebar|^2 / A - 3 |Ebar|^2 dA / A^2, A = abar_0 + abar_1.
    void WeightGradient(Vec3<T>* d_area, Vec3<T>* d_weight) const {
      d_area[0] = area0.grad[0] + area1.grad[1];
      d_area[1] = area0.grad[1] + area1.grad[0];
      d_area[2] = area0.grad[2];
      d_area[3] = area1.grad[2];
      const Vec3<T> zero = Vec3<T>::Zero();
      const Vec3<T> d_edge_sq[4] = {T(-2) * edge, T(2) * edge, zero, zero};
      for (int v = 0; v < 4; ++v) {
        d_weight[v] = T(3) * d_edge_sq[v] / area_sum -
                      (T(3) * edge_sq / (area_sum * area_sum)) * d_area[v];
      }
    }
  };

  template <typename T>
  bool Evaluate(const Vec3<T>* ref, const Vec3<T>* def, T* residual,
                Jacobian<T>* jacobian_reference,
                Jacobian<T>* jacobian_deformed) const {
    const Stencil<T> s(ref, def, eta);
    if (!s.ok) return false;
    residual[0] = s.scale * s.delta;
    if (jacobian_deformed) {
      for (int v = 0; v < 4; ++v) {
        jacobian_deformed->template segment<3>(3 * v) =
            s.scale * s.angle.grad[v].transpose();
      }
    }
    if (jacobian_reference) {
      // d scale = eta d weight / scale.
      Vec3<T> d_area[4], d_weight[4];
      s.WeightGradient(d_area, d_weight);
      for (int v = 0; v < 4; ++v) {
        const Vec3<T> d_scale = T(eta) * d_weight[v] / s.scale;
        jacobian_reference->template segment<3>(3 * v) =
            (d_scale * s.delta - s.scale * s.angle_bar.grad[v]).transpose();
      }
    }
    return true;
  }

  // Energy, gradients and second derivatives (element_hessian.h) of
  // e = 1/2 r^2 = eta wbar delta^2, from the Stencil (no dual numbers):
  //   D_2^2 e = 2 eta wbar (dtheta dtheta^T + delta d2theta),
  //   d_Xbar d_X e = 2 eta (delta dwbar - wbar dthetabar) dtheta^T
  //                  (rows Xbar, columns X),
  //   D_1^2 e = eta (delta^2 d2wbar - 2 delta (dwbar dthetabar^T +
  //             dthetabar dwbar^T) + 2 wbar dthetabar dthetabar^T
  //             - 2 wbar delta d2thetabar),
  //   d2wbar = 3 d2|Ebar|^2 / A - 3 (d|Ebar|^2 dA^T + dA d|Ebar|^2^T) / A^2
  //            + 6 |Ebar|^2 dA dA^T / A^3 - 3 |Ebar|^2 d2A / A^2,
  // with d2theta (DihedralAngle::Hessian), d2A the sum of the two triangle
  // area Hessians (TriangleArea::Hessian), d2|Ebar|^2 = 2 c c^T (x) I, c =
  // (-1, 1, 0, 0). The energy and the gradients are computed exactly as
  // 1/2 r^2 and J^T r of Evaluate.
  bool SecondDerivatives(const double* reference, const double* deformed,
                         ShellSide active, double weight,
                         ElementSecondDerivatives<4>::Rows rows,
                         ElementSecondDerivatives<4>* out) const;

  // ElementSliceSecondDerivatives (element_hessian.h) for the exact model,
  // with X's dihedral angle (and its Hessian H_X) computed once. With wbar_A,
  // delta_A of e[P, X] and wbar_B, delta_B, dwbar_B of e[X, N] (wbar_B and
  // its derivatives from X's areas), dX = dtheta(X), dN = dtheta(N), the
  // two blocks of SecondDerivatives add up to
  //   diagonal = weight eta (2 (wbar_A + wbar_B) dX dX^T
  //              + 2 (wbar_A delta_A - wbar_B delta_B) H_X
  //              + delta_B^2 d2wbar_B - 2 delta_B (dwbar_B dX^T + dX
  //              dwbar_B^T)),
  //   coupling = 2 weight eta dN (delta_B dwbar_B - wbar_B dX)^T.
  void SliceSecondDerivatives(const double* previous, const double* own,
                              const double* next, double weight,
                              bool want_coupling,
                              ElementSliceSecondDerivatives<4>* out) const;

  // The unweighted term (theta - thetabar)^2 |Ebar|^2 / dbar_E, dbar_E =
  // (abar_0 + abar_1) / 3, in closed form (without eta). False if it is not
  // finite.
  bool Energy(const Vec3<double>* ref, const Vec3<double>* def,
              double* energy) const;
};

// Its second derivatives are compiled once, in bending_element.cc.
SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(extern template, BendingElement);

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_BENDING_ELEMENT_H_
