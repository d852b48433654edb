// Steihaug-Toint CG (solvers/steihaug_cg.h) against closed forms: the
// Newton step inside the region, the boundary step and the Cauchy decrease,
// negative curvature, the preconditioner's norm.
#include "shellspace/solvers/steihaug_cg.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace shellspace {
namespace {

// M = diag(d) (identity for d = 1).
class DiagonalPreconditioner : public Preconditioner {
 public:
  explicit DiagonalPreconditioner(Eigen::VectorXd d) : d_(std::move(d)) {}
  bool Factorize(const LinearSystem&) override { return true; }
  Eigen::VectorXd Apply(const Eigen::VectorXd& r) const override {
    return r.cwiseQuotient(d_);
  }

 private:
  Eigen::VectorXd d_;
};

Eigen::SparseMatrix<double> Lower(const Eigen::MatrixXd& h) {
  return Eigen::MatrixXd(h.triangularView<Eigen::Lower>()).sparseView();
}

// An SPD tridiagonal matrix (a 1-D Laplacian plus identity).
Eigen::MatrixXd Spd(int n) {
  Eigen::MatrixXd h = 3 * Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i + 1 < n; ++i) h(i, i + 1) = h(i + 1, i) = -1;
  return h;
}

double Model(const Eigen::MatrixXd& h, const Eigen::VectorXd& g,
             const Eigen::VectorXd& p) {
  return g.dot(p) + 0.5 * p.dot(h * p);
}

TEST(SteihaugCgTest, InsideTheRegionItIsTheNewtonStep) {
  const int n = 12;
  const Eigen::MatrixXd h = Spd(n);
  Eigen::VectorXd g(n);
  for (int i = 0; i < n; ++i) g[i] = std::cos(0.7 * i);
  const DiagonalPreconditioner jacobi(h.diagonal());
  const SteihaugResult r =
      SolveSteihaugCg(Lower(h), g, jacobi,
                      std::numeric_limits<double>::infinity(), 1e-12, 100);
  const Eigen::VectorXd newton = -h.ldlt().solve(g);
  EXPECT_EQ(r.stop, SteihaugResult::Stop::kConverged);
  EXPECT_LT((r.step - newton).norm(), 1e-10 * newton.norm());
  EXPECT_NEAR(r.model_decrease, -Model(h, g, r.step), 1e-12);
  EXPECT_NEAR(r.step_norm,
              std::sqrt(r.step.dot(h.diagonal().cwiseProduct(r.step))),
              1e-12);
  EXPECT_LE(r.iterations, n);
}

// A radius below |p_N|_M: the step lies on the boundary (in M's norm) and
// decreases the model at least as much as the Cauchy point (the model's
// minimiser along -g within the region, M = I here).
TEST(SteihaugCgTest, ABoundaryStepBeatsTheCauchyPoint) {
  const int n = 12;
  const Eigen::MatrixXd h = Spd(n);
  Eigen::VectorXd g(n);
  for (int i = 0; i < n; ++i) g[i] = 1.0 + 0.1 * i;
  const DiagonalPreconditioner identity(Eigen::VectorXd::Ones(n));
  const double newton_norm = h.ldlt().solve(g).norm();
  const double radius = 0.3 * newton_norm;
  const SteihaugResult r =
      SolveSteihaugCg(Lower(h), g, identity, radius, 1e-12, 100);
  EXPECT_EQ(r.stop, SteihaugResult::Stop::kBoundary);
  EXPECT_NEAR(r.step.norm(), radius, 1e-12 * radius);
  const double curvature = g.dot(h * g);
  const double tau = std::min(g.squaredNorm() / curvature, radius / g.norm());
  const double cauchy = -Model(h, g, -tau * g);
  EXPECT_GE(r.model_decrease, cauchy * (1 - 1e-12));
  EXPECT_NEAR(r.model_decrease, -Model(h, g, r.step), 1e-12);
}

// H = diag(1, -1), g = (1, 1): the first CG direction -g has zero
// curvature, so the step goes along it to the boundary:
// p = -radius g / |g|, -m(p) = radius sqrt(2) (the quadratic term is 0).
TEST(SteihaugCgTest, NegativeCurvatureGoesToTheBoundary) {
  Eigen::MatrixXd h(2, 2);
  h << 1, 0, 0, -1;
  const Eigen::Vector2d g(1, 1);
  const DiagonalPreconditioner identity(Eigen::VectorXd::Ones(2));
  const double radius = 0.5;
  const SteihaugResult r = SolveSteihaugCg(Lower(h), g, identity, radius,
                                           1e-12, 10);
  EXPECT_EQ(r.stop, SteihaugResult::Stop::kNegativeCurvature);
  EXPECT_LT((r.step + radius * g / g.norm()).norm(), 1e-14);
  EXPECT_NEAR(r.model_decrease, radius * std::sqrt(2.0), 1e-14);
  // Without a region: the preconditioned steepest-descent step -M^-1 g.
  const SteihaugResult free = SolveSteihaugCg(
      Lower(h), g, identity, std::numeric_limits<double>::infinity(), 1e-12,
      10);
  EXPECT_EQ(free.stop, SteihaugResult::Stop::kNegativeCurvature);
  EXPECT_LT((free.step + g).norm(), 1e-15);
}

// The same iteration cap and tolerance give the same digits every time.
TEST(SteihaugCgTest, DeterministicAndCapped) {
  const int n = 40;
  const Eigen::MatrixXd h = Spd(n);
  const Eigen::VectorXd g = Eigen::VectorXd::LinSpaced(n, -1, 2);
  const DiagonalPreconditioner identity(Eigen::VectorXd::Ones(n));
  const SteihaugResult a = SolveSteihaugCg(
      Lower(h), g, identity, std::numeric_limits<double>::infinity(), 1e-14, 3);
  const SteihaugResult b = SolveSteihaugCg(
      Lower(h), g, identity, std::numeric_limits<double>::infinity(), 1e-14, 3);
  EXPECT_EQ(a.stop, SteihaugResult::Stop::kMaxIterations);
  EXPECT_EQ(a.iterations, 3);
  EXPECT_EQ(a.step, b.step);
  EXPECT_GT(a.model_decrease, 0);
}

}  // namespace
}  // namespace shellspace
