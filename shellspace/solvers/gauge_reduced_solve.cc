#include "shellspace/solvers/gauge_reduced_solve.h"

#include <Eigen/SparseCholesky>
#include <vector>

#include "shellspace/solvers/rigid_gauge.h"

namespace shellspace {

Eigen::SparseMatrix<double> RigidGaugeBasis(const Positions& shape) {
  return RigidGaugeBasis(shape, ChooseGaugeVertices(shape));
}

Eigen::SparseMatrix<double> RigidGaugeBasis(
    const Positions& shape, const std::array<int, 3>& vertices) {
  return RigidGaugeBasis(shape, std::vector<std::array<int, 3>>{vertices});
}

Eigen::SparseMatrix<double> RigidGaugeBasis(
    const Positions& shape, const std::vector<std::array<int, 3>>& triples) {
  const int n = static_cast<int>(shape.rows());
  // Per vertex: the directions it keeps (0: held; none listed: all three).
  std::vector<std::vector<Eigen::Vector3d>> kept(n);
  std::vector<char> in_gauge(n, 0);
  for (const std::array<int, 3>& vertices : triples) {
    const RigidGauge gauge = MakeRigidGauge(shape, vertices);
    const auto [a, b, c] = vertices;
    in_gauge[a] = in_gauge[b] = in_gauge[c] = 1;
    kept[b] = {gauge.line};                            // the line ab
    kept[c] = {gauge.line, Eigen::Vector3d(gauge.plane.col(1))};  // plane abc
  }
  std::vector<Eigen::Triplet<double>> t;
  int column = 0;
  for (int v = 0; v < n; ++v) {
    if (!in_gauge[v]) {
      for (int k = 0; k < 3; ++k) t.emplace_back(3 * v + k, column++, 1.0);
      continue;
    }
    for (const Eigen::Vector3d& dir : kept[v]) {
      for (int k = 0; k < 3; ++k) t.emplace_back(3 * v + k, column, dir(k));
      ++column;
    }
  }
  Eigen::SparseMatrix<double> basis(3 * n, column);
  basis.setFromTriplets(t.begin(), t.end());
  return basis;
}

std::vector<int> BasisColumnVertices(const Eigen::SparseMatrix<double>& basis) {
  std::vector<int> vertex(basis.cols());
  for (int c = 0; c < basis.cols(); ++c) {
    vertex[c] = basis.innerIndexPtr()[basis.outerIndexPtr()[c]] / 3;
  }
  return vertex;
}

Eigen::SparseMatrix<double> FreeVertexBasis(
    int num_vertices, const std::vector<int>& fixed_vertices) {
  std::vector<bool> fixed(num_vertices, false);
  for (int v : fixed_vertices) fixed[v] = true;
  std::vector<Eigen::Triplet<double>> t;
  int column = 0;
  for (int v = 0; v < num_vertices; ++v) {
    if (fixed[v]) continue;
    for (int k = 0; k < 3; ++k) t.emplace_back(3 * v + k, column++, 1.0);
  }
  Eigen::SparseMatrix<double> basis(3 * num_vertices, column);
  basis.setFromTriplets(t.begin(), t.end());
  return basis;
}

GaugeReducedStep SolveModuloRigidMotions(const Eigen::SparseMatrix<double>& h,
                                         const Eigen::VectorXd& rhs,
                                         const Positions& shape,
                                         double shift) {
  const Eigen::SparseMatrix<double> basis = RigidGaugeBasis(shape);
  Eigen::SparseMatrix<double> reduced =
      Eigen::SparseMatrix<double>(basis.transpose() * h * basis);
  if (shift > 0) {
    Eigen::SparseMatrix<double> identity(reduced.rows(), reduced.cols());
    identity.setIdentity();
    reduced += shift * identity;
  }
  GaugeReducedStep step;
  step.p = Eigen::VectorXd::Zero(rhs.size());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(reduced);
  if (ldlt.info() != Eigen::Success) return step;
  step.p = basis * ldlt.solve(basis.transpose() * rhs);
  step.positive_definite = ldlt.vectorD().minCoeff() > 0 && step.p.allFinite();
  return step;
}

}  // namespace shellspace
