// Small closed-form problems for the tests of the Newton engine
// (solvers/newton_solver.h; tests/solvers/newton_*_test.cc): a problem on
// R^n given by callbacks that records its iterates and trial points, a
// strictly convex example with a known minimiser, a sum of hyperbolas and a
// scaled saddle, and the checks of a quadratic rate and of monotone merits.
#ifndef SHELLSPACE_TESTS_TESTING_NEWTON_PROBLEMS_H_
#define SHELLSPACE_TESTS_TESTING_NEWTON_PROBLEMS_H_

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "shellspace/solvers/newton_solver.h"

namespace shellspace::testing {

// A problem on R^n with x ⊕ p = x + p, given by closed-form callbacks; an
// empty merit means root finding. Infeasible points: `feasible` false.
struct Callbacks {
  std::function<double(const Eigen::VectorXd&)> merit;
  std::function<Eigen::VectorXd(const Eigen::VectorXd&)> residual;
  std::function<Eigen::MatrixXd(const Eigen::VectorXd&)> jacobian;
  std::function<bool(const Eigen::VectorXd&)> feasible = [](const auto&) {
    return true;
  };
};

// The NewtonProblem of `Callbacks` from x0, the Jacobian's lower triangle
// only if `lower_only` (the symmetric solvers read no more); it records
// the iterates, the trial points and their merits.
class FunctionProblem : public NewtonProblem {
 public:
  FunctionProblem(Callbacks f, Eigen::VectorXd x0, bool lower_only)
      : f_(std::move(f)), x_(std::move(x0)), lower_only_(lower_only) {
    iterates.push_back(x_);
  }
  EvaluationStatus Merit(NewtonPoint point, double* merit) override;
  EvaluationStatus Residual(NewtonPoint point, NewtonResidual* r) override;
  EvaluationStatus Assemble(LinearSystem* system) override;
  void SetTrial(const Eigen::VectorXd& step) override {
    trial_ = x_ + step;
    trial_points.push_back(trial_);
  }
  void AcceptTrial() override {
    x_ = trial_;
    iterates.push_back(x_);
  }
  const Eigen::VectorXd& x() const { return x_; }

  std::vector<Eigen::VectorXd> iterates;      // x_0, accepted points
  std::vector<Eigen::VectorXd> trial_points;  // every SetTrial
  std::vector<double> trial_merits;           // NaN: infeasible
  int infeasible_evaluations = 0;

 private:
  const Eigen::VectorXd& At(NewtonPoint p) const {
    return p == NewtonPoint::kCurrent ? x_ : trial_;
  }
  Callbacks f_;
  Eigen::VectorXd x_, trial_;
  bool lower_only_;
};

// f(x) = sum_i phi((M x - a)_i), phi(u) = e^u - u, M = I + 0.3 (upper
// shift): strictly convex, minimiser x* = M^-1 a (phi'(0) = 0), G = M^T
// phi'(u), H = M^T diag(e^u) M.
struct ConvexExample {
  Eigen::MatrixXd m;
  Eigen::VectorXd a;
  explicit ConvexExample(int n);
  Eigen::VectorXd Minimiser() const;
  Callbacks MakeCallbacks() const;
};

// Whether e_{k+1} <= bound e_k^2 (e_k = |x_k - x*|_2) for every step whose
// e_k is above round-off (1e-6), with at least three such steps (the rate is
// observed, not implied by one step).
::testing::AssertionResult QuadraticRate(
    const std::vector<Eigen::VectorXd>& iterates, const Eigen::VectorXd& x_star,
    double bound);

// Minimisation to `tolerance` in at most `max_steps` steps, forcing 1e-14.
NewtonSettings Minimize(double tolerance, int max_steps);

// The convex example's callbacks with the Hessian doubled (a wrong
// derivative for the negative twins of the rate checks).
Callbacks WithDoubledHessian(const ConvexExample& example);

// f(x) = sum_i sqrt(1 + x_i^2), minimiser 0: from (3, -2.5, 2) the Newton
// step and its half both raise f.
Callbacks Hyperbolas();

// Merits f(x_k) of the accepted iterates never rise.
::testing::AssertionResult MonotoneMerits(
    const Callbacks& c, const std::vector<Eigen::VectorXd>& iterates);

// f(x) = 1 + scale (x_0^2 / 2 + (x_1^2 - 1)^2 / 4): a saddle at the origin,
// valleys at x_1 = +-1, its gradient and Hessian; scaled small, f changes
// only below its round-off near the saddle.
Callbacks ScaledSaddle(double scale);

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_NEWTON_PROBLEMS_H_
