// The Newton engine (solvers/newton_solver.h) on small closed-form problems:
// quadratic convergence on a strictly convex function, root finding on a
// nonlinear system, the line search (an increasing step rejected, an
// infeasible trial point backtracked), the stall rules and the stop reasons.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <iostream>
#include <vector>

#include "shellspace/solvers/newton_solver.h"
#include "shellspace/solvers/reusable_cholesky.h"
#include "shellspace/solvers/sparse_lu.h"

namespace shellspace {
namespace {

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

class FunctionProblem : public NewtonProblem {
 public:
  FunctionProblem(Callbacks f, Eigen::VectorXd x0, bool lower_only)
      : f_(std::move(f)), x_(std::move(x0)), lower_only_(lower_only) {
    iterates.push_back(x_);
  }
  EvaluationStatus Merit(NewtonPoint point, double* merit) override {
    const Eigen::VectorXd& x = At(point);
    if (point == NewtonPoint::kTrial) trial_merits.push_back(NAN);
    if (!f_.feasible(x)) {
      ++infeasible_evaluations;
      return EvaluationStatus::kInfeasible;
    }
    *merit = f_.merit(x);
    if (point == NewtonPoint::kTrial) trial_merits.back() = *merit;
    return EvaluationStatus::kOk;
  }
  EvaluationStatus Residual(NewtonPoint point, NewtonResidual* r) override {
    const Eigen::VectorXd& x = At(point);
    if (!f_.feasible(x)) {
      ++infeasible_evaluations;
      return EvaluationStatus::kInfeasible;
    }
    *r = NewtonResidual::OfReduced(f_.residual(x));
    return EvaluationStatus::kOk;
  }
  EvaluationStatus Assemble(LinearSystem* system) override {
    Eigen::MatrixXd j = f_.jacobian(x_);
    if (lower_only_) j = j.triangularView<Eigen::Lower>();
    system->matrix = j.sparseView();
    system->vertex_of.resize(j.rows());
    for (int i = 0; i < j.rows(); ++i) system->vertex_of[i] = i;
    system->num_vertices = static_cast<int>(j.rows());
    return EvaluationStatus::kOk;
  }
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
  explicit ConvexExample(int n) : m(Eigen::MatrixXd::Identity(n, n)), a(n) {
    for (int i = 0; i + 1 < n; ++i) m(i, i + 1) = 0.3;
    for (int i = 0; i < n; ++i) a(i) = std::sin(1.0 + i);  // in [-1, 1]
  }
  Eigen::VectorXd Minimiser() const { return m.partialPivLu().solve(a); }
  Callbacks MakeCallbacks() const {
    Callbacks c;
    c.merit = [this](const Eigen::VectorXd& x) {
      const Eigen::VectorXd u = m * x - a;
      return (u.array().exp() - u.array()).sum();
    };
    c.residual = [this](const Eigen::VectorXd& x) {
      const Eigen::VectorXd u = m * x - a;
      return Eigen::VectorXd(m.transpose() *
                             (u.array().exp() - 1.0).matrix());
    };
    c.jacobian = [this](const Eigen::VectorXd& x) {
      const Eigen::VectorXd u = m * x - a;
      return Eigen::MatrixXd(m.transpose() * u.array().exp().matrix().asDiagonal() * m);
    };
    return c;
  }
};

// Whether e_{k+1} <= bound e_k^2 (e_k = |x_k - x*|_2) for every step whose
// e_k is above round-off (1e-6), with at least three such steps (the rate is
// observed, not implied by one step).
::testing::AssertionResult QuadraticRate(
    const std::vector<Eigen::VectorXd>& iterates, const Eigen::VectorXd& x_star,
    double bound) {
  int observed = 0;
  for (size_t k = 0; k + 1 < iterates.size(); ++k) {
    const double e = (iterates[k] - x_star).norm();
    const double e_next = (iterates[k + 1] - x_star).norm();
    if (e < 1e-6) break;
    if (!(e_next <= bound * e * e)) {
      return ::testing::AssertionFailure()
             << "step " << k << ": e = " << e << ", next " << e_next;
    }
    ++observed;
  }
  if (observed < 3) {
    return ::testing::AssertionFailure() << "only " << observed << " steps";
  }
  return ::testing::AssertionSuccess();
}

NewtonSettings Minimize(double tolerance, int max_steps) {
  NewtonSettings s;
  s.mode = NewtonMode::kMinimize;
  s.tolerance = tolerance;
  s.max_steps = max_steps;
  s.forcing = 1e-14;
  return s;
}

TEST(NewtonSolverTest, ConvergesQuadraticallyOnAStrictlyConvexFunction) {
  const ConvexExample example(6);
  FunctionProblem problem(example.MakeCallbacks(), Eigen::VectorXd::Zero(6),
                          /*lower_only=*/true);
  ReusableCholesky cholesky;
  const NewtonReport report =
      SolveNewton(&problem, &cholesky, Minimize(1e-13, 20));
  EXPECT_TRUE(report.converged) << report.stop_reason;
  EXPECT_EQ(report.stop, NewtonStop::kConverged);
  EXPECT_EQ(report.stop_reason, "converged");
  EXPECT_LE(report.final_gradient, 1e-13);
  EXPECT_GT(report.initial_gradient, 0.1);
  const Eigen::VectorXd x_star = example.Minimiser();
  EXPECT_LT((problem.x() - x_star).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_TRUE(QuadraticRate(problem.iterates, x_star, 5.0));
  EXPECT_EQ(report.steps, static_cast<int>(problem.iterates.size()) - 1);
  EXPECT_GE(report.factorizations, 1);
}

// Negative twin: with a wrong Hessian (2 H) Newton still converges, but
// linearly (e_{k+1} ~ e_k / 2), and the same rate check fails.
// The convex example's callbacks with the Hessian doubled (a wrong
// derivative for the negative twins of the rate checks).
Callbacks WithDoubledHessian(const ConvexExample& example) {
  Callbacks wrong = example.MakeCallbacks();
  const auto exact = wrong.jacobian;
  wrong.jacobian = [exact](const Eigen::VectorXd& x) {
    return Eigen::MatrixXd(2.0 * exact(x));
  };
  return wrong;
}

TEST(NewtonSolverTest, WrongHessianFailsTheQuadraticRateCheck) {
  const ConvexExample example(6);
  FunctionProblem problem(WithDoubledHessian(example), Eigen::VectorXd::Zero(6),
                          true);
  ReusableCholesky cholesky;
  const NewtonReport report =
      SolveNewton(&problem, &cholesky, Minimize(1e-13, 100));
  EXPECT_TRUE(report.converged) << report.stop_reason;
  EXPECT_GT(report.steps, 20);  // linear: about one bit per step
  EXPECT_FALSE(QuadraticRate(problem.iterates, example.Minimiser(), 5.0));
}

// The stop hook: true at the third poll stops before the third step, at
// the point two steps reach (the same as max_steps = 2); a hook that never
// fires changes nothing.
TEST(NewtonSolverTest, StopHookEndsAtTheCurrentPoint) {
  const ConvexExample example(6);
  FunctionProblem capped(example.MakeCallbacks(), Eigen::VectorXd::Zero(6),
                         true);
  ReusableCholesky cholesky;
  const NewtonReport two = SolveNewton(&capped, &cholesky, Minimize(1e-13, 2));
  FunctionProblem stopped(example.MakeCallbacks(), Eigen::VectorXd::Zero(6),
                          true);
  NewtonSettings settings = Minimize(1e-13, 100);
  int polls = 0;
  settings.stop = [&polls] { return ++polls == 3; };
  ReusableCholesky cholesky2;
  const NewtonReport report = SolveNewton(&stopped, &cholesky2, settings);
  EXPECT_EQ(report.stop, NewtonStop::kStopped);
  EXPECT_EQ(report.stop_reason, "stopped on request");
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.steps, 2);
  EXPECT_EQ(polls, 3);
  EXPECT_EQ(report.final_gradient, two.final_gradient);
  EXPECT_EQ(stopped.iterates.back(), capped.iterates.back());
  // Never firing: the same run as without the hook.
  FunctionProblem plain(example.MakeCallbacks(), Eigen::VectorXd::Zero(6),
                        true), hooked(example.MakeCallbacks(),
                                      Eigen::VectorXd::Zero(6), true);
  ReusableCholesky c3, c4;
  NewtonSettings never = Minimize(1e-13, 100);
  never.stop = [] { return false; };
  const NewtonReport a = SolveNewton(&plain, &c3, Minimize(1e-13, 100));
  const NewtonReport b = SolveNewton(&hooked, &c4, never);
  EXPECT_TRUE(b.converged);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.final_gradient, b.final_gradient);
  EXPECT_EQ(plain.iterates.back(), hooked.iterates.back());
}

TEST(NewtonSolverTest, MaxStepsIsNotConvergence) {
  const ConvexExample example(6);
  FunctionProblem problem(example.MakeCallbacks(), Eigen::VectorXd::Zero(6),
                          true);
  ReusableCholesky cholesky;
  const NewtonReport report =
      SolveNewton(&problem, &cholesky, Minimize(1e-13, 2));
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.stop, NewtonStop::kMaxSteps);
  EXPECT_EQ(report.stop_reason, "max steps");
  EXPECT_EQ(report.steps, 2);
  EXPECT_GT(report.final_gradient, 1e-13);
  EXPECT_LT(report.final_gradient, report.initial_gradient);
}

