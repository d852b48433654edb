// Tests of the parts of the LΘA spline (docs/math.md, "Riemannian
// splines") on elements and data made here: the analytic Jacobians of its
// three residuals and the cubic splines in time (the per-frame
// reconstruction on the shared plate: ltheta_spline_data_test.cc).
#include "shellspace/problems/splines/ltheta_spline.h"

#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "shellspace/cost_functions/ltheta_cost_functions.h"
#include "shellspace/geometry/element_geometry.h"
#include "shellspace/problems/splines/cubic_spline.h"

namespace shellspace {
namespace {

// ---------------------------------------------------------------------------
// Cost functions: analytic Jacobians against central differences.

// Random vertex positions (fixed seed) in [-1, 1]^3.
std::vector<Eigen::Vector3d> RandomPoints(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Eigen::Vector3d> points(n);
  for (auto& p : points) p = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
  return points;
}

// A well-shaped random edge flap (i, j, k, l) (fixed seed): the flat flap
// i = (0,0,0), j = (1,0,0), k = (0.5,0.8,0), l = (0.5,-0.8,0) with every
// coordinate perturbed by up to 0.3, so |theta| ranges over about [0, 1.5].
std::vector<Eigen::Vector3d> RandomFlap(unsigned seed) {
  std::vector<Eigen::Vector3d> flap = {
      {0, 0, 0}, {1, 0, 0}, {0.5, 0.8, 0}, {0.5, -0.8, 0}};
  const auto noise = RandomPoints(4, seed);
  for (int v = 0; v < 4; ++v) flap[v] += 0.3 * noise[v];
  return flap;
}

// Probes `cost` at `points` with ceres::GradientChecker (central
// differences); returns whether the Jacobians agree to `precision`.
bool JacobiansAgree(const ceres::CostFunction& cost,
                    const std::vector<Eigen::Vector3d>& points,
                    double precision, std::string* error = nullptr) {
  // The checker differentiates with Ridders' extrapolation; its default first
  // step (1e-2 relative) is too coarse for the curvature of small flaps.
  ceres::NumericDiffOptions options;
  options.ridders_relative_initial_step_size = 1e-4;
  const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
  ceres::GradientChecker checker(&cost, no_manifolds, options);
  std::vector<const double*> parameters;
  for (const auto& p : points) parameters.push_back(p.data());
  ceres::GradientChecker::ProbeResults results;
  const bool ok = checker.Probe(parameters.data(), precision, &results);
  if (error != nullptr) *error = results.error_log;
  return ok;
}

TEST(LThetaCostFunctionTest, EdgeLengthJacobianMatchesCentralDifferences) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const auto x = RandomPoints(2, seed);
    std::unique_ptr<ceres::CostFunction> cost(
        EdgeLengthCostFunction::Create(0.7, 1.3));
    std::string error;
    EXPECT_TRUE(JacobiansAgree(*cost, x, 1e-7, &error)) << error;
    double r;
    const double* params[2] = {x[0].data(), x[1].data()};
    ASSERT_TRUE(cost->Evaluate(params, &r, nullptr));
    EXPECT_NEAR(r, 1.3 * ((x[1] - x[0]).norm() - 0.7), 1e-15);
  }
}

TEST(LThetaCostFunctionTest, TriangleAreaJacobianMatchesCentralDifferences) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const auto x = RandomPoints(3, 100 + seed);
    std::unique_ptr<ceres::CostFunction> cost(
        TriangleAreaCostFunction::Create(0.2, 2.0));
    std::string error;
    EXPECT_TRUE(JacobiansAgree(*cost, x, 1e-7, &error)) << error;
    double r;
    const double* params[3] = {x[0].data(), x[1].data(), x[2].data()};
    ASSERT_TRUE(cost->Evaluate(params, &r, nullptr));
    const double area = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
    EXPECT_NEAR(r, 2.0 * (area - 0.2), 1e-14);
  }
}

TEST(LThetaCostFunctionTest, DihedralJacobianMatchesCentralDifferences) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const auto x = RandomFlap(200 + seed);
    std::unique_ptr<ceres::CostFunction> cost(
        DihedralAngleCostFunction::Create(0.3, 0.8));
    std::string error;
    EXPECT_TRUE(JacobiansAgree(*cost, x, 1e-6, &error)) << error;
  }
}

