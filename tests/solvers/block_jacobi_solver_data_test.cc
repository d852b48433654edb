// BlockJacobiSolver through the LinearSolver interface: against a direct
// solve on the Kronecker model T (x) G of a path Hessian, the deterministic
// refactorisation rule (stale factors within the iteration budget, fresh
// ones beyond it), and the "not positive definite" failures.
#include "shellspace/solvers/block_jacobi_solver.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include "shellspace/geometry/topology.h"
#include "tests/testing/kronecker_model.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

SparseMatrix PlateMetric(double shift) {
  return testing::PlateLaplacianMetric(shift);
}

// The Kronecker model (tests/testing/kronecker_model.h) with its slices.
LinearSystem KroneckerSystem(const SparseMatrix& g, int K,
                             double diagonal_scale = 1.0) {
  LinearSystem system;
  system.matrix = testing::KroneckerPathModel(g, K, diagonal_scale);
  system.block_offsets =
      testing::SliceOffsets(K - 1, static_cast<int>(g.rows()));
  return system;
}

Eigen::VectorXd DirectSolve(const LinearSystem& system,
                            const Eigen::VectorXd& b) {
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower> direct(system.matrix);
  EXPECT_EQ(direct.info(), Eigen::Success);
  return direct.solve(b);
}

double RelativeResidual(const LinearSystem& system, const Eigen::VectorXd& x,
                        const Eigen::VectorXd& b) {
  return (system.matrix.selfadjointView<Eigen::Lower>() * x - b).norm() /
         b.norm();
}

TEST(BlockJacobiSolverTest, AgreesWithADirectSolveThroughTheInterface) {
  const LinearSystem system = KroneckerSystem(PlateMetric(0.1), 8);
  const Eigen::VectorXd b =
      Eigen::VectorXd::LinSpaced(system.matrix.rows(), -1, 2);
  const Eigen::VectorXd expected = DirectSolve(system, b);
  BlockJacobiSolver solver;
  solver.time_coupling = false;  // plain block Jacobi
  LinearSolver& interface = solver;
  Eigen::VectorXd x;
  ASSERT_TRUE(interface.Solve(system, b, 1e-12, &x));
  EXPECT_LT(RelativeResidual(system, x, b), 1e-12);
  EXPECT_LT((x - expected).norm(), 1e-9 * expected.norm());
  EXPECT_STREQ(interface.name(), "block-jacobi");
  EXPECT_EQ(interface.stats().factorizations, 1);
  EXPECT_EQ(interface.stats().time_coupled_factorizations, 0);
  EXPECT_EQ(interface.stats().cg_solves, 1);
  // T preconditioned by 2I: K - 1 = 7 distinct eigenvalues.
  EXPECT_GE(interface.stats().cg_iterations, 1);
  EXPECT_LE(interface.stats().cg_iterations, 10);
  EXPECT_EQ(interface.stats().cg_not_converged, 0);
  // Time-coupled with double-precision factors: the model's own inverse,
  // no CG iteration.
  BlockJacobiSolver coupled;
  coupled.single_precision_factors = false;
  Eigen::VectorXd y;
  ASSERT_TRUE(coupled.Solve(system, b, 1e-12, &y));
  EXPECT_LT((y - expected).norm(), 1e-9 * expected.norm());
  EXPECT_EQ(coupled.stats().time_coupled_factorizations, 1);
  EXPECT_EQ(coupled.stats().cg_iterations, 0);
  // The default, single-precision factors: the inverse to float round-off,
  // so CG needs one or two iterations to 1e-12 (and the same answer).
  BlockJacobiSolver single;
  ASSERT_TRUE(single.Solve(system, b, 1e-12, &y));
  EXPECT_LT(RelativeResidual(system, y, b), 1e-12);
  EXPECT_LT((y - expected).norm(), 1e-9 * expected.norm());
  EXPECT_GE(single.stats().cg_iterations, 1);
  EXPECT_LE(single.stats().cg_iterations, 2);
}

// Stale factors are kept while CG on them meets the budget; a matrix whose
// diagonal blocks changed so much that it does not gets fresh factors. The
// counts are the same in a repeated run.
TEST(BlockJacobiSolverTest, RefactorisesOnlyBeyondTheIterationBudget) {
  const SparseMatrix g = PlateMetric(0.1);
  const LinearSystem h0 = KroneckerSystem(g, 8);
  const LinearSystem near = KroneckerSystem(g, 8, 1.01);
  const LinearSystem far = KroneckerSystem(PlateMetric(100.0), 8);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(h0.matrix.rows(), 1, -1);
  std::vector<LinearSolverStats> runs;
  for (int run = 0; run < 2; ++run) {
    BlockJacobiSolver solver;
    solver.stale_iteration_budget = 12;
    Eigen::VectorXd x;
    ASSERT_TRUE(solver.Solve(h0, b, 1e-10, &x));
    EXPECT_EQ(solver.stats().factorizations, 1);
    ASSERT_TRUE(solver.Solve(near, b, 1e-10, &x));
    EXPECT_LT(RelativeResidual(near, x, b), 1e-10);
    EXPECT_EQ(solver.stats().factorizations, 1);  // the stale factors did
    // Another metric G' = L + 100 I: the stale M^-1 H = T/2 (x) G^-1 G' has
    // eigenvalues spread over (lambda + 100) / (lambda + 0.1) in [~1, 1000]
    // (a scaling alone would not matter to CG); it exceeds 12 iterations.
    ASSERT_TRUE(solver.Solve(far, b, 1e-10, &x));
    EXPECT_LT(RelativeResidual(far, x, b), 1e-10);
    EXPECT_EQ(solver.stats().factorizations, 2);
    EXPECT_EQ(solver.stats().cg_solves, 3);
    EXPECT_EQ(solver.stats().cg_not_converged, 0);
    runs.push_back(solver.stats());
  }
  EXPECT_EQ(runs[0].cg_iterations, runs[1].cg_iterations);
  // The negative twin of the budget: with a budget of 0 iterations every
  // solve refactorises.
  BlockJacobiSolver no_reuse;
  no_reuse.stale_iteration_budget = 0;
  Eigen::VectorXd x;
  ASSERT_TRUE(no_reuse.Solve(h0, b, 1e-10, &x));
  ASSERT_TRUE(no_reuse.Solve(near, b, 1e-10, &x));
  EXPECT_EQ(no_reuse.stats().factorizations, 2);
}