// F(x) = (x0^3 - 8, x0 x1 - 6, x1 + x2^2 - 7): root (2, 3, 2) near (1, 1, 1);
// J non-symmetric, solved by SparseLu.
TEST(NewtonSolverTest, FindsTheRootOfASmallNonlinearSystem) {
  Callbacks c;
  c.residual = [](const Eigen::VectorXd& x) {
    return Eigen::Vector3d(x(0) * x(0) * x(0) - 8, x(0) * x(1) - 6,
                           x(1) + x(2) * x(2) - 7)
        .eval();
  };
  c.jacobian = [](const Eigen::VectorXd& x) {
    Eigen::MatrixXd j(3, 3);
    j << 3 * x(0) * x(0), 0, 0,  //
        x(1), x(0), 0,           //
        0, 1, 2 * x(2);
    return j;
  };
  FunctionProblem problem(c, Eigen::Vector3d(1, 1, 1), false);
  NewtonSettings s;
  s.mode = NewtonMode::kRootFind;
  s.tolerance = 1e-12;
  s.max_steps = 40;
  s.max_halvings = 20;
  s.accept_smaller_max_norm = true;
  s.accept_smaller_two_norm = true;
  SparseLu lu;
  const NewtonReport report = SolveNewton(&problem, &lu, s);
  EXPECT_TRUE(report.converged) << report.stop_reason;
  EXPECT_LT((problem.x() - Eigen::Vector3d(2, 3, 2)).cwiseAbs().maxCoeff(),
            1e-12);
  EXPECT_EQ(report.factorizations, report.steps);
  EXPECT_EQ(report.cg_iterations, 0);
}

// One minimisation of the 1-D function `f` from x0 by ReusableCholesky with
// at most `max_halvings` halvings of each step: the problem (its trial
// points and iterates) and the report.
struct OneDimensionalRun {
  OneDimensionalRun(Callbacks f, double x0, double tolerance, int max_steps,
                    int max_halvings)
      : problem(std::move(f), Eigen::VectorXd::Constant(1, x0), true) {
    ReusableCholesky cholesky;
    NewtonSettings s = Minimize(tolerance, max_steps);
    s.max_halvings = max_halvings;
    report = SolveNewton(&problem, &cholesky, s);
  }
  FunctionProblem problem;
  NewtonReport report;
};

// The line search of `problem` tried the points `expected` first (to 1e-12).
void ExpectFirstTrialPoints(const FunctionProblem& problem,
                            const std::vector<double>& expected) {
  ASSERT_GE(problem.trial_points.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(problem.trial_points[i](0), expected[i], 1e-12) << i;
  }
}

// f(x) = sqrt(1 + x^2): Newton's step from x is -x (1 + x^2); from 2 the
// full step (to -8) and the half step (to -3) raise f, the quarter step (to
// -1/2) lowers it.
Callbacks Hyperbola() {
  Callbacks c;
  c.merit = [](const Eigen::VectorXd& x) { return std::sqrt(1 + x(0) * x(0)); };
  c.residual = [](const Eigen::VectorXd& x) {
    return Eigen::VectorXd::Constant(1, x(0) / std::sqrt(1 + x(0) * x(0)))
        .eval();
  };
  c.jacobian = [](const Eigen::VectorXd& x) {
    return Eigen::MatrixXd::Constant(1, 1, std::pow(1 + x(0) * x(0), -1.5));
  };
  return c;
}

