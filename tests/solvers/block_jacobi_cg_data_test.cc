// Block-Jacobi preconditioned CG: against a direct solve on the Kronecker
// model of a path Hessian and on a real assembled path Hessian; iteration
// counts of the model; the statuses.
#include "shellspace/solvers/block_jacobi_cg.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include "shellspace/geometry/topology.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "tests/testing/kronecker_model.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

SparseMatrix PlateMetric() { return testing::PlateLaplacianMetric(0.1); }

SparseMatrix KroneckerModel(const SparseMatrix& g, int K) {
  return testing::KroneckerPathModel(g, K);
}

std::vector<int> Offsets(int blocks, int m) {
  return testing::SliceOffsets(blocks, m);
}

// Solves lower x = b by `cg` (its diagonal blocks, `blocks` blocks of m
// unknowns, factorised here; CG from M^-1 b to 1e-12 in at most
// max_iterations) and expects x within `relative_error` (normwise) of the
// direct solution (SimplicialLLT). x and the CG iterations are returned in
// *x and *iterations.
void SolveAndCompareWithDirect(const SparseMatrix& lower,
                               const Eigen::VectorXd& b, int blocks, int m,
                               int max_iterations, double relative_error,
                               BlockJacobiCg* cg, Eigen::VectorXd* x,
                               int* iterations) {
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower> direct(lower);
  ASSERT_EQ(direct.info(), Eigen::Success);
  const Eigen::VectorXd expected = direct.solve(b);
  ASSERT_TRUE(cg->Factorize(lower, Offsets(blocks, m)));
  ASSERT_EQ(cg->Solve(lower, b, 1e-12, max_iterations, x, iterations),
            BlockJacobiCg::Status::kSolved);
  EXPECT_LT((*x - expected).norm(), relative_error * expected.norm());
}

TEST(BlockJacobiCgTest, SolvesTheKroneckerModelInOrderKIterations) {
  const SparseMatrix g = PlateMetric();
  const int m = static_cast<int>(g.rows());
  int previous = 0;
  for (int K : {4, 8, 16, 32}) {
    const SparseMatrix lower = KroneckerModel(g, K);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(lower.rows(), -1, 2);
    BlockJacobiCg cg;
    Eigen::VectorXd x;
    int iterations = 0;
    SCOPED_TRACE(K);
    SolveAndCompareWithDirect(lower, b, K - 1, m, 1000, 1e-9, &cg, &x,
                              &iterations);
    if (HasFatalFailure()) return;
    // CG on T preconditioned by 2I: at most K - 1 iterations in exact
    // arithmetic (K - 1 distinct eigenvalues), so O(K).
    EXPECT_LE(iterations, K + 2) << K;
    EXPECT_GE(iterations, previous) << K;
    previous = iterations;
  }
}

// A warm start from the solution needs no iteration; the twin, the same
// solve from M^-1 b, needs some; a warm start from a half-way iterate needs
// fewer than the cold solve.
TEST(BlockJacobiCgTest, WarmStartContinuesFromTheGivenIterate) {
  const SparseMatrix g = PlateMetric();
  const int m = static_cast<int>(g.rows());
  const SparseMatrix lower = KroneckerModel(g, 8);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(lower.rows(), -1, 2);
  BlockJacobiCg cg;  // plain block Jacobi: several iterations on the model
  ASSERT_TRUE(cg.Factorize(lower, Offsets(7, m)));
  Eigen::VectorXd cold;
  int cold_iterations = 0;
  ASSERT_EQ(cg.Solve(lower, b, 1e-12, 1000, &cold, &cold_iterations),
            BlockJacobiCg::Status::kSolved);
  EXPECT_GE(cold_iterations, 3);
  Eigen::VectorXd x = cold;
  int iterations = -1;
  ASSERT_EQ(cg.Solve(lower, b, 1e-12, 1000, &x, &iterations, true),
            BlockJacobiCg::Status::kSolved);
  EXPECT_EQ(iterations, 0);
  x = cold;
  ASSERT_EQ(cg.Solve(lower, b, 1e-12, 1000, &x, &iterations, false),
            BlockJacobiCg::Status::kSolved);
  EXPECT_EQ(iterations, cold_iterations);
  Eigen::VectorXd half;
  ASSERT_EQ(cg.Solve(lower, b, 1e-3, 1000, &half, &iterations),
            BlockJacobiCg::Status::kSolved);
  ASSERT_EQ(cg.Solve(lower, b, 1e-12, 1000, &half, &iterations, true),
            BlockJacobiCg::Status::kSolved);
  EXPECT_LT(iterations, cold_iterations);
}

TEST(BlockJacobiCgTest, MatchesADirectSolveOfARealPathHessian) {
  const auto [a, b, space] =
      testing::LoadPair("plate/plate121.ply", "plate/plate121_rolledA.ply");
  const int K = 6;
  // Two rows of the plate (one row alone leaves the rotation about it free).
  std::vector<int> mask;
  for (int v = 0; v < 15; ++v) mask.push_back(v);
  // The Hessian at the geodesic (at the linear path it is indefinite).
  GeodesicInput input = GeodesicInput::Between(a.positions, b.positions, K);
  input.fixed_vertices = mask;
  const ShellPath path = SolveGeodesic(space, input, SolverSettings{}).path;
  const SparseMatrix basis = FreeVertexBasis(a.num_vertices(), mask);
  const std::vector<SparseMatrix> bases(K - 1, basis);
  const SparseMatrix lower =
      PathHessianAssembler(space).Assemble(path, bases, 2);
  const int m = static_cast<int>(basis.cols());
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(lower.rows(), 1, -1);
  BlockJacobiCg cg;
  Eigen::VectorXd x;
  int iterations = 0;
  SolveAndCompareWithDirect(lower, rhs, K - 1, m, 2000, 1e-8, &cg, &x,
                            &iterations);
  if (HasFatalFailure()) return;
  std::cout << "block-Jacobi CG iterations on the plate path Hessian (K = 6): "
            << iterations << "\n";
  // Deterministic: the same solve gives the same digits and count.
  Eigen::VectorXd again;
  int iterations_again = 0;
  cg.Solve(lower, rhs, 1e-12, 2000, &again, &iterations_again);
  EXPECT_EQ(iterations_again, iterations);
  EXPECT_EQ(again, x);
}

TEST(BlockJacobiCgTest, ReportsIndefiniteBlocksAndIterationLimits) {
  const SparseMatrix g = PlateMetric();
  const int m = static_cast<int>(g.rows());
  const SparseMatrix lower = KroneckerModel(g, 8);
  BlockJacobiCg cg;
  ASSERT_TRUE(cg.Factorize(lower, Offsets(7, m)));
  Eigen::VectorXd x;
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(lower.rows());
  EXPECT_EQ(cg.Solve(lower, b, 1e-14, 1, &x),
            BlockJacobiCg::Status::kNotConverged);
  // A negative diagonal block.
  const SparseMatrix negative = -lower;
  BlockJacobiCg bad;
  EXPECT_FALSE(bad.Factorize(negative, Offsets(7, m)));
  EXPECT_EQ(bad.Solve(negative, b, 1e-8, 10, &x),
            BlockJacobiCg::Status::kNotPositive);
}

}  // namespace
}  // namespace shellspace
