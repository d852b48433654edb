// Tests of the LΘA spline (docs/math.md, "Riemannian splines"): the analytic
// Jacobians of its three residuals, the cubic splines in time, and the
// per-frame reconstruction.
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
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/splines/cubic_spline.h"
#include "tests/testing/test_support.h"

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

// ---------------------------------------------------------------------------
// The LΘA spline.

class LThetaSplineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    plate_ = testing::LoadData("plate/plate121.ply");
    rolled_a_ = testing::LoadData("plate/plate121_rolledA.ply").positions;
    rolled_b_ = testing::LoadData("plate/plate121_rolledB.ply").positions;
    space_ = testing::MakeSpace(plate_);
  }

  static SolverSettings Tight() {
    SolverSettings settings = testing::TightSettings(1e-12);
    settings.num_threads = 1;
    return settings;
  }

  Mesh plate_;
  Positions rolled_a_, rolled_b_;
  ShellSpace space_;
};

// The frames are solved in parallel, each on one thread: 1 and 3 threads
// give the same path to the bit and the same LM iterations.
TEST_F(LThetaSplineTest, ThreadCountDoesNotChangeADigit) {
  const std::vector<Positions> keys = {plate_.positions, rolled_a_, rolled_b_};
  SolverSettings one = SolverSettings{}, three = SolverSettings{};
  one.num_threads = 1;
  three.num_threads = 3;
  LThetaSplineReport report_one, report_three;
  const ShellPath a =
      LThetaSpline(space_, keys, {0, 2, 5}, 6, false, one, &report_one);
  const ShellPath b =
      LThetaSpline(space_, keys, {0, 2, 5}, 6, false, three, &report_three);
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) EXPECT_TRUE(a[k] == b[k]) << k;
  EXPECT_EQ(report_one.lm_iterations(), report_three.lm_iterations());
  EXPECT_GT(report_one.lm_iterations(), 4);
}

TEST_F(LThetaSplineTest, PassesThroughItsKeyframes) {
  const std::vector<Positions> keys = {plate_.positions, rolled_a_, rolled_b_};
  LThetaSplineReport report;
  const ShellPath path = LThetaSpline(space_, keys, {0, 2, 5}, 6, false,
                                      SolverSettings{}, &report);
  ASSERT_EQ(path.size(), 7u);
  EXPECT_TRUE(path[0] == keys[0]);
  EXPECT_TRUE(path[2] == keys[1]);
  EXPECT_TRUE(path[5] == keys[2]);
  EXPECT_EQ(report.solved_frames, (std::vector<int>{1, 3, 4, 6}));
  int iterations = 0;  // Ceres' records, less each solve's iteration 0
  for (const auto& summary : report.summaries) {
    EXPECT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
    iterations += static_cast<int>(summary.iterations.size()) - 1;
  }
  EXPECT_GT(iterations, 4);
  EXPECT_EQ(report.lm_iterations(), iterations);
  EXPECT_TRUE(report.unconverged_frames().empty());
  // One LM iteration per frame: every solved frame is named unconverged.
  SolverSettings one_iteration;
  one_iteration.max_iterations = 1;
  LThetaSplineReport capped;
  LThetaSpline(space_, keys, {0, 2, 5}, 6, false, one_iteration, &capped);
  EXPECT_EQ(capped.unconverged_frames(), (std::vector<int>{1, 3, 4, 6}));
  EXPECT_EQ(capped.lm_iterations(), 4);
  // Inner frames are genuine shells between their neighbouring keyframes a,
  // b: a copy of neither, and nearer to one of them than they are apart.
  const std::vector<std::array<int, 3>> frames = {
      {1, 0, 1}, {3, 1, 2}, {4, 1, 2}};
  for (const auto& [k, a, b] : frames) {
    const double to_a = RelativeDistanceUpToRigidMotion(path[k], keys[a]);
    const double to_b = RelativeDistanceUpToRigidMotion(path[k], keys[b]);
    EXPECT_GT(std::min(to_a, to_b), 1e-2) << k;
    EXPECT_LT(std::min(to_a, to_b),
              RelativeDistanceUpToRigidMotion(keys[a], keys[b]))
        << k;
  }

  const ShellPath closed =
      LThetaSpline(space_, keys, {0, 2, 4}, 6, true, SolverSettings{});
  ASSERT_EQ(closed.size(), 7u);
  EXPECT_TRUE(closed[0] == keys[0]);
  EXPECT_TRUE(closed[2] == keys[1]);
  EXPECT_TRUE(closed[4] == keys[2]);
  EXPECT_TRUE(closed[6] == closed[0]);
}

