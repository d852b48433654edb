// The linear solvers of the Newton engine against dense solves: SparseLu
// (UMFPACK) on a non-symmetric system, ReusableCholesky (CHOLMOD + CG on a
// reused factor) on SPD systems, both through the LinearSolver interface;
// and the deterministic CG budget (identical iteration counts and digits
// for repeated solves).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "shellspace/solvers/linear_solver.h"
#include "shellspace/solvers/reusable_cholesky.h"
#include "shellspace/solvers/sparse_lu.h"

namespace shellspace {
namespace {

// A random sparse n x n matrix: `diagonal` on the diagonal plus about
// `per_row` entries in [-1, 1] per row.
Eigen::MatrixXd RandomSparseDense(int n, int per_row, double diagonal,
                                  unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1, 1);
  std::uniform_int_distribution<int> column(0, n - 1);
  Eigen::MatrixXd a = diagonal * Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < per_row; ++k) a(i, column(rng)) += value(rng);
  }
  return a;
}

// An SPD system of n unknowns on n / 3 "vertices" (3 per vertex): B^T B +
// shift I of a random sparse B.
LinearSystem SpdSystem(int n, double shift, unsigned seed) {
  const Eigen::MatrixXd b = RandomSparseDense(n, 3, 1.0, seed);
  Eigen::MatrixXd h = b.transpose() * b;
  h.diagonal().array() += shift;
  LinearSystem system;
  system.matrix = Eigen::MatrixXd(h.triangularView<Eigen::Lower>()).sparseView();
  system.num_vertices = n / 3;
  for (int i = 0; i < n; ++i) system.vertex_of.push_back(i / 3);
  return system;
}

Eigen::MatrixXd FullSymmetric(const LinearSystem& s) {
  const Eigen::MatrixXd lower = Eigen::MatrixXd(s.matrix);
  Eigen::MatrixXd full = lower + lower.transpose();
  full.diagonal() = lower.diagonal();
  return full;
}

TEST(SparseLuTest, AgreesWithADenseLuSolve) {
  const int n = 40;
  const Eigen::MatrixXd a = RandomSparseDense(n, 4, 3.0, 7);
  ASSERT_GT((a - a.transpose()).norm(), 1.0);  // really non-symmetric
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -2.0, 1.0);
  LinearSystem system;
  system.matrix = a.sparseView();
  SparseLu lu;
  LinearSolver& solver = lu;
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.Solve(system, b, 0.5, &x));  // the tolerance is ignored
  const Eigen::VectorXd dense = a.partialPivLu().solve(b);
  EXPECT_LT((x - dense).norm(), 1e-12 * dense.norm());
  EXPECT_EQ(solver.stats().factorizations, 1);
}

TEST(SparseLuTest, SingularMatrixIsReported) {
  Eigen::MatrixXd a = RandomSparseDense(10, 3, 3.0, 3);
  a.row(4).setZero();
  LinearSystem system;
  system.matrix = a.sparseView();
  SparseLu lu;
  Eigen::VectorXd x;
  EXPECT_FALSE(lu.Solve(system, Eigen::VectorXd::Ones(10), 0, &x));
}

TEST(ReusableCholeskyTest, AgreesWithDenseSolvesThroughTheInterface) {
  const int n = 60;
  const LinearSystem h1 = SpdSystem(n, 1.0, 11);
  // A nearby matrix: CG on the factor of h1.
  LinearSystem h2 = h1;
  h2.matrix.diagonal().array() += 0.05;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, -1.0);
  ReusableCholesky cholesky;
  LinearSolver& solver = cholesky;
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.Solve(h1, b, 1e-12, &x));
  const Eigen::VectorXd dense1 = FullSymmetric(h1).llt().solve(b);
  EXPECT_LT((x - dense1).norm(), 1e-10 * dense1.norm());
  EXPECT_EQ(solver.stats().factorizations, 1);
  ASSERT_TRUE(solver.Solve(h2, b, 1e-6, &x));
  const Eigen::MatrixXd full2 = FullSymmetric(h2);
  EXPECT_LE((full2 * x - b).norm(), 1e-6 * b.norm());
  const Eigen::VectorXd dense2 = full2.llt().solve(b);
  const double condition = 1 / full2.llt().matrixL().toDenseMatrix()
                                   .diagonal().array().square().minCoeff() *
                           full2.norm();
  EXPECT_LT((x - dense2).norm(), 1e-6 * condition * dense2.norm());
  EXPECT_EQ(solver.stats().factorizations, 1);
  EXPECT_EQ(solver.stats().cg_solves, 1);
  EXPECT_GT(solver.stats().cg_iterations, 0);
}

// The CG budget is a flop estimate (no timing): CG stops once it has cost
// as much as the last factorisation, here after a fixed number of
// iterations, the same in every run.
TEST(ReusableCholeskyTest, CgBudgetIsDeterministic) {
  const int n = 300;
  const LinearSystem h1 = SpdSystem(n, 0.5, 5);
  // Unrelated to h1: CG preconditioned by h1's factor needs many iterations.
  const LinearSystem far = SpdSystem(n, 0.5, 6);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  std::vector<int> iterations;
  std::vector<Eigen::VectorXd> solutions;
  for (int run = 0; run < 3; ++run) {
    ReusableCholesky solver;
    solver.max_cg_iterations = 1000;  // only the flop budget limits CG
    Eigen::VectorXd x;
    ASSERT_TRUE(solver.Solve(h1, b, 1e-14, &x));
    ASSERT_TRUE(solver.Solve(far, b, 1e-14, &x));
    iterations.push_back(solver.stats().cg_iterations);
    solutions.push_back(x);
    // The budget ran out: a second factorisation, exact solve.
    EXPECT_EQ(solver.stats().factorizations, 2);
    EXPECT_LT((FullSymmetric(far) * x - b).norm(), 1e-10 * b.norm());
  }
  EXPECT_GT(iterations[0], 0);
  EXPECT_LT(iterations[0], 1000);
  EXPECT_EQ(iterations[1], iterations[0]);
  EXPECT_EQ(iterations[2], iterations[0]);
  EXPECT_EQ(solutions[1], solutions[0]);  // bit for bit
  EXPECT_EQ(solutions[2], solutions[0]);
}

}  // namespace
}  // namespace shellspace
