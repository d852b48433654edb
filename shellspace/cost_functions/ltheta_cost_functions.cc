#include "shellspace/cost_functions/ltheta_cost_functions.h"

#include <Eigen/Core>
#include <cmath>

#include "shellspace/geometry/element_geometry.h"

namespace shellspace {
namespace {

// The vertex of a 3-double parameter block.
Eigen::Vector3d Vertex(const double* p) {
  return Eigen::Vector3d(p[0], p[1], p[2]);
}

bool AllFinite(const Eigen::Vector3d* v, int n) {
  for (int m = 0; m < n; ++m) {
    if (!v[m].allFinite()) return false;
  }
  return true;
}

// Writes weight * gradient into the requested 1 x 3 Jacobian blocks.
void WriteJacobians(double weight, const Eigen::Vector3d* grad, int n,
                    double** jacobians) {
  if (jacobians == nullptr) return;
  for (int b = 0; b < n; ++b) {
    if (jacobians[b] == nullptr) continue;
    Eigen::Map<Eigen::Vector3d> block(jacobians[b]);
    block = weight * grad[b];
  }
}

}  // namespace

double WrapAngle(double angle) {
  constexpr double kTwoPi = 2.0 * M_PI;
  double wrapped = std::fmod(angle + M_PI, kTwoPi);
  if (wrapped < 0) wrapped += kTwoPi;
  return wrapped - M_PI;
}

bool EdgeLengthCostFunction::Evaluate(double const* const* parameters,
                                      double* residuals,
                                      double** jacobians) const {
  const Eigen::Vector3d e = Vertex(parameters[1]) - Vertex(parameters[0]);
  const double length = e.norm();
  if (!(length > 0) || !std::isfinite(length)) return false;
  residuals[0] = weight_ * (length - target_);
  const Eigen::Vector3d grad[2] = {-e / length, e / length};
  WriteJacobians(weight_, grad, 2, jacobians);
  return true;
}

bool TriangleAreaCostFunction::Evaluate(double const* const* parameters,
                                        double* residuals,
                                        double** jacobians) const {
  const TriangleArea<double> triangle(
      Vertex(parameters[0]), Vertex(parameters[1]), Vertex(parameters[2]));
  if (!(triangle.area > 0) || !std::isfinite(triangle.area) ||
      !AllFinite(triangle.grad, 3)) {
    return false;
  }
  residuals[0] = weight_ * (triangle.area - target_);
  WriteJacobians(weight_, triangle.grad, 3, jacobians);
  return true;
}

bool DihedralAngleCostFunction::Evaluate(double const* const* parameters,
                                         double* residuals,
                                         double** jacobians) const {
  const DihedralAngle<double> flap(Vertex(parameters[0]), Vertex(parameters[1]),
                                   Vertex(parameters[2]),
                                   Vertex(parameters[3]));
  if (!std::isfinite(flap.theta) || !AllFinite(flap.grad, 4)) return false;
  residuals[0] = weight_ * WrapAngle(flap.theta - target_);
  WriteJacobians(weight_, flap.grad, 4, jacobians);
  return true;
}

}  // namespace shellspace
