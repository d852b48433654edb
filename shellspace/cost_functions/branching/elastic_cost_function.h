// Elastic term of the relaxed functional (docs/math.md, "Branching: the
// Kohn–Müller model", relaxed model): one residual per x-edge of the grid.
#ifndef SHELLSPACE_COST_FUNCTIONS_BRANCHING_ELASTIC_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_BRANCHING_ELASTIC_COST_FUNCTION_H_

#include <cmath>

#include <ceres/ceres.h>

namespace shellspace::branching {

// The x-edge from node (i-1, j) to node (i, j) of the grid carries the
// elastic energy  w u_x^2  with  u_x ~ (u_i - u_{i-1}) / dx  and the cell
// weight  w = dx dy / H  (the energy is per unit height). As a residual:
//
//   r = sqrt(w) (u_i - u_{i-1}) / dx = a (u_i - u_{i-1}),
//   a = sqrt(dy / (H dx)),
//
// so that r^2 is the edge's contribution to E_delta (Ceres minimises
// 1/2 sum r^2, i.e. E_delta / 2).
//
// Parameter blocks (each of size 1): [0] u_{i-1, j}, [1] u_{i, j}.
// Jacobian (1 x 1 per block): dr/du_{i-1} = -a, dr/du_i = +a.
// At the austenite (i = 1) the first block is the constant node u_{0,j} = 0.
class ElasticCostFunction : public ceres::SizedCostFunction<1, 1, 1> {
 public:
  explicit ElasticCostFunction(double a) : a_(a) {}

  // `dx`, `dy`: grid spacings of the edge; `height`: domain height H.
  static ceres::CostFunction* Create(double dx, double dy, double height) {
    return new ElasticCostFunction(std::sqrt(dy / (height * dx)));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    residuals[0] = a_ * (parameters[1][0] - parameters[0][0]);
    if (jacobians != nullptr) {
      if (jacobians[0] != nullptr) jacobians[0][0] = -a_;
      if (jacobians[1] != nullptr) jacobians[1][0] = a_;
    }
    return true;
  }

  double coefficient() const { return a_; }

 private:
  double a_;
};

}  // namespace shellspace::branching

#endif  // SHELLSPACE_COST_FUNCTIONS_BRANCHING_ELASTIC_COST_FUNCTION_H_