TEST(LThetaCostFunctionTest, DihedralResidualOfAFoldedFlap) {
  // Flap i = (0,0,0), j = (1,0,0), k = (0.5,1,0) in the plane, l = the
  // mirror of (0.5,-1,0) rotated about the edge by alpha: theta = +-alpha.
  const double alpha = 0.4;
  const Eigen::Vector3d xi(0, 0, 0), xj(1, 0, 0), xk(0.5, 1, 0);
  const Eigen::Vector3d xl(0.5, -std::cos(alpha), std::sin(alpha));
  const DihedralAngle<double> flap(xi, xj, xk, xl);
  EXPECT_NEAR(std::abs(flap.theta), alpha, 1e-14);
  std::unique_ptr<ceres::CostFunction> cost(
      DihedralAngleCostFunction::Create(flap.theta, 2.0));
  const double* params[4] = {xi.data(), xj.data(), xk.data(), xl.data()};
  double r;
  ASSERT_TRUE(cost->Evaluate(params, &r, nullptr));
  EXPECT_NEAR(r, 0.0, 1e-15);
  // A target differing by 2 pi is the same angle (wrapped difference).
  std::unique_ptr<ceres::CostFunction> shifted(
      DihedralAngleCostFunction::Create(flap.theta + 2 * M_PI + 0.1, 2.0));
  ASSERT_TRUE(shifted->Evaluate(params, &r, nullptr));
  EXPECT_NEAR(r, -0.2, 1e-12);
}

TEST(LThetaCostFunctionTest, DegenerateElementsAreRejected) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(2, 0, 0), d(0, 1, 0);
  double r;
  std::unique_ptr<ceres::CostFunction> edge(
      EdgeLengthCostFunction::Create(1, 1));
  const double* e_params[2] = {a.data(), a.data()};
  EXPECT_FALSE(edge->Evaluate(e_params, &r, nullptr));
  std::unique_ptr<ceres::CostFunction> area(
      TriangleAreaCostFunction::Create(1, 1));
  const double* t_params[3] = {a.data(), b.data(), c.data()};  // collinear
  EXPECT_FALSE(area->Evaluate(t_params, &r, nullptr));
  std::unique_ptr<ceres::CostFunction> dihedral(
      DihedralAngleCostFunction::Create(0, 1));
  const double* f_params[4] = {a.data(), b.data(), c.data(), d.data()};
  double j_storage[4][3];
  double* jacobians[4] = {j_storage[0], j_storage[1], j_storage[2],
                          j_storage[3]};
  EXPECT_FALSE(dihedral->Evaluate(f_params, &r, jacobians));
}

// A dihedral cost function whose Jacobian w.r.t. X_k is wrong by 5%: the
// gradient checker must reject it (the checks above can fail).
class WrongDihedralCostFunction
    : public ceres::SizedCostFunction<1, 3, 3, 3, 3> {
 public:
  WrongDihedralCostFunction()
      : inner_(DihedralAngleCostFunction::Create(0.3, 0.8)) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    if (!inner_->Evaluate(parameters, residuals, jacobians)) return false;
    if (jacobians != nullptr && jacobians[2] != nullptr) {
      for (int c = 0; c < 3; ++c) jacobians[2][c] *= 1.05;
    }
    return true;
  }

 private:
  std::unique_ptr<ceres::CostFunction> inner_;
};

// An edge cost function that forgets the normalisation of the direction.
class WrongEdgeCostFunction : public ceres::SizedCostFunction<1, 3, 3> {
 public:
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Eigen::Vector3d e = Eigen::Map<const Eigen::Vector3d>(parameters[1]) -
                              Eigen::Map<const Eigen::Vector3d>(parameters[0]);
    residuals[0] = e.norm() - 0.5;
    if (jacobians != nullptr) {
      for (int b = 0; b < 2; ++b) {
        if (jacobians[b] == nullptr) continue;
        for (int c = 0; c < 3; ++c) jacobians[b][c] = (b == 0 ? -e : e)(c);
      }
    }
    return true;
  }
};

TEST(LThetaCostFunctionTest, GradientCheckerCatchesWrongJacobians) {
  const auto x4 = RandomFlap(7);
  WrongDihedralCostFunction wrong_dihedral;
  EXPECT_FALSE(JacobiansAgree(wrong_dihedral, x4, 1e-6));
  const auto x2 = RandomPoints(2, 8);
  WrongEdgeCostFunction wrong_edge;
  EXPECT_FALSE(JacobiansAgree(wrong_edge, x2, 1e-7));
}

