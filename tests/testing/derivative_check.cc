#include "tests/testing/derivative_check.h"

#include <ceres/gradient_checker.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace shellspace::testing {

double CentralDifferenceError(const VectorFunction& f, const Eigen::VectorXd& x,
                              const DerivativeColumn& analytic,
                              const std::vector<int>& probes, double h,
                              double scale) {
  double error = 0, numeric_scale = 0;
  for (int j : probes) {
    Eigen::VectorXd plus = x, minus = x;
    plus(j) += h;
    minus(j) -= h;
    const Eigen::VectorXd numeric = (f(plus) - f(minus)) / (2 * h);
    const Eigen::VectorXd exact = analytic(j);
    error = std::max(error, (exact - numeric).cwiseAbs().maxCoeff());
    numeric_scale = std::max(numeric_scale, numeric.cwiseAbs().maxCoeff());
  }
  return error / std::max(scale > 0 ? scale : numeric_scale, 1e-300);
}

double NormwiseRelativeError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                             double scale) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return HUGE_VAL;
  const double reference = scale > 0 ? scale : b.cwiseAbs().maxCoeff();
  return (a - b).cwiseAbs().maxCoeff() / std::max(reference, 1e-300);
}

std::vector<int> ProbeCoordinates(int n, int count, unsigned seed) {
  std::vector<int> all(n);
  for (int i = 0; i < n; ++i) all[i] = i;
  std::mt19937 rng(seed);
  std::shuffle(all.begin(), all.end(), rng);
  all.resize(std::min(n, count));
  return all;
}

double CostFunctionJacobianError(const ceres::CostFunction& cost,
                                 const std::vector<double*>& parameters) {
  // Ridders' extrapolation from an initial step of 1e-6 |x|: the default
  // (1e-2 |x|) reaches across thin triangles of real meshes.
  ceres::NumericDiffOptions options;
  options.ridders_relative_initial_step_size = 1e-6;
  ceres::GradientChecker checker(
      &cost, static_cast<const std::vector<const ceres::Manifold*>*>(nullptr),
      options);
  ceres::GradientChecker::ProbeResults results;
  // The checker's own verdict (entry-wise) is not used: see the header.
  checker.Probe(parameters.data(), 1.0, &results);
  if (results.jacobians.size() != parameters.size()) return HUGE_VAL;
  double max_error = 0, scale = 0;
  for (size_t b = 0; b < results.jacobians.size(); ++b) {
    max_error = std::max(max_error,
                         (results.jacobians[b] - results.numeric_jacobians[b])
                             .cwiseAbs()
                             .maxCoeff());
    scale = std::max(scale, results.numeric_jacobians[b].cwiseAbs().maxCoeff());
  }
  return max_error / std::max(scale, 1e-300);
}

CostFunctionWithWrongJacobian::CostFunctionWithWrongJacobian(
    std::unique_ptr<ceres::CostFunction> inner, int block, int entry,
    double offset)
    : inner_(std::move(inner)), block_(block), entry_(entry), offset_(offset) {
  set_num_residuals(inner_->num_residuals());
  *mutable_parameter_block_sizes() = inner_->parameter_block_sizes();
}

bool CostFunctionWithWrongJacobian::Evaluate(double const* const* parameters,
                                             double* residuals,
                                             double** jacobians) const {
  if (!inner_->Evaluate(parameters, residuals, jacobians)) return false;
  if (jacobians != nullptr && jacobians[block_] != nullptr) {
    jacobians[block_][entry_] += offset_;
  }
  return true;
}

ErrorAndTwin CentralDifferenceErrorAndTwin(
    const VectorFunction& f, const Eigen::VectorXd& x,
    const DerivativeColumn& analytic, const std::vector<int>& probes,
    double h, const WrongEntry& wrong) {
  const DerivativeColumn twin =
      WrongInOneEntry(analytic, wrong.row, wrong.col, wrong.offset);
  return {CentralDifferenceError(f, x, analytic, probes, h),
          CentralDifferenceError(f, x, twin, probes, h)};
}

DerivativeColumn WrongInOneEntry(DerivativeColumn analytic, int row, int col,
                                 double offset) {
  return [analytic = std::move(analytic), row, col, offset](int j) {
    Eigen::VectorXd column = analytic(j);
    if (j == col) column(row) += offset;
    return column;
  };
}

}  // namespace shellspace::testing
