// RequireVariableResidual (solvers/problem_checks.h): a residual whose
// blocks are all constant is an error naming it; one free block is enough.
// The silent alternative it replaces: Ceres reports CONVERGENCE after 0
// iterations with the residual's cost unchanged.
#include <gtest/gtest.h>

#include <ceres/ceres.h>

#include <string>

#include "shellspace/geometry/mesh.h"
#include "shellspace/solvers/problem_checks.h"

namespace shellspace {
namespace {

struct Difference {
  template <typename T>
  bool operator()(const T* x, const T* y, T* r) const {
    r[0] = x[0] - y[0] - T(1);
    return true;
  }
};

TEST(ProblemChecksTest, AResidualOnConstantBlocksIsAnErrorNamingIt) {
  double x = 0, y = 0;
  ceres::Problem problem;
  const ceres::ResidualBlockId id = problem.AddResidualBlock(
      new ceres::AutoDiffCostFunction<Difference, 1, 1, 1>(new Difference), nullptr,
      &x, &y);
  EXPECT_NO_THROW(RequireVariableResidual(problem, id, "the pull"));
  problem.SetParameterBlockConstant(&x);
  EXPECT_NO_THROW(RequireVariableResidual(problem, id, "the pull"));  // y free
  problem.SetParameterBlockConstant(&y);
  try {
    RequireVariableResidual(problem, id, "the pull on vertex 7");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("the pull on vertex 7 acts only on", 0), 0u)
        << e.what();
  }
  // What the check prevents: Ceres "converges" without moving.
  ceres::Solver::Options options;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  EXPECT_EQ(summary.termination_type, ceres::CONVERGENCE)
      << summary.FullReport();
  EXPECT_LE(summary.iterations.size(), 1u);
  EXPECT_EQ(x, 0.0);
  EXPECT_EQ(y, 0.0);
}

}  // namespace
}  // namespace shellspace