TEST(NewtonSolverTest, LineSearchRejectsAnIncreasingStep) {
  const OneDimensionalRun run(Hyperbola(), 2.0, 1e-12, 1, 2);
  ASSERT_EQ(run.problem.trial_points.size(), 3u);
  ExpectFirstTrialPoints(run.problem, {-8.0, -3.0, -0.5});
  EXPECT_GT(run.problem.trial_merits[0], std::sqrt(5.0));
  EXPECT_GT(run.problem.trial_merits[1], std::sqrt(5.0));
  EXPECT_EQ(run.report.steps, 1);
  EXPECT_NEAR(run.problem.x()(0), -0.5, 1e-12);
  EXPECT_NEAR(run.report.final_merit, std::sqrt(1.25), 1e-12);

  // With one halving only, no step is accepted: the point stays.
  const OneDimensionalRun stuck(Hyperbola(), 2.0, 1e-12, 1, 1);
  const NewtonReport& failed = stuck.report;
  EXPECT_FALSE(failed.converged);
  EXPECT_EQ(failed.stop, NewtonStop::kLineSearchFailed);
  EXPECT_EQ(failed.stop_reason, "no decrease along the Newton direction");
  EXPECT_EQ(failed.steps, 0);
  EXPECT_EQ(stuck.problem.x()(0), 2.0);
}

// f(x) = x - log x on x > 0 (minimiser 1): Newton's step x - x^2 from 3
// lands at -3 and (halved) at 0, both infeasible; the quarter step (1.5) is
// taken and Newton converges.
Callbacks LogBarrier() {
  Callbacks c;
  c.merit = [](const Eigen::VectorXd& x) { return x(0) - std::log(x(0)); };
  c.residual = [](const Eigen::VectorXd& x) {
    return Eigen::VectorXd::Constant(1, 1 - 1 / x(0)).eval();
  };
  c.jacobian = [](const Eigen::VectorXd& x) {
    return Eigen::MatrixXd::Constant(1, 1, 1 / (x(0) * x(0)));
  };
  c.feasible = [](const Eigen::VectorXd& x) { return x(0) > 0; };
  return c;
}

TEST(NewtonSolverTest, InfeasibleTrialPointsAreBacktracked) {
  const OneDimensionalRun run(LogBarrier(), 3.0, 1e-14, 20, 4);
  ASSERT_GE(run.problem.trial_points.size(), 3u);
  ExpectFirstTrialPoints(run.problem, {-3.0, 0.0});
  EXPECT_NEAR(run.problem.iterates[1](0), 1.5, 1e-12);
  EXPECT_EQ(run.problem.infeasible_evaluations, 2);
  EXPECT_TRUE(run.report.converged) << run.report.stop_reason;
  EXPECT_NEAR(run.problem.x()(0), 1.0, 1e-13);
}

TEST(NewtonSolverTest, StopReasons) {
  ReusableCholesky cholesky;
  {  // The start cannot be evaluated.
    FunctionProblem problem(LogBarrier(), Eigen::VectorXd::Constant(1, -1.0),
                            true);
    const NewtonReport r = SolveNewton(&problem, &cholesky, Minimize(0, 5));
    EXPECT_EQ(r.stop, NewtonStop::kInfeasibleStart);
    EXPECT_EQ(r.stop_reason, "degenerate initial guess");
    EXPECT_FALSE(r.converged);
    EXPECT_EQ(r.steps, 0);
    // No residual, not a residual of 0 (a caller's tolerance test fails).
    EXPECT_EQ(r.initial_gradient, HUGE_VAL);
    EXPECT_EQ(r.final_gradient, HUGE_VAL);
    EXPECT_EQ(r.final_merit, HUGE_VAL);
  }
  {  // A negative definite Hessian: f = -x^2 from 1.
    Callbacks c;
    c.merit = [](const Eigen::VectorXd& x) { return -x(0) * x(0); };
    c.residual = [](const Eigen::VectorXd& x) { return (-2 * x).eval(); };
    c.jacobian = [](const Eigen::VectorXd&) {
      return Eigen::MatrixXd::Constant(1, 1, -2.0);
    };
    FunctionProblem problem(c, Eigen::VectorXd::Constant(1, 1.0), true);
    ReusableCholesky fresh;
    const NewtonReport r = SolveNewton(&problem, &fresh, Minimize(0, 5));
    EXPECT_EQ(r.stop, NewtonStop::kLinearSolveFailed);
    EXPECT_EQ(r.stop_reason, "Hessian not positive definite");
    EXPECT_FALSE(r.converged);
  }
  {  // A singular Jacobian: F = (x0 + x1 - 1, 2 x0 + 2 x1 - 3).
    Callbacks c;
    c.residual = [](const Eigen::VectorXd& x) {
      return Eigen::Vector2d(x(0) + x(1) - 1, 2 * x(0) + 2 * x(1) - 3).eval();
    };
    c.jacobian = [](const Eigen::VectorXd&) {
      Eigen::MatrixXd j(2, 2);
      j << 1, 1, 2, 2;
      return j;
    };
    FunctionProblem problem(c, Eigen::Vector2d(0, 0), false);
    NewtonSettings s;
    s.mode = NewtonMode::kRootFind;
    SparseLu lu;
    const NewtonReport r = SolveNewton(&problem, &lu, s);
    EXPECT_EQ(r.stop, NewtonStop::kLinearSolveFailed);
    EXPECT_EQ(r.stop_reason, "singular Jacobian");
  }
  {  // Already converged: no step, no factorisation.
    const ConvexExample example(3);
    FunctionProblem problem(example.MakeCallbacks(), example.Minimiser(),
                            true);
    ReusableCholesky fresh;
    const NewtonReport r = SolveNewton(&problem, &fresh, Minimize(1e-12, 5));
    EXPECT_TRUE(r.converged);
    EXPECT_EQ(r.steps, 0);
    EXPECT_EQ(r.factorizations, 0);
  }
}

