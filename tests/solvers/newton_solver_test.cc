// The Newton engine (solvers/newton_solver.h) with its line search on small
// closed-form problems (tests/testing/newton_problems.h): quadratic
// convergence on a strictly convex function, root finding on a nonlinear
// system, the line search (an increasing step rejected, an infeasible trial
// point backtracked), the shifted Hessian H + lambda I, the stall rules,
// the stop hook and the stop reasons, and the sum of reports.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <iostream>
#include <vector>

#include "shellspace/solvers/newton_solver.h"
#include "shellspace/solvers/reusable_cholesky.h"
#include "shellspace/solvers/sparse_lu.h"
#include "tests/testing/newton_problems.h"

namespace shellspace {
namespace {

using testing::Callbacks;
using testing::ConvexExample;
using testing::FunctionProblem;
using testing::Hyperbolas;
using testing::Minimize;
using testing::MonotoneMerits;
using testing::QuadraticRate;
using testing::WithDoubledHessian;

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
  settings.stop = StopToken([&polls] { return ++polls == 3; });
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
  never.stop = StopToken([] { return false; });
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
