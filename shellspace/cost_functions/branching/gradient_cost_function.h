// The u_yy part of the Modica–Mortola term of the relaxed functional
// (docs/math.md, "Branching: the Kohn–Müller model"): one residual per node.
#ifndef SHELLSPACE_COST_FUNCTIONS_BRANCHING_GRADIENT_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_BRANCHING_GRADIENT_COST_FUNCTION_H_

#include <cmath>

#include <ceres/ceres.h>

namespace shellspace::branching {

// Node (i, j) carries  (3 eps delta / 4) w u_yy^2  with the periodic central
// second difference  u_yy ~ (u_{j-1} - 2 u_j + u_{j+1}) / dy^2  and the node
// weight  w = wx dy / H  (wx: the x-length the node represents). Residual:
//
//   r = sqrt(3 eps delta w / 4) (u_{j-1} - 2 u_j + u_{j+1}) / dy^2
//     = b (u_{j-1} - 2 u_j + u_{j+1}),
//   b = sqrt(3 eps delta wx dy / (4 H)) / dy^2.
//
// u_yy is the difference of the two staggered slopes used by the double-well
// term (DoubleWellCostFunction), so the two terms are consistent.
// Parameter blocks (size 1 each): [0] u_{i,j-1}, [1] u_{i,j}, [2] u_{i,j+1}.
// Jacobian: dr/du_{j-1} = b, dr/du_j = -2 b, dr/du_{j+1} = b.
class GradientCostFunction : public ceres::SizedCostFunction<1, 1, 1, 1> {
 public:
  explicit GradientCostFunction(double b) : b_(b) {}

  // `epsilon`: twin-boundary energy; `delta`: interface width; `wx`: x-weight
  // of the node; `dy`: y spacing; `height`: domain height H.
  static ceres::CostFunction* Create(double epsilon, double delta, double wx,
                                     double dy, double height) {
    return new GradientCostFunction(Coefficient(epsilon, delta, wx, dy, height));
  }
  static double Coefficient(double epsilon, double delta, double wx, double dy,
                            double height) {
    return std::sqrt(0.75 * epsilon * delta * wx * dy / height) / (dy * dy);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    residuals[0] =
        b_ * (parameters[0][0] - 2.0 * parameters[1][0] + parameters[2][0]);
    if (jacobians != nullptr) {
      if (jacobians[0] != nullptr) jacobians[0][0] = b_;
      if (jacobians[1] != nullptr) jacobians[1][0] = -2.0 * b_;
      if (jacobians[2] != nullptr) jacobians[2][0] = b_;
    }
    return true;
  }

 private:
  double b_;
};

}  // namespace shellspace::branching

#endif  // SHELLSPACE_COST_FUNCTIONS_BRANCHING_GRADIENT_COST_FUNCTION_H_
