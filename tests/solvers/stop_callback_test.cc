// SolverSettings::stop in a Ceres solve (SolveWithSettings): a token that
// says stop at iteration 2 ends the solve there with USER_SUCCESS and the
// parameters of iteration 2 (the same as a solve capped at 2 iterations);
// one that says stop from the start ends it at its first poll, at the
// start; one that never says stop changes nothing.
#include <ceres/autodiff_cost_function.h>
#include <ceres/problem.h>
#include <gtest/gtest.h>

#include <array>

#include "shellspace/solvers/solver_settings.h"

namespace shellspace {
namespace {

// Rosenbrock as least squares: r = (10 (y - x^2), 1 - x).
struct Rosenbrock {
  template <typename T>
  bool operator()(const T* const p, T* r) const {
    r[0] = T(10.0) * (p[1] - p[0] * p[0]);
    r[1] = T(1.0) - p[0];
    return true;
  }
};

// Solves from (-1.2, 1); returns the parameters.
std::array<double, 2> Solve(const SolverSettings& settings,
                            ceres::Solver::Summary* summary) {
  std::array<double, 2> p = {-1.2, 1.0};
  ceres::Problem problem;
  problem.AddResidualBlock(
      new ceres::AutoDiffCostFunction<Rosenbrock, 2, 2>(new Rosenbrock),
      nullptr, p.data());
  *summary = SolveWithSettings(&problem, settings);
  return p;
}

TEST(StopCallbackTest, StopsAtTheIterationItFiresKeepingItsIterate) {
  SolverSettings capped;
  capped.linear_solver = SolverSettings::LinearSolver::kDenseQr;
  capped.max_iterations = 2;
  ceres::Solver::Summary capped_summary;
  const auto two = Solve(capped, &capped_summary);
  ASSERT_EQ(capped_summary.termination_type, ceres::NO_CONVERGENCE);

  SolverSettings settings = capped;
  settings.max_iterations = 100;
  int polls = 0;  // iteration 0, 1, 2
  settings.stop = StopToken([&polls] { return ++polls == 3; });
  ceres::Solver::Summary summary;
  const auto stopped = Solve(settings, &summary);
  EXPECT_TRUE(StoppedByRequest(summary));
  EXPECT_EQ(summary.iterations.size(), capped_summary.iterations.size());
  EXPECT_EQ(stopped, two);
  EXPECT_FALSE(StoppedByRequest(capped_summary));

  // Never firing: the uncapped solve, bit for bit.
  SolverSettings plain = capped;
  plain.max_iterations = 100;
  SolverSettings never = plain;
  never.stop = StopToken([] { return false; });
  ceres::Solver::Summary a, b;
  const auto x = Solve(plain, &a);
  const auto y = Solve(never, &b);
  EXPECT_EQ(a.termination_type, ceres::CONVERGENCE);
  EXPECT_EQ(b.termination_type, ceres::CONVERGENCE);
  EXPECT_EQ(x, y);
  EXPECT_EQ(a.iterations.size(), b.iterations.size());
  EXPECT_NEAR(x[0], 1.0, 1e-6);
  EXPECT_NEAR(x[1], 1.0, 1e-6);
}

TEST(StopCallbackTest, AStoppedTokenEndsTheSolveAtItsFirstPoll) {
  SolverSettings settings;
  settings.linear_solver = SolverSettings::LinearSolver::kDenseQr;
  int polls = 0;
  settings.stop = StopToken([&polls] {
    ++polls;
    return true;
  });
  ceres::Solver::Summary summary;
  const auto p = Solve(settings, &summary);
  EXPECT_TRUE(StoppedByRequest(summary));
  EXPECT_EQ(polls, 1);
  ASSERT_EQ(summary.iterations.size(), 1u);  // iteration 0 only
  EXPECT_EQ(p, (std::array<double, 2>{-1.2, 1.0}));
}

}  // namespace
}  // namespace shellspace
