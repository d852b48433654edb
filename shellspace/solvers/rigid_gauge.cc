#include "shellspace/solvers/rigid_gauge.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace shellspace {

AffineSubspaceManifold::AffineSubspaceManifold(const Eigen::MatrixXd& basis)
    : basis_(basis) {}

bool AffineSubspaceManifold::Plus(const double* x, const double* delta,
                                  double* x_plus_delta) const {
  const Eigen::Map<const Eigen::VectorXd> d(delta, basis_.cols());
  Eigen::Map<Eigen::Vector3d> out(x_plus_delta);
  out = Eigen::Map<const Eigen::Vector3d>(x) + basis_ * d;
  return true;
}

bool AffineSubspaceManifold::PlusJacobian(const double* /*x*/,
                                          double* jacobian) const {
  // Row-major 3 x m.
  Eigen::Map<
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
      out(jacobian, 3, basis_.cols());
  out = basis_;
  return true;
}

bool AffineSubspaceManifold::Minus(const double* y, const double* x,
                                   double* y_minus_x) const {
  Eigen::Map<Eigen::VectorXd> out(y_minus_x, basis_.cols());
  out = basis_.transpose() * (Eigen::Map<const Eigen::Vector3d>(y) -
                              Eigen::Map<const Eigen::Vector3d>(x));
  return true;
}

bool AffineSubspaceManifold::MinusJacobian(const double* /*x*/,
                                           double* jacobian) const {
  // Row-major m x 3.
  Eigen::Map<
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
      out(jacobian, basis_.cols(), 3);
  out = basis_.transpose();
  return true;
}

std::array<int, 3> ChooseGaugeVertices(const Positions& shape,
                                       const std::vector<int>& group) {
  if (static_cast<Eigen::Index>(group.size()) == shape.rows())
    return ChooseGaugeVertices(shape);  // the whole shape
  Eigen::RowVector3d centroid = Eigen::RowVector3d::Zero();
  for (const int v : group) centroid += shape.row(v);
  centroid /= static_cast<double>(group.size());
  // The first vertex of `group` farthest from `from` (its squared distance
  // given by `distance`).
  const auto farthest = [&](const auto& distance) {
    int best_vertex = group.front();
    double best = -1;
    for (const int v : group) {
      const double d = distance(v);
      if (d > best) best = d, best_vertex = v;
    }
    return best_vertex;
  };
  const int a = farthest(
      [&](int v) { return (shape.row(v) - centroid).squaredNorm(); });
  const int b = farthest(
      [&](int v) { return (shape.row(v) - shape.row(a)).squaredNorm(); });
  const Eigen::Vector3d axis = (shape.row(b) - shape.row(a)).normalized();
  const int c = farthest([&](int v) {
    const Eigen::Vector3d d = (shape.row(v) - shape.row(a)).transpose();
    return (d - d.dot(axis) * axis).squaredNorm();
  });
  return {a, b, c};
}

std::array<int, 3> ChooseGaugeVertices(const Positions& shape) {
  const Eigen::RowVector3d centroid = shape.colwise().mean();
  int a = 0, b = 0, c = 0;
  (shape.rowwise() - centroid).rowwise().squaredNorm().maxCoeff(&a);
  (shape.rowwise() - shape.row(a)).rowwise().squaredNorm().maxCoeff(&b);
  const Eigen::Vector3d axis = (shape.row(b) - shape.row(a)).normalized();
  double best = -1;
  for (int i = 0; i < shape.rows(); ++i) {
    const Eigen::Vector3d d = (shape.row(i) - shape.row(a)).transpose();
    const double dist = (d - d.dot(axis) * axis).squaredNorm();
    if (dist > best) best = dist, c = i;
  }
  return {a, b, c};
}

std::vector<std::array<int, 3>> ChooseGaugeVertices(
    const Positions& shape, const std::vector<std::vector<int>>& components) {
  std::vector<std::array<int, 3>> vertices;
  for (const std::vector<int>& group : components)
    vertices.push_back(ChooseGaugeVertices(shape, group));
  return vertices;
}

RigidGauge MakeRigidGauge(const Positions& shape) {
  return MakeRigidGauge(shape, ChooseGaugeVertices(shape));
}

RigidGauge MakeRigidGauge(const Positions& shape,
                          const std::array<int, 3>& vertices) {
  RigidGauge gauge;
  gauge.vertices = vertices;
  const auto [a, b, c] = gauge.vertices;
  const Eigen::Vector3d pa = shape.row(a), pb = shape.row(b),
                        pc = shape.row(c);
  gauge.line = (pb - pa).normalized();
  Eigen::Vector3d w = (pc - pa) - (pc - pa).dot(gauge.line) * gauge.line;
  w.normalize();
  gauge.plane << gauge.line, w;
  return gauge;
}

double GaugeFreeMaxNorm(const RigidGauge& gauge, const Eigen::VectorXd& g) {
  const auto [a, b, c] = gauge.vertices;
  double norm = 0;
  for (int v = 0; 3 * v < g.size(); ++v) {
    if (v == a || v == b || v == c) continue;
    norm = std::max(norm, g.segment<3>(3 * v).cwiseAbs().maxCoeff());
  }
  norm = std::max(norm, std::abs(gauge.line.dot(g.segment<3>(3 * b))));
  norm = std::max(norm, (gauge.plane.transpose() * g.segment<3>(3 * c))
                            .cwiseAbs()
                            .maxCoeff());
  return norm;
}

namespace {

void PinRigidGauge(const RigidGauge& gauge, Positions* shape,
                   ceres::Problem* problem) {
  const auto [a, b, c] = gauge.vertices;
  problem->SetParameterBlockConstant(shape->data() + 3 * a);
  problem->SetManifold(shape->data() + 3 * b,
                       new AffineSubspaceManifold(Eigen::MatrixXd(gauge.line)));
  problem->SetManifold(shape->data() + 3 * c,
                       new AffineSubspaceManifold(Eigen::MatrixXd(gauge.plane)));
}

}  // namespace

std::array<int, 3> PinRigidMotions(Positions* shape, ceres::Problem* problem) {
  const RigidGauge gauge = MakeRigidGauge(*shape);
  PinRigidGauge(gauge, shape, problem);
  return gauge.vertices;
}

void PinRigidMotions(Positions* shape, ceres::Problem* problem,
                     const std::vector<std::vector<int>>& components) {
  for (const std::array<int, 3>& vertices :
       ChooseGaugeVertices(*shape, components)) {
    PinRigidGauge(MakeRigidGauge(*shape, vertices), shape, problem);
  }
}

}  // namespace shellspace