// A scripted problem for the stall rules: the residual max norm after the
// k-th accepted step is norms[k]; every full step is accepted (smaller max
// norm or not, the two-norm is scripted below the current one).
class ScriptedProblem : public NewtonProblem {
 public:
  explicit ScriptedProblem(std::vector<double> norms)
      : norms_(std::move(norms)) {}
  EvaluationStatus Merit(NewtonPoint, double*) override {
    return EvaluationStatus::kInfeasible;
  }
  EvaluationStatus Residual(NewtonPoint point, NewtonResidual* r) override {
    const int k = point == NewtonPoint::kCurrent ? step_ : step_ + 1;
    r->reduced = Eigen::VectorXd::Constant(1, norms_.at(k));
    r->max_norm = norms_.at(k);
    r->two_norm = 1.0 / (k + 1);  // always smaller
    return EvaluationStatus::kOk;
  }
  EvaluationStatus Assemble(LinearSystem* system) override {
    system->matrix = Eigen::MatrixXd::Identity(1, 1).sparseView();
    return EvaluationStatus::kOk;
  }
  void SetTrial(const Eigen::VectorXd&) override {}
  void AcceptTrial() override { ++step_; }

 private:
  std::vector<double> norms_;
  int step_ = 0;
};

NewtonSettings RootFinding() {
  NewtonSettings s;
  s.mode = NewtonMode::kRootFind;
  s.tolerance = 1e-12;
  s.max_steps = 20;
  s.accept_smaller_two_norm = true;
  return s;
}

TEST(NewtonSolverTest, RoundOffFloorStopsAStalledIteration) {
  ScriptedProblem problem({1, 1e-3, 1e-6, 0.8e-6, 1e-7, 1e-13});
  NewtonSettings s = RootFinding();
  s.round_off_floor = 1e-5;
  SparseLu lu;
  const NewtonReport r = SolveNewton(&problem, &lu, s);
  EXPECT_EQ(r.stop, NewtonStop::kRoundOffFloor);
  EXPECT_EQ(r.stop_reason, "round-off floor");
  EXPECT_EQ(r.steps, 3);  // 1e-6 -> 0.8e-6 did not halve below the floor
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.final_gradient, 0.8e-6);
  // Without the rule the same script converges.
  ScriptedProblem again({1, 1e-3, 1e-6, 0.8e-6, 1e-7, 1e-13});
  const NewtonReport full = SolveNewton(&again, &lu, RootFinding());
  EXPECT_TRUE(full.converged);
  EXPECT_EQ(full.steps, 5);
}

TEST(NewtonSolverTest, NoProgressRuleStopsACrawl) {
  ScriptedProblem problem({1, 0.9, 0.8, 0.7, 0.6, 0.4, 0.1});
  NewtonSettings s = RootFinding();
  s.progress_steps = 3;
  s.progress_factor = 0.5;
  SparseLu lu;
  const NewtonReport r = SolveNewton(&problem, &lu, s);
  EXPECT_EQ(r.stop, NewtonStop::kNoProgress);
  EXPECT_EQ(r.stop_reason, "no progress");
  EXPECT_EQ(r.steps, 3);
  EXPECT_FALSE(r.converged);
}

// The stall rule compares each accepted step's max norm with the one
// stall_steps accepted steps before: 0.25 is half of 0.5 (two steps
// before), 0.2 is more than half of 0.3, so the fourth step stops.
TEST(NewtonSolverTest, StallRuleStopsWhereTheNormDidNotHalfInTheWindow) {
  const std::vector<double> norms = {1, 0.5, 0.3, 0.25, 0.2, 0.19, 1e-13};
  ScriptedProblem problem(norms);
  NewtonSettings s = RootFinding();
  s.stall_steps = 2;
  s.stall_factor = 0.5;
  SparseLu lu;
  const NewtonReport r = SolveNewton(&problem, &lu, s);
  EXPECT_EQ(r.stop, NewtonStop::kNoProgress);
  EXPECT_EQ(r.steps, 4);
  EXPECT_EQ(r.final_gradient, 0.2);
  EXPECT_FALSE(r.converged);
  // Twin: without the rule the same script converges.
  ScriptedProblem again(norms);
  const NewtonReport full = SolveNewton(&again, &lu, RootFinding());
  EXPECT_TRUE(full.converged);
  EXPECT_EQ(full.steps, 6);
}

// f(x) = sum_i sqrt(1 + x_i^2) (Hyperbola in each coordinate), minimiser 0:
// from (3, -2.5, 2) the Newton step and its half both raise f.
Callbacks Hyperbolas() {
  Callbacks c;
  c.merit = [](const Eigen::VectorXd& x) {
    return (1 + x.array().square()).sqrt().sum();
  };
  c.residual = [](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(x.array() / (1 + x.array().square()).sqrt());
  };
  c.jacobian = [](const Eigen::VectorXd& x) {
    return Eigen::MatrixXd(
        (1 + x.array().square()).pow(-1.5).matrix().asDiagonal());
  };
  return c;
}

// Merits f(x_k) of the accepted iterates never rise.
::testing::AssertionResult MonotoneMerits(
    const Callbacks& c, const std::vector<Eigen::VectorXd>& iterates) {
  for (size_t k = 0; k + 1 < iterates.size(); ++k) {
    const double before = c.merit(iterates[k]);
    const double after = c.merit(iterates[k + 1]);
    if (!(after <= before)) {
      return ::testing::AssertionFailure()
             << "step " << k << ": " << before << " -> " << after;
    }
  }
  return ::testing::AssertionSuccess();
}