// ---------------------------------------------------------------------------
// Cubic splines.

TEST(CubicSplineTest, NaturalSplinePassesThroughKnots) {
  const std::vector<double> knots = {0, 1, 3, 4, 7};
  Eigen::MatrixXd values(5, 2);
  values << 1, -2, 3, 0.5, -1, 4, 2, 2, 0, -3;
  const Eigen::MatrixXd at_knots =
      InterpolateCubicSpline(knots, values, knots, SplineEnds::kNatural);
  EXPECT_LT((at_knots - values).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(CubicSplineTest, NaturalSplineReproducesLinearDataAndExtrapolates) {
  const std::vector<double> knots = {0, 2, 3, 6};
  Eigen::MatrixXd values(4, 1);
  for (int j = 0; j < 4; ++j) values(j, 0) = 2.5 * knots[j] - 1;
  std::vector<double> times;
  for (double t = -2; t <= 8; t += 0.25) times.push_back(t);
  const Eigen::MatrixXd s =
      InterpolateCubicSpline(knots, values, times, SplineEnds::kNatural);
  for (size_t r = 0; r < times.size(); ++r) {
    EXPECT_NEAR(s(r, 0), 2.5 * times[r] - 1, 1e-13) << "t = " << times[r];
  }
}

TEST(CubicSplineTest, NaturalSplineMatchesClosedForm) {
  // Knots 0, 1, 2 with values 0, 1, 0: M_1 = -3 and on [0, 1]
  // S(t) = -t^3/2 + 3t/2 (symmetric about t = 1); linear with slope -3/2
  // beyond t = 2.
  const Eigen::MatrixXd values = (Eigen::MatrixXd(3, 1) << 0, 1, 0).finished();
  const std::vector<double> times = {0.25, 0.5, 1.5, 1.75, 3.0};
  const Eigen::MatrixXd s =
      InterpolateCubicSpline({0, 1, 2}, values, times, SplineEnds::kNatural);
  auto closed = [](double t) { return -0.5 * t * t * t + 1.5 * t; };
  EXPECT_NEAR(s(0, 0), closed(0.25), 1e-15);
  EXPECT_NEAR(s(1, 0), 0.6875, 1e-15);
  EXPECT_NEAR(s(2, 0), closed(0.5), 1e-15);
  EXPECT_NEAR(s(3, 0), closed(0.25), 1e-15);
  EXPECT_NEAR(s(4, 0), -1.5, 1e-15);
}

TEST(CubicSplineTest, NaturalSplineHasZeroEndCurvatureAndIsC2) {
  const std::vector<double> knots = {0, 1, 2, 4, 5};
  Eigen::MatrixXd values(5, 1);
  values << 0, 2, -1, 3, 1;
  const double d = 1e-3;
  auto s = [&](double t) {
    return InterpolateCubicSpline(knots, values, {t}, SplineEnds::kNatural)(0,
                                                                            0);
  };
  auto second = [&](double t) {
    return (s(t + d) - 2 * s(t) + s(t - d)) / (d * d);
  };
  EXPECT_NEAR(second(d), 0.0, 1e-2);
  EXPECT_NEAR(second(5 - d), 0.0, 1e-2);
  for (double t : {1.0, 2.0, 4.0}) {
    EXPECT_NEAR(second(t - 2 * d), second(t + 2 * d), 5e-2) << t;
    const double left = (s(t) - s(t - d)) / d, right = (s(t + d) - s(t)) / d;
    EXPECT_NEAR(left, right, 1e-2) << t;
  }
}

TEST(CubicSplineTest, PeriodicSplineReproducesSinSamples) {
  const int period = 8;
  std::vector<double> knots, times;
  Eigen::MatrixXd values(period, 2);
  for (int j = 0; j < period; ++j) {
    knots.push_back(j);
    values(j, 0) = std::sin(2 * M_PI * j / period);
    values(j, 1) = std::cos(2 * M_PI * j / period) + 3;
  }
  for (double t = -4; t <= 12; t += 0.125) times.push_back(t);
  const Eigen::MatrixXd s = InterpolateCubicSpline(
      knots, values, times, SplineEnds::kPeriodic, period);
  for (size_t r = 0; r < times.size(); ++r) {
    const double phase = 2 * M_PI * times[r] / period;
    // Interpolation error (5/384) h^4 max|f''''| = 0.005 for h = 1.
    EXPECT_NEAR(s(r, 0), std::sin(phase), 5e-3) << times[r];
    EXPECT_NEAR(s(r, 1), std::cos(phase) + 3, 5e-3) << times[r];
  }
  // Halving h shrinks the error ~16x (fourth-order accuracy).
  std::vector<double> fine_knots;
  Eigen::MatrixXd fine_values(2 * period, 1);
  for (int j = 0; j < 2 * period; ++j) {
    fine_knots.push_back(0.5 * j);
    fine_values(j, 0) = std::sin(2 * M_PI * 0.5 * j / period);
  }
  const Eigen::MatrixXd fine = InterpolateCubicSpline(
      fine_knots, fine_values, times, SplineEnds::kPeriodic, period);
  double coarse_error = 0, fine_error = 0;
  for (size_t r = 0; r < times.size(); ++r) {
    const double exact = std::sin(2 * M_PI * times[r] / period);
    coarse_error = std::max(coarse_error, std::abs(s(r, 0) - exact));
    fine_error = std::max(fine_error, std::abs(fine(r, 0) - exact));
  }
  EXPECT_LT(fine_error, coarse_error / 10);
}

TEST(CubicSplineTest, PeriodicSplineThroughUnevenKnotsIsPeriodicAndC2) {
  const std::vector<double> knots = {1, 2, 5};
  Eigen::MatrixXd values(3, 1);
  values << 0.5, -1, 2;
  const double period = 6, d = 1e-3;
  auto s = [&](double t) {
    return InterpolateCubicSpline(knots, values, {t}, SplineEnds::kPeriodic,
                                  period)(0, 0);
  };
  for (size_t j = 0; j < knots.size(); ++j) {
    EXPECT_NEAR(s(knots[j]), values(j, 0), 1e-14);
    EXPECT_NEAR(s(knots[j] + period), values(j, 0), 1e-13);
  }
  // Smooth across the wrap (t = 7 = 1 + period) and the other knots.
  for (double t : {1.0, 2.0, 5.0, 7.0}) {
    const double left = (s(t) - s(t - d)) / d, right = (s(t + d) - s(t)) / d;
    EXPECT_NEAR(left, right, 1e-2) << t;
    const double second_left = (s(t) - 2 * s(t - d) + s(t - 2 * d)) / (d * d);
    const double second_right = (s(t + 2 * d) - 2 * s(t + d) + s(t)) / (d * d);
    EXPECT_NEAR(second_left, second_right, 5e-2) << t;
  }
  // Two knots: still well defined and through both.
  const Eigen::MatrixXd two =
      InterpolateCubicSpline({0, 3}, (Eigen::MatrixXd(2, 1) << 1, 2).finished(),
                             {0, 3, 6}, SplineEnds::kPeriodic, 6);
  EXPECT_NEAR(two(0, 0), 1, 1e-14);
  EXPECT_NEAR(two(1, 0), 2, 1e-14);
  EXPECT_NEAR(two(2, 0), 1, 1e-14);
}

TEST(CubicSplineTest, AtStepsAndInputErrors) {
  Eigen::MatrixXd values(3, 1);
  values << 1, 5, 3;
  const Eigen::MatrixXd natural =
      InterpolateCubicSplineAtSteps({0, 2, 4}, values, 4, SplineEnds::kNatural);
  ASSERT_EQ(natural.rows(), 5);
  EXPECT_NEAR(natural(0, 0), 1, 1e-14);
  EXPECT_NEAR(natural(2, 0), 5, 1e-14);
  EXPECT_NEAR(natural(4, 0), 3, 1e-14);
  const Eigen::MatrixXd periodic = InterpolateCubicSplineAtSteps(
      {0, 2, 4}, values, 6, SplineEnds::kPeriodic);
  ASSERT_EQ(periodic.rows(), 7);
  EXPECT_NEAR(periodic(6, 0), periodic(0, 0), 1e-14);
  EXPECT_THROW(InterpolateCubicSpline({0, 0}, Eigen::MatrixXd::Zero(2, 1), {},
                                      SplineEnds::kNatural),
               InputError);
  EXPECT_THROW(InterpolateCubicSplineAtSteps({0, 6}, values.topRows(2), 6,
                                             SplineEnds::kPeriodic),
               InputError);
  EXPECT_THROW(
      InterpolateCubicSpline({0, 1}, values, {0.5}, SplineEnds::kNatural),
      InputError);
}

}  // namespace
}  // namespace shellspace
