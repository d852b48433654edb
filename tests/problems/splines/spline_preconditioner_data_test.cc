// SplinePreconditioner: T^T is the adjoint of T, and on a constant path
// (one metric for all shapes) T^T (A (x) (G + alpha I)) T is the identity.
#include "shellspace/problems/splines/spline_preconditioner.h"

#include <gtest/gtest.h>

#include <random>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

Eigen::VectorXd Random(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = u(rng);
  return v;
}

SplineSpec RegressionSpec(const Positions& shape, int steps) {
  SplineSpec spec;
  spec.steps = steps;
  spec.sigma = 0.3;
  spec.initial.assign(steps + 1, shape);
  spec.is_free.assign(steps + 1, 1);
  spec.data = {{shape, 0}, {shape, 2}, {shape, steps}};
  return spec;
}

TEST(SplinePreconditionerTest, TransposeIsTheAdjoint) {
  const auto [a, b, space] =
      testing::LoadPair("plate/plate121.ply", "plate/plate121_rolledA.ply");
  SplineSpec spec;  // a spline with different free shapes
  spec.steps = 4;
  spec.initial = {a.positions, a.positions, 0.5 * (a.positions + b.positions),
                  b.positions, b.positions};
  spec.is_free = {0, 1, 1, 1, 0};
  const SplinePreconditioner t(space, spec);
  const int n = t.num_parameters();
  ASSERT_EQ(n, 3 * 3 * a.num_vertices());
  const Eigen::VectorXd y = Random(n, 1), g = Random(n, 2);
  Eigen::VectorXd ty(n), tg(n);
  t.Apply(y.data(), ty.data());
  t.ApplyTransposed(g.data(), tg.data());
  EXPECT_NEAR(ty.dot(g), y.dot(tg), 1e-10 * std::abs(ty.dot(g)));
}

TEST(SplinePreconditionerTest, ModelHessianBecomesTheIdentity) {
  const Mesh a = testing::LoadData("plate/plate121.ply");
  const ShellSpace space = testing::MakeSpace(a);
  const int K = 5;
  const SplineSpec spec = RegressionSpec(a.positions, K);
  const double regularization = 1e-6;
  const SplinePreconditioner t(space, spec, regularization);
  // A = E + sigma K^3 D^T D (+ ridge) over all K + 1 shapes.
  const Eigen::MatrixXd& a_time = t.time_matrix();
  ASSERT_EQ(a_time.rows(), K + 1);
  const double w = 0.3 * K * K * K;
  EXPECT_NEAR(a_time(0, 0), 1 + w, 1e-5 * w);  // + a 1e-6 relative ridge
  EXPECT_NEAR(a_time(0, 1), -2 * w, 1e-12 * w);
  EXPECT_NEAR(a_time(1, 3), w, 1e-12 * w);
  EXPECT_EQ(a_time(0, 3), 0.0);
  SparseMatrix g = EnergyHessian(space, a.positions, a.positions,
                                 ShellSide::kDeformed, ShellSide::kDeformed);
  SparseMatrix identity(g.rows(), g.rows());
  identity.setIdentity();
  g += regularization * g.diagonal().mean() * identity;
  const int n = t.num_parameters(), block = static_cast<int>(g.rows());
  const Eigen::VectorXd y = Random(n, 3);
  Eigen::VectorXd x(n), hx = Eigen::VectorXd::Zero(n), back(n);
  t.Apply(y.data(), x.data());
  for (int i = 0; i <= K; ++i) {
    for (int j = 0; j <= K; ++j) {
      hx.segment(i * block, block) +=
          a_time(i, j) * (g * x.segment(j * block, block));
    }
  }
  t.ApplyTransposed(hx.data(), back.data());
  EXPECT_LT((back - y).norm(), 1e-6 * y.norm());
}

}  // namespace
}  // namespace shellspace
