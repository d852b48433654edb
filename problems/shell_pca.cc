#include "problems/shell_pca.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "cost_functions/energy_derivatives.h"
#include "geometry/rigid_alignment.h"
#include "problems/elastic_mean.h"
#include "problems/exponential_map.h"

namespace shellspace {
namespace {

Eigen::Map<const Eigen::VectorXd> Flat(const Positions& p) {
  return Eigen::Map<const Eigen::VectorXd>(p.data(), p.size());
}

void CheckOptions(const ShellPcaOptions& options) {
  if (options.steps < 1) throw InputError("shell PCA: steps must be at least 1");
  if (!(options.relative_cutoff >= 0)) {
    throw InputError("shell PCA: relative cutoff must be non-negative");
  }
}

}  // namespace

ShellMetric::ShellMetric(const ShellSpace& space, const Positions& at)
    : hessian_(EnergyHessian(space, at, at, ShellSide::kDeformed,
                             ShellSide::kDeformed)) {}

double ShellMetric::Inner(const Positions& u, const Positions& w) const {
  if (u.size() != hessian_.rows() || w.size() != hessian_.rows()) {
    throw InputError("shell metric: variation of the wrong size");
  }
  return 0.5 * Flat(u).dot(hessian_ * Flat(w));
}

double ShellMetric::Norm(const Positions& u) const {
  return std::sqrt(std::max(0.0, Inner(u, u)));
}

GramModes ModesFromGram(const Eigen::MatrixXd& gram,
                        const std::vector<Positions>& displacements,
                        double relative_cutoff) {
  const int n = static_cast<int>(displacements.size());
  if (n == 0 || gram.rows() != n || gram.cols() != n) {
    throw InputError("PCA: Gram matrix does not match the displacements");
  }
  const Eigen::MatrixXd symmetric = 0.5 * (gram + gram.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(symmetric);
  // Eigen sorts ascending; reverse to lambda_1 >= lambda_2 >= ...
  GramModes result;
  result.eigenvalues = solver.eigenvalues().reverse();
  const Eigen::MatrixXd vectors = solver.eigenvectors().rowwise().reverse();
  const double largest = std::max(result.eigenvalues(0), 0.0);
  for (int j = 0; j < n; ++j) {
    const double lambda = result.eigenvalues(j);
    if (!(lambda > relative_cutoff * largest) || !(lambda > 0)) break;
    Positions mode = Positions::Zero(displacements[0].rows(), 3);
    for (int i = 0; i < n; ++i) mode += vectors(i, j) * displacements[i];
    mode /= std::sqrt(n * lambda);
    // Sign convention: the largest-magnitude coefficient positive.
    Eigen::Index k = 0;
    vectors.col(j).cwiseAbs().maxCoeff(&k);
    if (vectors(k, j) < 0) mode = -mode;
    result.modes.push_back(std::move(mode));
  }
  return result;
}

Positions ShellDisplacement(const ShellSpace& space, const Positions& mean,
                            const Positions& shape,
                            const ShellPcaOptions& options,
                            const SolverSettings& settings) {
  CheckOptions(options);
  const Positions aligned = AlignRigidly(shape, mean);
  if (options.displacement == DisplacementKind::kAlignedDifference) {
    return aligned - mean;
  }
  return LogK(space, mean, aligned, options.steps, {}, settings);
}

ShellPcaModel ComputeShellPca(const ShellSpace& space, const Positions& mean,
                              const std::vector<Positions>& shapes,
                              const ShellPcaOptions& options,
                              const SolverSettings& settings) {
  CheckOptions(options);
  CheckShapeSet(space, shapes, "shell PCA");
  CheckShapeSet(space, {mean}, "shell PCA mean");
  ShellPcaModel model{mean, {}, {}, {}, {}, ShellMetric(space, mean)};
  const int n = static_cast<int>(shapes.size());
  for (const Positions& shape : shapes) {
    model.displacements.push_back(
        ShellDisplacement(space, mean, shape, options, settings));
  }
  // Gamma = V^T H V / (2 n) with the displacements as the columns of V.
  Eigen::MatrixXd v(mean.size(), n);
  for (int i = 0; i < n; ++i) v.col(i) = Flat(model.displacements[i]);
  const Eigen::MatrixXd hv = model.metric.hessian() * v;
  model.gram = 0.5 * v.transpose() * hv / n;
  GramModes modes =
      ModesFromGram(model.gram, model.displacements, options.relative_cutoff);
  model.eigenvalues = std::move(modes.eigenvalues);
  model.modes = std::move(modes.modes);
  return model;
}

Positions ShellModeShape(const ShellSpace& space, const ShellPcaModel& model,
                         int j, double t, const ShellPcaOptions& options,
                         const SolverSettings& settings) {
  CheckOptions(options);
  if (j < 0 || j >= static_cast<int>(model.modes.size())) {
    throw InputError("shell PCA: mode " + std::to_string(j + 1) +
                     " does not exist (the model has " +
                     std::to_string(model.modes.size()) + ")");
  }
  const Positions variation =
      t * std::sqrt(model.eigenvalues(j)) * model.modes[j];
  return AlignRigidly(
      ExpK(space, model.mean, variation, options.steps, {}, settings),
      model.mean);
}

Eigen::VectorXd ShellModeCoefficients(const ShellPcaModel& model,
                                      const Positions& v, int m) {
  if (m < 0 || m > static_cast<int>(model.modes.size())) {
    throw InputError("shell PCA: " + std::to_string(m) +
                     " modes requested, the model has " +
                     std::to_string(model.modes.size()));
  }
  Eigen::VectorXd c(m);
  for (int j = 0; j < m; ++j) c(j) = model.metric.Inner(v, model.modes[j]);
  return c;
}

Positions ShellFromCoefficients(const ShellSpace& space,
                                const ShellPcaModel& model,
                                const Eigen::VectorXd& coefficients,
                                const ShellPcaOptions& options,
                                const SolverSettings& settings) {
  CheckOptions(options);
  const int m = static_cast<int>(coefficients.size());
  if (m > static_cast<int>(model.modes.size())) {
    throw InputError("shell PCA: more coefficients than modes");
  }
  if (m == 0) return model.mean;
  Positions variation = Positions::Zero(model.mean.rows(), 3);
  for (int j = 0; j < m; ++j) variation += coefficients(j) * model.modes[j];
  return AlignRigidly(
      ExpK(space, model.mean, variation, options.steps, {}, settings),
      model.mean);
}

}  // namespace shellspace