// The globalisation by H + lambda I: where the Newton step (and its half)
// raise f, plain Newton gives up (negative twin), the shifted engine
// decreases f monotonically to the minimiser.
TEST(NewtonSolverTest, ShiftedHessianDecreasesWhereTheNewtonStepRaisesF) {
  const Callbacks c = Hyperbolas();
  const Eigen::VectorXd x0 = Eigen::Vector3d(3, -2.5, 2);
  NewtonSettings s = Minimize(1e-12, 60);
  s.max_halvings = 1;
  {
    FunctionProblem plain(c, x0, true);
    ReusableCholesky cholesky;
    const NewtonReport r = SolveNewton(&plain, &cholesky, s);
    EXPECT_EQ(r.stop, NewtonStop::kLineSearchFailed);
    EXPECT_EQ(r.steps, 0);
    ASSERT_EQ(plain.trial_merits.size(), 2u);
    for (double m : plain.trial_merits) EXPECT_GT(m, c.merit(x0));
  }
  s.max_shifts = 8;
  FunctionProblem problem(c, x0, true);
  ReusableCholesky cholesky;
  const NewtonReport r = SolveNewton(&problem, &cholesky, s);
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_GE(r.shifted_steps, 1);
  EXPECT_GT(r.max_shift, 0);
  EXPECT_LT(problem.x().cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_TRUE(MonotoneMerits(c, problem.iterates));
}

// f(x) = sum_i x_i^4 / 4 - x_i^2 / 2 from (0.1, -0.2, 0.3): H = diag(3 x^2 -
// 1) is negative definite. Plain Newton stops ("Hessian not positive
// definite"); the shifted engine descends monotonically to the minimiser
// (sign(x_i)) of the start's orthant.
TEST(NewtonSolverTest, ShiftedHessianLeavesANegativeDefiniteRegion) {
  Callbacks c;
  c.merit = [](const Eigen::VectorXd& x) {
    return (x.array().pow(4) / 4 - x.array().square() / 2).sum();
  };
  c.residual = [](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(x.array().cube() - x.array());
  };
  c.jacobian = [](const Eigen::VectorXd& x) {
    return Eigen::MatrixXd((3 * x.array().square() - 1).matrix().asDiagonal());
  };
  const Eigen::VectorXd x0 = Eigen::Vector3d(0.1, -0.2, 0.3);
  NewtonSettings s = Minimize(1e-12, 200);
  {
    FunctionProblem plain(c, x0, true);
    ReusableCholesky cholesky;
    const NewtonReport r = SolveNewton(&plain, &cholesky, s);
    EXPECT_EQ(r.stop, NewtonStop::kLinearSolveFailed);
    EXPECT_EQ(r.stop_reason, "Hessian not positive definite");
  }
  s.max_shifts = 8;
  FunctionProblem problem(c, x0, true);
  ReusableCholesky cholesky;
  const NewtonReport r = SolveNewton(&problem, &cholesky, s);
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_LT((problem.x() - Eigen::Vector3d(1, -1, 1)).cwiseAbs().maxCoeff(),
            1e-11);
  EXPECT_TRUE(MonotoneMerits(c, problem.iterates));
  std::cout << "steps " << r.steps << ", shifted " << r.shifted_steps
            << ", factorisations " << r.factorizations << "\n";
}

// Rosenbrock's function as least squares, f = 1/2 |r|^2 with r = (10 (x_2 -
// x_1^2), 1 - x_1): gradient J^T r, model matrix the Gauss-Newton J^T J
// (J = [[-20 x_1, 10], [-1, 0]]), minimiser (1, 1) with r = 0 there, so
// Gauss-Newton converges fast near it. `wrong_j11` replaces dr_1/dx_1 in
// the model matrix only (a deliberately wrong derivative).
Callbacks RosenbrockLeastSquares(double wrong_j11_factor = 1) {
  Callbacks c;
  const auto r = [](const Eigen::VectorXd& x) {
    return Eigen::Vector2d(10 * (x(1) - x(0) * x(0)), 1 - x(0));
  };
  const auto jac = [](const Eigen::VectorXd& x, double factor) {
    Eigen::Matrix2d j;
    j << -20 * x(0) * factor, 10, -1, 0;
    return j;
  };
  c.merit = [r](const Eigen::VectorXd& x) { return 0.5 * r(x).squaredNorm(); };
  c.residual = [r, jac](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(jac(x, 1).transpose() * r(x));
  };
  c.jacobian = [jac, wrong_j11_factor](const Eigen::VectorXd& x) {
    const Eigen::Matrix2d j = jac(x, wrong_j11_factor);
    return Eigen::MatrixXd(j.transpose() * j);
  };
  return c;
}

NewtonSettings LevenbergMarquardt(double tolerance, int max_steps) {
  NewtonSettings s = Minimize(tolerance, max_steps);
  s.globalisation = NewtonSettings::Globalisation::kLevenbergMarquardt;
  return s;
}

// Accepted LM steps from Rosenbrock's start (-1.2, 1) until |x - (1, 1)| <=
// 1e-10 (max_steps + 1 if never), merits checked to be monotone.
int LevenbergMarquardtStepsOnRosenbrock(const Callbacks& c, int max_steps) {
  FunctionProblem problem(c, Eigen::Vector2d(-1.2, 1), true);
  ReusableCholesky cholesky;
  SolveNewton(&problem, &cholesky, LevenbergMarquardt(0, max_steps));
  EXPECT_TRUE(MonotoneMerits(c, problem.iterates));
  for (size_t k = 0; k < problem.iterates.size(); ++k) {
    if ((problem.iterates[k] - Eigen::Vector2d(1, 1)).norm() <= 1e-10) {
      return static_cast<int>(k);
    }
  }
  return max_steps + 1;
}

// The engine's Levenberg-Marquardt on the Gauss-Newton matrix solves
// Rosenbrock's valley with monotone merits in few steps (Ceres' LM needs
// about as many); the twin, whose model has dr_1/dx_1 off by a factor 1.5,
// still descends (LM accepts only decreasing steps) but is counted by the
// same helper as not converging within the bound.
TEST(NewtonSolverTest, LevenbergMarquardtSolvesRosenbrockOnTheGaussNewtonModel) {
  const int steps = LevenbergMarquardtStepsOnRosenbrock(RosenbrockLeastSquares(), 200);
  std::cout << "LM steps to 1e-10: " << steps << "\n";
  EXPECT_LE(steps, 40);
  const int wrong =
      LevenbergMarquardtStepsOnRosenbrock(RosenbrockLeastSquares(1.5), 200);
  std::cout << "with a wrong model: " << wrong << "\n";
  EXPECT_GT(wrong, 40);
}

// The hand-over rule ends LM at its first accepted step that divides the
// gradient's max norm by the set factor (here on Rosenbrock's valley, where
// Gauss-Newton's steps contract the gradient by less far from the
// minimiser and by more near it). The contractions are read from the
// iterates with the problem's own gradient; the twin without the rule runs
// to convergence through the same steps.
std::vector<double> GradientMaxNorms(const Callbacks& c,
                                     const std::vector<Eigen::VectorXd>& xs) {
  std::vector<double> norms;
  for (const Eigen::VectorXd& x : xs) {
    norms.push_back(c.residual(x).cwiseAbs().maxCoeff());
  }
  return norms;
}

TEST(NewtonSolverTest, HandOverEndsLevenbergMarquardtAtAContractingStep) {
  const Callbacks c = RosenbrockLeastSquares();
  const double factor = 10;
  NewtonSettings s = LevenbergMarquardt(1e-12, 200);
  s.hand_over_contraction = factor;
  FunctionProblem problem(c, Eigen::Vector2d(-1.2, 1), true);
  ReusableCholesky cholesky;
  const NewtonReport r = SolveNewton(&problem, &cholesky, s);
  EXPECT_EQ(r.stop, NewtonStop::kHandedOver);
  EXPECT_EQ(r.stop_reason, "gradient contracting: handed over");
  EXPECT_FALSE(r.converged);
  const std::vector<double> g = GradientMaxNorms(c, problem.iterates);
  ASSERT_GE(g.size(), 3u);  // a few steps before the contracting one
  for (size_t k = 1; k + 1 < g.size(); ++k) EXPECT_GT(g[k] * factor, g[k - 1]);
  EXPECT_LE(g.back() * factor, g[g.size() - 2]);
  // Without the rule: the same first steps, on to convergence.
  FunctionProblem all(c, Eigen::Vector2d(-1.2, 1), true);
  ReusableCholesky cholesky2;
  const NewtonReport full =
      SolveNewton(&all, &cholesky2, LevenbergMarquardt(1e-12, 200));
  EXPECT_TRUE(full.converged) << full.stop_reason;
  ASSERT_GT(all.iterates.size(), problem.iterates.size());
  for (size_t k = 0; k < problem.iterates.size(); ++k) {
    EXPECT_EQ(all.iterates[k], problem.iterates[k]) << k;
  }
}

// On the hyperbolas from (3, -2.5, 2), where the Newton step raises f, and
// with the exact (there positive definite but misleading) Hessian as the
// model: every accepted step lowers f, rejected steps raise lambda (the
// largest lambda tried exceeds the initial one), and it converges.
TEST(NewtonSolverTest, LevenbergMarquardtRejectsRisingStepsAndRaisesLambda) {
  const Callbacks c = Hyperbolas();
  FunctionProblem problem(c, Eigen::Vector3d(3, -2.5, 2), true);
  ReusableCholesky cholesky;
  NewtonSettings s = LevenbergMarquardt(1e-12, 100);
  s.lm_initial = 1e-8;
  s.accept_smaller_max_norm = true;  // the last steps change f below round-off
  const NewtonReport r = SolveNewton(&problem, &cholesky, s);
  EXPECT_TRUE(r.converged) << r.stop_reason;
  EXPECT_TRUE(MonotoneMerits(c, problem.iterates));
  EXPECT_GT(r.max_shift, 1e-8);
  EXPECT_EQ(r.shifted_steps, r.steps);
  EXPECT_GT(problem.trial_points.size(), problem.iterates.size() - 1);
  EXPECT_LT(problem.x().cwiseAbs().maxCoeff(), 1e-11);
}

// f(x) = 1 + scale (x_0^2 / 2 + (x_1^2 - 1)^2 / 4): a saddle at the origin,
// valleys at x_1 = +-1, its gradient and Hessian; scaled small, f changes
// only below its round-off near the saddle.
Callbacks ScaledSaddle(double scale) {
  Callbacks c;
  c.merit = [scale](const Eigen::VectorXd& x) {
    return 1 +
           scale * (0.5 * x[0] * x[0] + 0.25 * std::pow(x[1] * x[1] - 1, 2));
  };
  c.residual = [scale](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(
        scale *
        (Eigen::VectorXd(2) << x[0], x[1] * (x[1] * x[1] - 1)).finished());
  };
  c.jacobian = [scale](const Eigen::VectorXd& x) {
    Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, 2);
    h(0, 0) = scale;
    h(1, 1) = scale * (3 * x[1] * x[1] - 1);
    return h;
  };
  return c;
}