// ForgetFactors drops the factors but not the pattern analysis: the next
// solve factorises H afresh and answers exactly as a new solver does (same
// ordering and supernodes, same bits). Its twin: without ForgetFactors the
// stale factors of H0 precondition, and the answer differs in its last bits.
TEST(BlockJacobiSolverTest, ForgottenFactorsAreRefactorisedAsByANewSolver) {
  const SparseMatrix g = PlateMetric(0.1);
  const LinearSystem h0 = KroneckerSystem(g, 8);
  const LinearSystem near = KroneckerSystem(g, 8, 1.01);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(h0.matrix.rows(), 1, -1);
  BlockJacobiSolver fresh;
  Eigen::VectorXd expected;
  ASSERT_TRUE(fresh.Solve(near, b, 1e-10, &expected));
  const auto second_solve = [&](bool forget, int* factorizations) {
    BlockJacobiSolver solver;
    Eigen::VectorXd x;
    EXPECT_TRUE(solver.Solve(h0, b, 1e-10, &x));
    if (forget) solver.ForgetFactors();
    EXPECT_TRUE(solver.Solve(near, b, 1e-10, &x));
    *factorizations = solver.stats().factorizations;
    return x;
  };
  int factorizations = 0;
  const Eigen::VectorXd forgotten = second_solve(true, &factorizations);
  EXPECT_EQ(factorizations, 2);
  EXPECT_EQ((forgotten - expected).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::VectorXd stale = second_solve(false, &factorizations);
  EXPECT_EQ(factorizations, 1);
  EXPECT_LT(RelativeResidual(near, stale, b), 1e-10);
  EXPECT_GT((stale - expected).cwiseAbs().maxCoeff(), 0.0);
}

TEST(BlockJacobiSolverTest, NotPositiveDefiniteAndBadBlocksAreFailures) {
  const LinearSystem system = KroneckerSystem(PlateMetric(0.1), 8);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(system.matrix.rows());
  Eigen::VectorXd x;
  // A negative definite matrix: its diagonal blocks are not SPD.
  LinearSystem negative = system;
  negative.matrix = -system.matrix;
  BlockJacobiSolver solver;
  EXPECT_FALSE(solver.Solve(negative, b, 1e-8, &x));
  // SPD diagonal blocks (1 x 1, value 1) but an indefinite H = [1 2; 2 1]
  // (eigenvalues 3, -1): CG meets d^T H d < 0 in its second iteration.
  LinearSystem indefinite;
  indefinite.matrix.resize(2, 2);
  indefinite.matrix.insert(0, 0) = 1;
  indefinite.matrix.insert(1, 0) = 2;
  indefinite.matrix.insert(1, 1) = 1;
  indefinite.block_offsets = {0, 1, 2};
  BlockJacobiSolver curvature;
  EXPECT_FALSE(curvature.Solve(indefinite, Eigen::Vector2d(1, 0), 1e-12, &x));
  EXPECT_EQ(curvature.stats().factorizations, 1);
  // Its SPD twin H = [2 1; 1 2] is solved.
  LinearSystem spd = indefinite;
  spd.matrix.coeffRef(0, 0) = 2;
  spd.matrix.coeffRef(1, 0) = 1;
  spd.matrix.coeffRef(1, 1) = 2;
  ASSERT_TRUE(curvature.Solve(spd, Eigen::Vector2d(1, 0), 1e-12, &x));
  EXPECT_NEAR(x(0), 2.0 / 3, 1e-12);
  EXPECT_NEAR(x(1), -1.0 / 3, 1e-12);
  // Offsets that do not partition H.
  LinearSystem unpartitioned = system;
  unpartitioned.block_offsets.pop_back();
  EXPECT_FALSE(BlockJacobiSolver().Solve(unpartitioned, b, 1e-8, &x));
  unpartitioned.block_offsets.clear();
  EXPECT_FALSE(BlockJacobiSolver().Solve(unpartitioned, b, 1e-8, &x));
}

}  // namespace
}  // namespace shellspace
