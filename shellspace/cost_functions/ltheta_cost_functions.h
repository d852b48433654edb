// Residuals of the LΘA reconstruction (docs/math.md, "Riemannian splines"): a
// shell is recovered from prescribed edge lengths l*_e, triangle areas a*_f and
// dihedral angles theta*_e by minimising the sum of squares
//
//   1/2 sum_e (l_e - l*_e)^2 / L_e^2 + 1/2 sum_f (a_f - a*_f)^2 / A_f
//     + 1/2 eta sum_{e interior} 3 L_e^2 / (A_f1 + A_f2) (theta_e - theta*_e)^2
//
// (L, A: lengths and areas of a reference shell). Each term is one Ceres
// residual r with 1/2 r^2 the term, i.e. r = weight * (quantity - target):
//   edge:     weight = 1 / L_e
//   area:     weight = 1 / sqrt(A_f)
//   dihedral: weight = sqrt(3 eta L_e^2 / (A_{f1} + A_{f2}))
// The weight is passed to Create(); LThetaResidualWeights in
// problems/ltheta_spline.h computes it from a reference shell.
//
// All three have analytic Jacobians and one parameter block of 3 doubles
// (x, y, z) per vertex of the element. Jacobian block b is 1 x 3:
// jacobians[b][c] = d r / d X_b[c]. The geometry and its gradients come from
// geometry/element_geometry.h (TriangleArea, DihedralAngle). A degenerate
// element (zero-length edge, zero-area triangle, non-finite value) makes
// Evaluate return false, so Ceres rejects the step.
#ifndef SHELLSPACE_COST_FUNCTIONS_LTHETA_COST_FUNCTIONS_H_
#define SHELLSPACE_COST_FUNCTIONS_LTHETA_COST_FUNCTIONS_H_

#include <ceres/sized_cost_function.h>

namespace shellspace {

// Edge length residual of the edge (X_i, X_j):
//   r = weight * (|X_j - X_i| - target_length).
// Blocks [X_i, X_j]. With u = (X_j - X_i) / |X_j - X_i|:
//   dr/dX_i = -weight u^T,   dr/dX_j = weight u^T.
class EdgeLengthCostFunction : public ceres::SizedCostFunction<1, 3, 3> {
 public:
  static EdgeLengthCostFunction* Create(double target_length, double weight) {
    return new EdgeLengthCostFunction(target_length, weight);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  double target() const { return target_; }
  double weight() const { return weight_; }

 private:
  EdgeLengthCostFunction(double target_length, double weight)
      : target_(target_length), weight_(weight) {}

  double target_;
  double weight_;
};

// Triangle area residual of the face (X_i, X_j, X_k) (counter-clockwise):
//   r = weight * (a - target_area),  a = |(X_j - X_i) x (X_k - X_i)| / 2.
// Blocks [X_i, X_j, X_k]; dr/dX_v = weight * da/dX_v with the TriangleArea
// gradient: da/dX_j = (E_2 x n)/2, da/dX_k = (n x E_1)/2, da/dX_i = -(sum).
class TriangleAreaCostFunction : public ceres::SizedCostFunction<1, 3, 3, 3> {
 public:
  static TriangleAreaCostFunction* Create(double target_area, double weight) {
    return new TriangleAreaCostFunction(target_area, weight);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  double target() const { return target_; }
  double weight() const { return weight_; }

 private:
  TriangleAreaCostFunction(double target_area, double weight)
      : target_(target_area), weight_(weight) {}

  double target_;
  double weight_;
};

// Dihedral angle residual of the edge flap (X_i, X_j, X_k, X_l)
// (geometry/topology.h, EdgeFlap):
//   r = weight * wrap(theta - target_angle),
// theta the signed dihedral angle of DihedralAngle (atan2 form, in (-pi, pi])
// and wrap() the representative of the difference in [-pi, pi) (so a target
// taken from an unwrapped time series, e.g. 3.2, is matched by theta = 3.2 -
// 2 pi). Blocks [X_i, X_j, X_k, X_l]; dr/dX_v = weight * dtheta/dX_v with the
// Discrete Shells gradient of DihedralAngle.
class DihedralAngleCostFunction
    : public ceres::SizedCostFunction<1, 3, 3, 3, 3> {
 public:
  static DihedralAngleCostFunction* Create(double target_angle, double weight) {
    return new DihedralAngleCostFunction(target_angle, weight);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  double target() const { return target_; }
  double weight() const { return weight_; }

 private:
  DihedralAngleCostFunction(double target_angle, double weight)
      : target_(target_angle), weight_(weight) {}

  double target_;
  double weight_;
};

// The representative of `angle` modulo 2 pi in [-pi, pi).
double WrapAngle(double angle);

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_LTHETA_COST_FUNCTIONS_H_