// Below round-off the residual decides in LM too (as in the trust region):
// on a saddle scaled by 1e-6 every damped step from (0, 1e-3) towards the
// valleys x_1 = +-1 lowers f by about 1e-12 (below merit_round_off = 1e-10
// of f = 1, so does the model's predicted decrease) with a ratio near 1 --
// a ratio rule would take it -- but raises the gradient: no step is taken,
// and LM gives up after its rejection limit. The twin, the same saddle
// unscaled, moves by the ratio and converges to a valley.
TEST(NewtonSolverTest, LevenbergMarquardtBelowRoundOffTheGradientDecides) {
  NewtonSettings settings = LevenbergMarquardt(1e-20, 60);
  settings.merit_round_off = 1e-10;
  settings.lm_max_rejections = 8;
  Eigen::VectorXd x0(2);
  x0 << 0, 1e-3;
  FunctionProblem flat(ScaledSaddle(1e-6), x0, true);
  ReusableCholesky cholesky;
  const NewtonReport stayed = SolveNewton(&flat, &cholesky, settings);
  EXPECT_FALSE(stayed.converged);
  EXPECT_EQ(stayed.stop, NewtonStop::kLineSearchFailed);
  EXPECT_EQ(flat.iterates.size(), 1u);  // no step taken
  // Its trials did lower f, by less than its round-off and not by nothing.
  const double f0 = ScaledSaddle(1e-6).merit(x0);
  int lower = 0;
  for (double f : flat.trial_merits) {
    if (f < f0) {
      ++lower;
      EXPECT_GT(f0 - f, 1e-15);
      EXPECT_LT(f0 - f, 1e-10);
    }
  }
  EXPECT_GE(lower, 1);

  settings.tolerance = 1e-11;
  FunctionProblem steep(ScaledSaddle(1), x0, true);
  ReusableCholesky cholesky2;
  const NewtonReport moved = SolveNewton(&steep, &cholesky2, settings);
  EXPECT_TRUE(moved.converged) << moved.stop_reason;
  EXPECT_NEAR(std::abs(steep.x()[1]), 1, 1e-10);
}

// lm_max_rejections rejected steps in a row end the solve with
// kLineSearchFailed: with the gradient's sign flipped every model step goes
// uphill; 1 + lm_max_rejections trials, each raising f, none accepted.
TEST(NewtonSolverTest, LevenbergMarquardtGivesUpAfterTheRejectionLimit) {
  Callbacks c = Hyperbolas();
  // The gradient's sign flipped: every model step points uphill.
  const auto gradient = c.residual;
  c.residual = [gradient](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(-gradient(x));
  };
  FunctionProblem problem(c, Eigen::Vector3d(3, -2.5, 2), true);
  ReusableCholesky cholesky;
  NewtonSettings s = LevenbergMarquardt(1e-12, 100);
  s.lm_max_rejections = 5;
  const NewtonReport r = SolveNewton(&problem, &cholesky, s);
  EXPECT_EQ(r.stop, NewtonStop::kLineSearchFailed);
  EXPECT_EQ(r.steps, 0);
  ASSERT_EQ(problem.trial_merits.size(), 6u);
  for (double m : problem.trial_merits) EXPECT_GT(m, c.merit(problem.x()));
}