TEST_F(LThetaSplineTest,
       UniformlyScaledFlatSheetKeepsSplineLengthsAndStaysFlat) {
  // Keyframes: the plate scaled by 1, 1.2, 1.44 at 0, 2, 4. Every length
  // follows the natural spline through (0, 1), (2, 1.2), (4, 1.44) times its
  // rest length (1.09625 at k = 1), every area the spline through the
  // squares (1.20185 at k = 1, not exactly 1.09625^2 = 1.20176): the frames
  // are a slight compromise between the two, in the plane of the sheet.
  const Positions& p = plate_.positions;
  const std::vector<Positions> keys = {p, 1.2 * p, 1.44 * p};
  const ShellPath path =
      LThetaSpline(space_, keys, {0, 2, 4}, 4, false, Tight());
  const Eigen::MatrixXd scales = InterpolateCubicSplineAtSteps(
      {0, 2, 4}, (Eigen::MatrixXd(3, 1) << 1, 1.2, 1.44).finished(), 4,
      SplineEnds::kNatural);
  EXPECT_NEAR(scales(1, 0), 1.09625, 1e-14);
  const LThetaQuantities rest = ComputeLThetaQuantities(space_, p);
  for (int k : {1, 3}) {
    const LThetaQuantities q = ComputeLThetaQuantities(space_, path[k]);
    const Eigen::ArrayXd ratio = q.lengths.array() / rest.lengths.array();
    EXPECT_NEAR(ratio.mean(), scales(k, 0), 1e-4) << k;
    EXPECT_LT((ratio - scales(k, 0)).abs().maxCoeff(), 2e-4) << k;
    // Flat: the plate lies in z = 0 and every frame stays in a plane.
    EXPECT_LT(path[k].col(2).cwiseAbs().maxCoeff(), 1e-12) << k;
    EXPECT_LT(q.dihedrals.cwiseAbs().maxCoeff(), 1e-12) << k;
  }
}

TEST_F(LThetaSplineTest, RigidMotionsOfAKeyframeGiveThatKeyframe) {
  // All keyframes are rigid motions of the rolled plate: every quantity's
  // spline is constant and each frame is the rolled plate up to rigid motion,
  // placed between its neighbours.
  const std::vector<Positions> keys = {
      rolled_a_, testing::RandomRigidMotion(rolled_a_, 3),
      testing::RandomRigidMotion(rolled_a_, 5)};
  for (bool periodic : {false, true}) {
    const ShellPath path =
        LThetaSpline(space_, keys, {0, 3, 5}, 7, periodic, Tight());
    for (int k = 0; k <= 7; ++k) {
      EXPECT_LT(RelativeDistanceUpToRigidMotion(path[k], rolled_a_), 1e-8)
          << "frame " << k << (periodic ? " periodic" : "");
    }
    // The rigid placement moves between the keyframes: frame 4 is neither
    // where keyframe 1 nor where keyframe 2 is.
    EXPECT_GT((path[4] - keys[1]).cwiseAbs().maxCoeff(), 1e-2);
    EXPECT_GT((path[4] - keys[2]).cwiseAbs().maxCoeff(), 1e-2);
  }
}

TEST_F(LThetaSplineTest, ReconstructingAShellsOwnQuantitiesGivesItBack) {
  const LThetaQuantities own = ComputeLThetaQuantities(space_, rolled_a_);
  const LThetaWeights weights = LThetaResidualWeights(space_, plate_.positions);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> noise(-0.02, 0.02);
  Positions perturbed = rolled_a_;
  for (int i = 0; i < perturbed.size(); ++i) perturbed.data()[i] += noise(rng);
  ASSERT_GT(RelativeDistanceUpToRigidMotion(perturbed, rolled_a_), 1e-2);
  ceres::Solver::Summary summary;
  const Positions back =
      ReconstructFromLTheta(space_, own, weights, perturbed, Tight(), &summary);
  EXPECT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
  EXPECT_LT(summary.final_cost, 1e-16);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(back, rolled_a_), 1e-8);
  // From the flat plate the quantities of the rolled plate also lead back to
  // it (the signed dihedral targets fix the rolling direction).
  const Positions from_flat = ReconstructFromLTheta(
      space_, own, weights, plate_.positions, Tight(), &summary);
  EXPECT_LT(RelativeDistanceUpToRigidMotion(from_flat, rolled_a_), 1e-6)
      << summary.BriefReport();
}

TEST_F(LThetaSplineTest, RejectsBadInputs) {
  const std::vector<Positions> keys = {plate_.positions, rolled_a_};
  const SolverSettings settings;
  EXPECT_THROW(LThetaSpline(space_, keys, {0}, 4, false, settings), InputError);
  EXPECT_THROW(LThetaSpline(space_, keys, {2, 1}, 4, false, settings),
               InputError);
  EXPECT_THROW(LThetaSpline(space_, keys, {0, 5}, 4, false, settings),
               InputError);
  EXPECT_THROW(LThetaSpline(space_, keys, {0, 4}, 4, true, settings),
               InputError);
  EXPECT_THROW(LThetaSpline(space_, keys, {0, 1}, 0, false, settings),
               InputError);
  const std::vector<Positions> wrong = {plate_.positions,
                                        rolled_a_.topRows(100)};
  EXPECT_THROW(LThetaSpline(space_, wrong, {0, 4}, 4, false, settings),
               InputError);
}

}  // namespace
}  // namespace shellspace
