// Double-well part of the Modica–Mortola term of the relaxed functional
// (docs/math.md, "Branching: the Kohn–Müller model"): one residual per y-edge.
#ifndef SHELLSPACE_COST_FUNCTIONS_BRANCHING_DOUBLE_WELL_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_BRANCHING_DOUBLE_WELL_COST_FUNCTION_H_

#include <cmath>

#include <ceres/ceres.h>

namespace shellspace::branching {

// The y-edge from node (i, j) to (i, j+1) (periodic in j) carries
// (3 eps / (4 delta)) w (1 - u_y^2)^2  with the staggered slope
// u_y = (u_{j+1} - u_j) / dy  and the edge weight  w = wx dy / H. Residual:
//
//   r = sqrt(3 eps w / (4 delta)) (1 - u_y^2) = c (1 - d^2 / dy^2),
//   d = u_{j+1} - u_j,   c = sqrt(3 eps wx dy / (4 delta H)).
//
// Parameter blocks (size 1 each): [0] u_{i,j}, [1] u_{i,j+1}.
// Jacobian: dr/du_j = 2 c d / dy^2, dr/du_{j+1} = -2 c d / dy^2.
// With the gradient term, one transition u_y: -1 -> +1 costs 2 eps per unit
// x-length (optimal profile u_y = tanh(y / delta)).
class DoubleWellCostFunction : public ceres::SizedCostFunction<1, 1, 1> {
 public:
  DoubleWellCostFunction(double c, double dy) : c_(c), inv_dy2_(1.0 / (dy * dy)) {}

  // `epsilon`: twin-boundary energy; `delta`: interface width; `wx`: x-weight
  // of the node row; `dy`: y spacing; `height`: domain height H.
  static ceres::CostFunction* Create(double epsilon, double delta, double wx,
                                     double dy, double height) {
    return new DoubleWellCostFunction(
        Coefficient(epsilon, delta, wx, dy, height), dy);
  }
  static double Coefficient(double epsilon, double delta, double wx, double dy,
                            double height) {
    return std::sqrt(0.75 * epsilon * wx * dy / (delta * height));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double d = parameters[1][0] - parameters[0][0];
    residuals[0] = c_ * (1.0 - d * d * inv_dy2_);
    if (jacobians != nullptr) {
      const double g = 2.0 * c_ * d * inv_dy2_;
      if (jacobians[0] != nullptr) jacobians[0][0] = g;
      if (jacobians[1] != nullptr) jacobians[1][0] = -g;
    }
    return true;
  }

 private:
  double c_;
  double inv_dy2_;
};

}  // namespace shellspace::branching

#endif  // SHELLSPACE_COST_FUNCTIONS_BRANCHING_DOUBLE_WELL_COST_FUNCTION_H_
