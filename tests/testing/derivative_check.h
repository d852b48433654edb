// Derivative checks shared by the whole suite. Every analytic derivative
// (cost-function Jacobians, energy gradients and Hessians, the path Hessian,
// the spline adjoint) is compared with central differences through one of
// these helpers, and every such check has a negative twin: the same helper
// applied to a deliberately wrong derivative must report an error above the
// tolerance. The helpers only measure; the tests assert.
#ifndef SHELLSPACE_TESTS_TESTING_DERIVATIVE_CHECK_H_
#define SHELLSPACE_TESTS_TESTING_DERIVATIVE_CHECK_H_

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

namespace shellspace::testing {

// f: R^n -> R^m, evaluated at points near x.
using VectorFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;
// Column j of the analytic derivative df/dx (m entries).
using DerivativeColumn = std::function<Eigen::VectorXd(int j)>;

// For each probed coordinate j, the central difference
//   N_j = (f(x + h e_j) - f(x - h e_j)) / (2 h)
// against the analytic column A_j; returns the normwise relative error
//   max_j |A_j - N_j|_inf / max_j |N_j|_inf.
// (Entry-wise relative errors are meaningless for entries that vanish
// analytically.) A gradient check is m = 1 (f the value, A_j = g_j); a
// Hessian check is f = the gradient, A_j = H e_j. With `scale` > 0 the
// error is relative to it instead (e.g. the largest entry of the whole
// analytic derivative).
double CentralDifferenceError(const VectorFunction& f, const Eigen::VectorXd& x,
                              const DerivativeColumn& analytic,
                              const std::vector<int>& probes, double h,
                              double scale = 0);

// `count` distinct coordinates of [0, n), drawn with a fixed seed.
std::vector<int> ProbeCoordinates(int n, int count, unsigned seed);

// The normwise relative error max |J - N| / max |N| over all Jacobian blocks
// of `cost` at `parameters` (J analytic, N Ridders' central differences of
// ceres::GradientChecker from an initial step of 1e-6 |x|).
double CostFunctionJacobianError(const ceres::CostFunction& cost,
                                 const std::vector<double*>& parameters);

// The negative twin of a cost function: `inner` with one Jacobian entry
// (block `block`, flat index `entry`) off by `offset`.
class CostFunctionWithWrongJacobian : public ceres::CostFunction {
 public:
  CostFunctionWithWrongJacobian(std::unique_ptr<ceres::CostFunction> inner,
                                int block, int entry, double offset);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  std::unique_ptr<ceres::CostFunction> inner_;
  int block_, entry_;
  double offset_;
};

// max |a - b| / max |b| over all entries (normwise relative): the check that
// two computations of one derivative block agree (e.g. analytic against
// dual numbers); `scale` > 0 replaces max |b|.
double NormwiseRelativeError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                             double scale = 0);

// The negative twin of an analytic derivative column: `analytic` with entry
// `row` of column `col` off by `offset`.
DerivativeColumn WrongInOneEntry(DerivativeColumn analytic, int row, int col,
                                 double offset);

// Where a negative twin's derivative is wrong: entry `row` of column `col`,
// off by `offset` (WrongInOneEntry).
struct WrongEntry {
  int row;
  int col;
  double offset;
};

// A derivative check and its negative twin through the same measurement:
// `error` is CentralDifferenceError(f, x, analytic, probes, h) and
// `twin_error` the same with the analytic derivative wrong at `wrong`. A
// test asserts `error` below and `twin_error` above its tolerance.
struct ErrorAndTwin {
  double error;
  double twin_error;
};
ErrorAndTwin CentralDifferenceErrorAndTwin(
    const VectorFunction& f, const Eigen::VectorXd& x,
    const DerivativeColumn& analytic, const std::vector<int>& probes,
    double h, const WrongEntry& wrong);

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_DERIVATIVE_CHECK_H_