// The stop hook ends an LM solve at the current point too: polled before
// every iteration and every retry, the third poll stops after two accepted
// steps, which are those of the same solve capped at two steps.
TEST(NewtonSolverTest, LevenbergMarquardtStopsOnRequest) {
  const Callbacks c = RosenbrockLeastSquares();
  FunctionProblem capped(c, Eigen::Vector2d(-1.2, 1), true);
  ReusableCholesky cholesky;
  const NewtonReport two =
      SolveNewton(&capped, &cholesky, LevenbergMarquardt(0, 2));
  ASSERT_EQ(two.steps, 2);
  FunctionProblem stopped(c, Eigen::Vector2d(-1.2, 1), true);
  NewtonSettings s = LevenbergMarquardt(0, 100);
  int polls = 0;
  s.stop = [&polls] { return ++polls == 3; };
  ReusableCholesky cholesky2;
  const NewtonReport r = SolveNewton(&stopped, &cholesky2, s);
  EXPECT_EQ(r.stop, NewtonStop::kStopped);
  EXPECT_FALSE(r.converged);
  EXPECT_LE(r.steps, 2);
  EXPECT_EQ(stopped.iterates.back(),
            capped.iterates[std::min<size_t>(r.steps, 2)]);
}

TEST(NewtonSolverTest, AppendSumsCountsAndKeepsTheFirstInitialGradient) {
  NewtonReport total, a, b;
  a.steps = 2;
  a.initial_gradient = 5;
  a.final_gradient = 1;
  a.factorizations = 1;
  a.cg_iterations = 3;
  a.stop_reason = "Hessian not positive definite";
  b.steps = 4;
  b.initial_gradient = 1;
  b.final_gradient = 1e-9;
  b.factorizations = 2;
  b.cg_iterations = 7;
  b.converged = true;
  b.stop = NewtonStop::kConverged;
  b.stop_reason = "converged";
  total.Append(a);
  total.Append(b);
  EXPECT_EQ(total.attempts, 2);
  EXPECT_EQ(total.steps, 6);
  EXPECT_EQ(total.initial_gradient, 5);
  EXPECT_EQ(total.final_gradient, 1e-9);
  EXPECT_EQ(total.factorizations, 3);
  EXPECT_EQ(total.cg_iterations, 10);
  EXPECT_TRUE(total.converged);
  EXPECT_EQ(total.stop_reason, "converged");
}

}  // namespace
}  // namespace shellspace

namespace shellspace {
namespace {

NewtonSettings TrustRegion(double tolerance, int max_steps) {
  NewtonSettings s = Minimize(tolerance, max_steps);
  s.globalisation = NewtonSettings::Globalisation::kTrustRegion;
  s.forcing_rule = NewtonSettings::Forcing::kInexactNewton;
  s.forcing = 0.1;
  return s;
}

// The trust region with Steihaug-Toint CG on the convex example: where CG
// stays inside the region the step is the inexact Newton step with forcing
// min(0.1, |g| / |g_0|), so the rate is quadratic, as the line search's.
TEST(NewtonTrustRegionTest, ConvergesQuadraticallyOnAStrictlyConvexFunction) {
  const ConvexExample example(6);
  FunctionProblem problem(example.MakeCallbacks(), Eigen::VectorXd::Zero(6),
                          true);
  ReusableCholesky cholesky;
  const NewtonReport report =
      SolveNewton(&problem, &cholesky, TrustRegion(1e-13, 30));
  EXPECT_TRUE(report.converged) << report.stop_reason;
  const Eigen::VectorXd x_star = example.Minimiser();
  EXPECT_LT((problem.x() - x_star).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_TRUE(QuadraticRate(problem.iterates, x_star, 5.0));
  EXPECT_EQ(report.negative_curvature_steps, 0);
  EXPECT_EQ(report.shifted_preconditioners, 0);
}

// Negative twin through the same rate check: the trust region on a wrong
// Hessian (2 H) converges only linearly.
TEST(NewtonTrustRegionTest, WrongHessianFailsTheQuadraticRateCheck) {
  const ConvexExample example(6);
  FunctionProblem problem(WithDoubledHessian(example), Eigen::VectorXd::Zero(6),
                          true);
  ReusableCholesky cholesky;
  const NewtonReport report =
      SolveNewton(&problem, &cholesky, TrustRegion(1e-13, 100));
  EXPECT_TRUE(report.converged) << report.stop_reason;
  EXPECT_FALSE(QuadraticRate(problem.iterates, example.Minimiser(), 5.0));
}

// f(x, y) = x^2/2 + (y^2 - 1)^2 / 4: a saddle at the origin (H = diag(1,
// -1)), minimisers (0, +-1). From a point near the saddle H is indefinite:
// the preconditioner is factorised from H + sigma I, CG meets the negative
// curvature, and the step follows it to the region's boundary -- the
// line-search Newton step would head for the saddle. The trust region
// reaches a minimiser, with f never rising.
TEST(NewtonTrustRegionTest, LeavesASaddleAlongNegativeCurvature) {
  Callbacks c;
  c.merit = [](const Eigen::VectorXd& x) {
    return 0.5 * x[0] * x[0] + 0.25 * std::pow(x[1] * x[1] - 1, 2);
  };
  c.residual = [](const Eigen::VectorXd& x) {
    return Eigen::VectorXd((Eigen::VectorXd(2) << x[0],
                            x[1] * (x[1] * x[1] - 1))
                               .finished());
  };
  c.jacobian = [](const Eigen::VectorXd& x) {
    Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, 2);
    h(0, 0) = 1;
    h(1, 1) = 3 * x[1] * x[1] - 1;
    return h;
  };
  Eigen::VectorXd x0(2);
  x0 << 0.5, 1e-3;
  FunctionProblem problem(c, x0, true);
  ReusableCholesky cholesky;
  const NewtonReport report =
      SolveNewton(&problem, &cholesky, TrustRegion(1e-12, 60));
  EXPECT_TRUE(report.converged) << report.stop_reason;
  EXPECT_NEAR(problem.x()[0], 0, 1e-10);
  EXPECT_NEAR(std::abs(problem.x()[1]), 1, 1e-10);
  EXPECT_GE(report.negative_curvature_steps, 1);
  EXPECT_GE(report.shifted_preconditioners, 1);
  double previous = c.merit(problem.iterates.front());
  for (const Eigen::VectorXd& x : problem.iterates) {
    EXPECT_LE(c.merit(x), previous + 1e-15);
    previous = c.merit(x);
  }
  // The line search from the same point ends at the saddle (its Newton
  // step is not a descent step there, and with shifts it still stalls
  // near y = 0) or needs the shifted Hessian: it does not take the
  // negative-curvature step the trust region takes.
  FunctionProblem line_search(c, x0, true);
  ReusableCholesky cholesky2;
  const NewtonReport plain =
      SolveNewton(&line_search, &cholesky2, Minimize(1e-12, 60));
  EXPECT_FALSE(plain.converged && std::abs(line_search.x()[1]) > 0.5);
}

// The basin probe: from near the saddle the first step follows negative
// curvature, so the probe ends there (kOutsideBasin) instead of
// globalising; on the convex example every step is a full Newton step of a
// good model (rho near 1) and the probe converges as the plain trust region
// does, through the same iterates.
TEST(NewtonTrustRegionTest, BasinProbeStopsAtTheFirstStepThatIsNotANewtonStep) {
  Callbacks saddle;
  saddle.merit = [](const Eigen::VectorXd& x) {
    return 0.5 * x[0] * x[0] + 0.25 * std::pow(x[1] * x[1] - 1, 2);
  };
  saddle.residual = [](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(
        (Eigen::VectorXd(2) << x[0], x[1] * (x[1] * x[1] - 1)).finished());
  };
  saddle.jacobian = [](const Eigen::VectorXd& x) {
    Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, 2);
    h(0, 0) = 1;
    h(1, 1) = 3 * x[1] * x[1] - 1;
    return h;
  };
  NewtonSettings probe = TrustRegion(1e-12, 60);
  probe.tr_basin_ratio = 0.5;
  Eigen::VectorXd x0(2);
  x0 << 0.5, 1e-3;
  FunctionProblem near_saddle(saddle, x0, true);
  ReusableCholesky cholesky;
  const NewtonReport stopped = SolveNewton(&near_saddle, &cholesky, probe);
  EXPECT_EQ(stopped.stop, NewtonStop::kOutsideBasin);
  EXPECT_EQ(stopped.stop_reason, "not yet in Newton's basin");
  EXPECT_LE(stopped.steps, 1);
  EXPECT_LE(saddle.merit(near_saddle.x()), saddle.merit(x0));

