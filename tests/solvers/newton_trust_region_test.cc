// The Newton engine's trust region with Steihaug-Toint CG
// (solvers/newton_solver.h) on small closed-form problems
// (tests/testing/newton_problems.h): quadratic convergence on a strictly
// convex function (and its negative twin), a saddle left along negative
// curvature, the basin probe, the gradient deciding below the merit's
// round-off, and infeasible trials that shrink the region.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "shellspace/solvers/newton_solver.h"
#include "shellspace/solvers/reusable_cholesky.h"
#include "tests/testing/newton_problems.h"

namespace shellspace {
namespace {

using testing::Callbacks;
using testing::ConvexExample;
using testing::FunctionProblem;
using testing::Minimize;
using testing::QuadraticRate;
using testing::ScaledSaddle;
using testing::WithDoubledHessian;

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