  const ConvexExample example(6);
  FunctionProblem convex(example.MakeCallbacks(), Eigen::VectorXd::Zero(6),
                         true);
  ReusableCholesky cholesky2;
  const NewtonReport converged = SolveNewton(&convex, &cholesky2, probe);
  EXPECT_TRUE(converged.converged) << converged.stop_reason;
  FunctionProblem plain(example.MakeCallbacks(), Eigen::VectorXd::Zero(6),
                        true);
  ReusableCholesky cholesky3;
  SolveNewton(&plain, &cholesky3, TrustRegion(1e-12, 60));
  EXPECT_EQ(convex.iterates, plain.iterates);
}

// Below the merit's round-off rho is noise, and the gradient decides. The
// saddle above, shifted and scaled, f = 1 + scale (x^2/2 + (y^2 - 1)^2/4),
// from (0, 1e-3): the negative-curvature step in y lowers f but raises the
// gradient (|g_y| = scale |y (y^2 - 1)| grows up to y = 3^-1/2). With scale
// 1e-12 every change of f is below 1e-10 |f| (merit_round_off, with
// accept_smaller_max_norm as the path finish sets it): no such step is
// taken, however good its computed rho, and the solve ends where it
// started. The twin with scale 1, the same steps in exact arithmetic but
// far above round-off, takes them and reaches a minimiser.
TEST(NewtonTrustRegionTest, BelowRoundOffTheGradientDecides) {
  // Each to 1e-8 of its initial gradient, scale 1e-3.
  NewtonSettings settings = TrustRegion(1e-23, 60);
  settings.accept_smaller_max_norm = true;
  settings.merit_round_off = 1e-10;
  Eigen::VectorXd x0(2);
  x0 << 0, 1e-3;
  FunctionProblem flat(ScaledSaddle(1e-12), x0, true);
  ReusableCholesky cholesky;
  const NewtonReport stayed = SolveNewton(&flat, &cholesky, settings);
  EXPECT_FALSE(stayed.converged);
  EXPECT_EQ(flat.iterates.size(), 1u);  // no step taken
  EXPECT_GE(stayed.rejected_trials, 1);
  // Some of its trials did lower f, by less than its round-off.
  const double f0 = ScaledSaddle(1e-12).merit(x0);
  EXPECT_TRUE(std::any_of(flat.trial_merits.begin(), flat.trial_merits.end(),
                          [f0](double f) { return f < f0; }));

  settings.tolerance = 1e-11;
  FunctionProblem steep(ScaledSaddle(1), x0, true);
  ReusableCholesky cholesky2;
  const NewtonReport moved = SolveNewton(&steep, &cholesky2, settings);
  EXPECT_TRUE(moved.converged) << moved.stop_reason;
  EXPECT_NEAR(std::abs(steep.x()[1]), 1, 1e-10);
  EXPECT_GE(moved.negative_curvature_steps, 1);
}

// Infeasible trials (outside |x|_inf < 3 here) shrink the region: the trust
// region never accepts one and still converges.
TEST(NewtonTrustRegionTest, AnInfeasibleTrialShrinksTheRegion) {
  const ConvexExample example(6);
  Callbacks c = example.MakeCallbacks();
  c.feasible = [](const Eigen::VectorXd& x) {
    return x.cwiseAbs().maxCoeff() < 3;
  };
  Eigen::VectorXd x0 = Eigen::VectorXd::Constant(6, 2.9);
  FunctionProblem problem(c, x0, true);
  ReusableCholesky cholesky;
  NewtonSettings settings = TrustRegion(1e-12, 60);
  settings.tr_initial_radius = 1e3;
  const NewtonReport report = SolveNewton(&problem, &cholesky, settings);
  EXPECT_TRUE(report.converged) << report.stop_reason;
  for (const Eigen::VectorXd& x : problem.iterates) {
    EXPECT_LT(x.cwiseAbs().maxCoeff(), 3);
  }
}

}  // namespace
}  // namespace shellspace
