// Riemannian splines and regression: the adjoint gradient against central
// differences, spline through keyframes on a geodesic, interpolation of
// regression for small sigma.
#include "shellspace/problems/splines/spline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "shellspace/geometry/rigid_alignment.h"
#include "tests/testing/cli_output.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

SolverSettings TightInner() {
  SolverSettings s = testing::TightSettings(1e-13);
  s.max_iterations = 200;
  return s;
}

class SplineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    a_ = testing::LoadData("plate/plate121.ply");
    b_ = testing::LoadData("plate/plate121_rolledA.ply");
    c_ = testing::LoadData("plate/plate121_rolledB.ply");
    space_ = testing::MakeSpace(a_);
  }
  // Regression on a periodic spline through the three plates, K = 3, data
  // at 0 and 2, sigma = 0.3, every shape free.
  SplineSpec PeriodicRegressionSpec() const {
    SplineSpec spec;
    spec.steps = 3;
    spec.periodic = true;
    spec.initial = {a_.positions, b_.positions, c_.positions};
    spec.is_free = {1, 1, 1};
    spec.data = {{a_.positions, 0}, {c_.positions, 2}};
    spec.sigma = 0.3;
    return spec;
  }
  // An interpolating spline, K = 4, through the three plates at 0, 2, 4
  // (held), started from the piecewise-linear path; shapes 1 and 3 free.
  SplineSpec InterpolatingSpec() const {
    SplineSpec spec;
    spec.steps = 4;
    spec.initial = PiecewiseLinearPath(
        {a_.positions, b_.positions, c_.positions}, {0, 2, 4}, 4, false);
    spec.is_free = {0, 1, 0, 1, 0};
    return spec;
  }
  Mesh a_, b_, c_;
  ShellSpace space_;
};

// The adjoint gradient of `objective` near its initial parameters against
// central differences of its value (testing::CentralDifferenceError, eight
// probed coordinates), and the negative twin: the same gradient with one
// probed entry off by 1e-4 of its scale must fail the same check.
void CheckGradient(const SplineObjective& objective, unsigned seed) {
  std::vector<double> x = objective.InitialParameters();
  // Move off the initial guess a little (deterministically).
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double& v : x) v += 1e-3 * u(rng);
  double cost = 0;
  std::vector<double> gradient(x.size());
  ASSERT_TRUE(objective.Evaluate(x.data(), &cost, gradient.data()));
  const Eigen::VectorXd g = Eigen::Map<const Eigen::VectorXd>(
      gradient.data(), static_cast<int>(gradient.size()));
  bool evaluated = true;
  const testing::VectorFunction value = [&](const Eigen::VectorXd& y) {
    double f = 0;
    evaluated = objective.Evaluate(y.data(), &f, nullptr) && evaluated;
    return Eigen::VectorXd::Constant(1, f);
  };
  const testing::DerivativeColumn columns = [&g](int j) {
    return Eigen::VectorXd::Constant(1, g(j));
  };
  const std::vector<int> probes =
      testing::ProbeCoordinates(static_cast<int>(x.size()), 8, seed);
  const Eigen::VectorXd x0 =
      Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<int>(x.size()));
  // Relative to the largest gradient entry, as |g_i - N_i| <= 1e-5 max |g|.
  const double scale = g.cwiseAbs().maxCoeff();
  EXPECT_LT(
      testing::CentralDifferenceError(value, x0, columns, probes, 1e-5, scale),
      1e-5);
  EXPECT_GT(testing::CentralDifferenceError(
                value, x0,
                testing::WrongInOneEntry(columns, 0, probes[0], 1e-4 * scale),
                probes, 1e-5, scale),
            1e-5);
  EXPECT_TRUE(evaluated);
}

TEST_F(SplineTest, AdjointGradientMatchesCentralDifferences) {
  CheckGradient(SplineObjective(space_, InterpolatingSpec(), TightInner()), 1);
}

TEST_F(SplineTest, RegressionAndPeriodicGradientsMatchCentralDifferences) {
  CheckGradient(SplineObjective(space_, PeriodicRegressionSpec(), TightInner()),
                2);
}

// A point with a collapsed free shape (every vertex of s_1 at one point) is
// rejected by a false return, a numerical status for the line search, not
// an exception; the objective still evaluates a good point afterwards.
TEST_F(SplineTest, DegeneratePointIsRejectedWithoutAnException) {
  const SplineObjective objective(space_, PeriodicRegressionSpec(),
                                  TightInner());
  const std::vector<double> good = objective.InitialParameters();
  std::vector<double> bad = good;
  const int n3 = 3 * space_.num_vertices;
  for (int i = n3; i < 2 * n3; ++i) bad[i] = 0.25;  // s_1 collapsed
  double f = 0;
  std::vector<double> g(good.size());
  bool value_ok = true, gradient_ok = true;
  EXPECT_NO_THROW(value_ok = objective.Evaluate(bad.data(), &f, nullptr));
  EXPECT_NO_THROW(gradient_ok = objective.Evaluate(bad.data(), &f, g.data()));
  EXPECT_FALSE(value_ok);
  EXPECT_FALSE(gradient_ok);
  ASSERT_TRUE(objective.Evaluate(good.data(), &f, g.data()));
  EXPECT_TRUE(std::isfinite(f));
  EXPECT_GT(f, 0);
}

// The warm-started evaluation (Newton from the previous midpoints, the last
// Newton step's Hessian reused for the adjoint) agrees with a cold one (LM
// from the neighbours' average, then Newton) at the same point; FD confirms the
// warm one where the two differed (a cold LM midpoint had been accepted at |G|
// ~ 1e-2).
TEST_F(SplineTest, WarmStartedEvaluationMatchesColdEvaluation) {
  const SplineSpec spec = InterpolatingSpec();
  const SplineObjective warm(space_, spec, TightInner());
  std::vector<double> x = warm.InitialParameters();
  double f = 0;
  std::vector<double> g_warm(x.size()), g_cold(x.size());
  ASSERT_TRUE(warm.Evaluate(x.data(), &f, g_warm.data()));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double& v : x) v += 1e-3 * u(rng);  // as in CheckGradient
  double f_warm = 0, f_cold = 0;
  ASSERT_TRUE(warm.Evaluate(x.data(), &f_warm, g_warm.data()));
  const SplineObjective cold(space_, spec, TightInner());
  ASSERT_TRUE(cold.Evaluate(x.data(), &f_cold, g_cold.data()));
  EXPECT_NEAR(f_warm, f_cold, 1e-10 * f_cold);
  double scale = 0, difference = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    scale = std::max(scale, std::abs(g_cold[i]));
    difference = std::max(difference, std::abs(g_warm[i] - g_cold[i]));
  }
  EXPECT_LT(difference, 1e-7 * scale);
}

// The midpoint terms are solved in parallel: one thread and three give the
// same cost and gradient to the last bit, over a sequence of warm-started
// evaluations (each term depends only on its own warm start and the path).
TEST_F(SplineTest, ThreadCountDoesNotChangeADigit) {
  const SplineSpec spec = PeriodicRegressionSpec();
  SolverSettings one = TightInner(), three = TightInner();
  one.num_threads = 1;
  three.num_threads = 3;
  const SplineObjective serial(space_, spec, one);
  const SplineObjective parallel(space_, spec, three);
  std::vector<double> x = serial.InitialParameters();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int evaluation = 0; evaluation < 3; ++evaluation) {
    double f_serial = 0, f_parallel = 0;
    std::vector<double> g_serial(x.size()), g_parallel(x.size());
    ASSERT_TRUE(serial.Evaluate(x.data(), &f_serial, g_serial.data()));
    ASSERT_TRUE(parallel.Evaluate(x.data(), &f_parallel, g_parallel.data()));
    EXPECT_EQ(f_serial, f_parallel) << "evaluation " << evaluation;
    EXPECT_EQ(g_serial, g_parallel) << "evaluation " << evaluation;
    for (double& v : x) v += 1e-4 * u(rng);
  }
  EXPECT_EQ(serial.timings().newton_steps, parallel.timings().newton_steps);
  EXPECT_EQ(serial.timings().lm_iterations, parallel.timings().lm_iterations);
}

TEST_F(SplineTest, KeyframesOnAGeodesicGiveTheGeodesic) {
  GeodesicInput input = GeodesicInput::Between(a_.positions, b_.positions, 4);
  SolverSettings tight = TightInner();
  const GeodesicResult g = SolveGeodesic(space_, input, tight);
  // The geodesic itself: F_K = 0 (each s_k is the midpoint of its
  // neighbours) and the adjoint gradient vanishes: it is the spline (F >= 0).
  SplineSpec spec;
  spec.steps = 4;
  spec.initial = g.path;
  spec.is_free = {0, 1, 0, 1, 0};
  const SplineObjective objective(space_, spec, tight);
  std::vector<double> x = objective.InitialParameters();
  double f = 0;
  std::vector<double> gradient(x.size());
  ASSERT_TRUE(objective.Evaluate(x.data(), &f, gradient.data()));
  EXPECT_LT(f, 1e-10 * g.path_energy);
  double gmax = 0;
  for (double v : gradient) gmax = std::max(gmax, std::abs(v));
  EXPECT_LT(gmax, 1e-6);
  // From the piecewise linear path, 60 preconditioned L-BFGS iterations
  // drive F_K down by four orders of magnitude and come within 2 % of the
  // linear path's distance to the geodesic (measured: F_K 2.4e-4 of 25.3,
  // distance 2.6e-4 vs 3.8e-2); in the vertex coordinates L-BFGS only gets
  // to F_K = 0.33 (the stiff membrane against the soft bending modes).
  SplineSettings settings;
  settings.inner = tight;
  settings.max_iterations = 60;
  const ShellPath linear = PiecewiseLinearPath(
      {g.path[0], g.path[2], g.path[4]}, {0, 2, 4}, 4, false);
  const double f_linear = objective.SplineEnergyOf(linear);
  const SplineResult spline =
      SolveSpline(space_, {g.path[0], g.path[2], g.path[4]}, {0, 2, 4}, 4,
                  false, {}, settings);
  EXPECT_LT(spline.spline_energy, 1e-4 * f_linear);
  for (int k : {1, 3}) {
    EXPECT_LT(RelativeDistanceUpToRigidMotion(spline.path[k], g.path[k]),
              0.02 * RelativeDistanceUpToRigidMotion(linear[k], g.path[k]))
        << k;
  }
  settings.precondition = false;
  const SplineResult plain =
      SolveSpline(space_, {g.path[0], g.path[2], g.path[4]}, {0, 2, 4}, 4,
                  false, {}, settings);
  EXPECT_GT(plain.spline_energy, 100 * spline.spline_energy);
  for (int k : {0, 2, 4}) {
    EXPECT_EQ((spline.path[k] - g.path[k]).cwiseAbs().maxCoeff(), 0.0) << k;
  }
}

// Euclidean limit: for keyframes within delta of a rest shape, F_K is the
// quadratic (1/2) K^3 sum_k |s_{k-1} - 2 s_k + s_{k+1}|^2_G up to O(delta^3),
// whose minimiser through the keyframes is the discrete cubic spline of the
// vertex positions (per coordinate; at 0, 2, 4 with K = 4:
// s_1 = (5 s_0 + 8 s_2 - s_4) / 12, s_3 = (-s_0 + 8 s_2 + 5 s_4) / 12).
// So the cubic spline is a critical point of F_K up to O(delta^2): the
// adjoint gradient there, relative to that on the piecewise linear path,
// falls linearly in delta.
TEST_F(SplineTest, CubicSplineIsCriticalInTheEuclideanLimit) {
  const Positions& rest = a_.positions;
  const Eigen::Vector3d lo = rest.colwise().minCoeff(),
                        hi = rest.colwise().maxCoeff();
  const double size = (hi - lo).norm();
  Positions bump(rest.rows(), 3), shear(rest.rows(), 3);
  for (int v = 0; v < rest.rows(); ++v) {
    const double x = (rest(v, 0) - lo(0)) / (hi(0) - lo(0));
    const double y = (rest(v, 1) - lo(1)) / (hi(1) - lo(1));
    bump.row(v) = Eigen::Vector3d(0.3 * x * y, 0,
                                  std::sin(M_PI * x) * std::sin(M_PI * y));
    shear.row(v) = Eigen::Vector3d(0, 0.2 * x * x, std::cos(M_PI * x) * y * y);
  }
  auto ratio = [&](double delta) {
    const std::vector<Positions> keys = {rest, rest + delta * size * bump,
                                         rest + delta * size * shear};
    SplineSpec spec;
    spec.steps = 4;
    spec.is_free = {0, 1, 0, 1, 0};
    auto gradient_norm = [&](const ShellPath& path) {
      spec.initial = path;
      const SplineObjective objective(space_, spec, TightInner());
      std::vector<double> x = objective.InitialParameters(), g(x.size());
      double f = 0;
      EXPECT_TRUE(objective.Evaluate(x.data(), &f, g.data()));
      return Eigen::Map<Eigen::VectorXd>(g.data(), g.size()).norm();
    };
    const ShellPath cubic = {
        keys[0], (5 * keys[0] + 8 * keys[1] - keys[2]) / 12, keys[1],
        (-keys[0] + 8 * keys[1] + 5 * keys[2]) / 12, keys[2]};
    const ShellPath linear = PiecewiseLinearPath(keys, {0, 2, 4}, 4, false);
    return gradient_norm(cubic) / gradient_norm(linear);
  };
  const double coarse = ratio(0.02), fine = ratio(0.01);
  std::cout << "|grad F_K(cubic)| / |grad F_K(linear)|: " << coarse
            << " (delta 0.02), " << fine << " (delta 0.01)\n";
  EXPECT_LT(coarse, 0.2);
  EXPECT_NEAR(fine / coarse, 0.5, 0.15);  // first order in delta
}

TEST_F(SplineTest, RegressionWithSmallSigmaInterpolates) {
  SplineSettings settings;
  settings.inner = TightInner();
  settings.gradient_tolerance = 1e-10;
  settings.max_iterations = 40;
  const std::vector<Positions> data = {a_.positions, b_.positions,
                                       c_.positions};
  const SplineResult r =
      SolveRegression(space_, data, {0, 1, 2}, 2, 1e-6, {}, settings);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(RelativeDistanceUpToRigidMotion(r.path[k], data[k]), 1e-3) << k;
  }
  // Larger sigma lowers F_K.
  const SplineResult smooth =
      SolveRegression(space_, data, {0, 1, 2}, 2, 1.0, r.path, settings);
  EXPECT_LT(smooth.spline_energy, r.spline_energy);
  EXPECT_GT(smooth.data_energy, r.data_energy);
}

// L-BFGS in rounds with refreshed metrics (preconditioner_refresh) against
// one round on the three plates (sigma 0.3, every shape free): the gradient
// is measured in the first round's variables in both (the same initial norm,
// to the bit); the rounds meet the criterion, with the reported final
// gradient below the target, in fewer iterations than the one round needs to
// come within 1e-6 of their objective. The criterion is 1e-5 relative: the
// rounds' line search ends on a zero step (the objective's noise from the
// inner midpoint solves) between about 0.9e-6 and 1.3e-6, whichever the
// round-off of the metrics' sums; one round stays near 0.3.
TEST_F(SplineTest, RegressionInRoundsBeatsOneRound) {
  SplineSettings settings;
  settings.inner = TightInner();
  settings.gradient_tolerance = 1e-5;
  settings.function_tolerance = 0;  // stop on the gradient alone
  settings.max_iterations = 150;
  const std::vector<Positions> data = {a_.positions, b_.positions,
                                       c_.positions};
  settings.preconditioner_refresh = 4;
  const SplineResult rounds =
      SolveRegression(space_, data, {0, 1, 2}, 2, 0.3, {}, settings);
  settings.preconditioner_refresh = 0;
  const SplineResult one =
      SolveRegression(space_, data, {0, 1, 2}, 2, 0.3, {}, settings);
  std::cout << "rounds of 4: " << rounds.iterations << " iterations in "
            << rounds.rounds << " rounds, objective " << rounds.objective
            << ", relative gradient " << rounds.relative_gradient_norm
            << "; one round: " << one.iterations << " iterations, objective "
            << one.objective << ", relative gradient "
            << one.relative_gradient_norm << "\n";
  EXPECT_EQ(one.rounds, 1);
  EXPECT_GT(rounds.rounds, 1);
  EXPECT_EQ(one.initial_gradient_norm, rounds.initial_gradient_norm);
  EXPECT_TRUE(rounds.gradient_criterion_met);
  EXPECT_LE(rounds.final_gradient_norm, 1e-5 * rounds.initial_gradient_norm);
  // Twin: one round, through the same criterion, does not meet it.
  EXPECT_FALSE(one.gradient_criterion_met);
  EXPECT_LT(rounds.iterations, one.iterations);
  EXPECT_GT(one.objective, rounds.objective * (1 + 1e-6));
}

// A stop requested on entry, or during the first evaluation (the second
// poll: the first cold-start LM iteration of a midpoint), returns the start
// as it is, with the energies NaN (not evaluated) and 0 iterations. The twin,
// a poll that never fires, evaluates F_K and changes no digit of the run
// without a poll.
TEST_F(SplineTest, AStopBeforeTheFirstEvaluationReturnsTheStartUnevaluated) {
  const std::vector<Positions> keys = {a_.positions, b_.positions,
                                       c_.positions};
  const ShellPath start = PiecewiseLinearPath(keys, {0, 2, 4}, 4, false);
  SplineSettings settings;
  settings.inner = TightInner();
  settings.max_iterations = 3;
  const auto solve = [&](int fire_at_poll, int* polls) {
    SplineSettings s = settings;
    if (polls != nullptr) {
      s.stop = StopToken(
          [polls, fire_at_poll] { return ++*polls >= fire_at_poll; });
    }
    return SolveSpline(space_, keys, {0, 2, 4}, 4, false, start, s);
  };
  for (const int fire_at : {1, 2}) {
    int polls = 0;
    const SplineResult stopped = solve(fire_at, &polls);
    EXPECT_GE(polls, fire_at);
    EXPECT_FALSE(stopped.evaluated) << fire_at;
    EXPECT_FALSE(stopped.converged);
    EXPECT_EQ(stopped.iterations, 0);
    EXPECT_TRUE(std::isnan(stopped.spline_energy));
    EXPECT_TRUE(std::isnan(stopped.objective));
    ASSERT_EQ(stopped.path.size(), start.size());
    for (size_t k = 0; k < start.size(); ++k) {
      EXPECT_EQ((stopped.path[k] - start[k]).cwiseAbs().maxCoeff(), 0.0) << k;
    }
  }
  int polls = 0;
  const SplineResult polled = solve(1 << 30, &polls);
  const SplineResult plain = solve(0, nullptr);
  EXPECT_GT(polls, 2);
  EXPECT_TRUE(polled.evaluated);
  EXPECT_TRUE(std::isfinite(polled.spline_energy));
  EXPECT_GT(polled.spline_energy, 0.0);
  EXPECT_EQ(polled.spline_energy, plain.spline_energy);
  EXPECT_EQ(polled.iterations, plain.iterations);
  for (size_t k = 0; k < start.size(); ++k) {
    EXPECT_EQ((polled.path[k] - plain.path[k]).cwiseAbs().maxCoeff(), 0.0);
  }
}

// Growing sigma lowers F_K monotonically (and raises the data term): four
// sphere poses at 0..3, K = 3, each solve warm-started from the previous.
TEST(RegressionTest, GrowingSigmaLowersSplineEnergy) {
  std::vector<Positions> data;
  Mesh first;
  for (const char* name :
       {"sphere/unitSphere1.ply", "sphere/unitSphere1_defX.ply",
        "sphere/unitSphere1_defY.ply", "sphere/unitSphere1_defZ.ply"}) {
    Mesh m = testing::LoadData(name);
    if (data.empty()) first = m;
    data.push_back(m.positions);
  }
  const ShellSpace space = testing::MakeSpace(first);
  SplineSettings settings;
  settings.max_iterations = 25;
  ShellPath warm;
  double previous_f = 1e300, previous_data = -1;
  for (double sigma : {1e-4, 1e-3, 1e-2, 1e-1}) {
    const SplineResult r =
        SolveRegression(space, data, {0, 1, 2, 3}, 3, sigma, warm, settings);
    EXPECT_LT(r.spline_energy, previous_f) << sigma;
    EXPECT_GT(r.data_energy, previous_data) << sigma;
    previous_f = r.spline_energy;
    previous_data = r.data_energy;
    warm = r.path;
    std::cout << "sigma " << sigma << ": F_K " << r.spline_energy
              << ", data term " << r.data_energy << "\n";
  }
}

// The flat and the two rolled plates, as --keyframes.
std::string PlateKeyframes() {
  std::string list;
  for (const char* name : {"plate121", "plate121_rolledA", "plate121_rolledB"}) {
    list += (list.empty() ? "" : ",") +
            testing::DataPath(std::string("plate/") + name + ".ply");
  }
  return list;
}

TEST(SplineCliTest, LThetaFramesAndErrors) {
  const std::string dir = testing::TempDir();
  const std::string keys = PlateKeyframes();
  std::string out, err;
  ASSERT_EQ(
      testing::RunCli("spline --quiet --json --method ltheta --keyframes " +
                          keys + " --at 0,2,4 --steps 4 --output " + dir + "/s",
                      &out, &err),
      0)
      << err;
  EXPECT_NE(out.find("\"spline_energy\""), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir + "/s/shape_004.ply"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/s/shape_005.ply"));
  for (const std::string& bad :
       {"spline --keyframes " + keys + " --at 0,2 --steps 4 --output " + dir +
            "/b",
        "spline --keyframes " + keys + " --at 0,3,2 --steps 4 --output " + dir +
            "/b",
        "spline --keyframes " + keys +
            " --at 0,2,4 --steps 4 --method cubic --output " + dir + "/b",
        "spline --keyframes " + keys +
            " --at 0,2,4 --steps 4 --init linear --output " + dir + "/b",
        "spline --keyframes " + keys +
            " --at 0,2,4 --steps 4 --method ltheta --init geodesic --output " +
            dir + "/b",
        "regress --inputs " + keys +
            " --at 0,1,2 --steps 2 --sigma -1 --output " + dir + "/b"}) {
    EXPECT_EQ(testing::RunCli(bad, nullptr, &err), 1) << bad;
    EXPECT_FALSE(std::filesystem::exists(dir + "/b")) << bad;
  }
}

// --init geodesic: the JSON names the initial path and its segments (no
// ltheta object), and the run ends converged -- at the same spline as from
// the LΘA start (measured: F_K 69.3878610931 from both, 2e-13 apart).
TEST(SplineCliTest, FromThePiecewiseGeodesic) {
  const std::string dir = testing::TempDir();
  const std::string keys = PlateKeyframes();
  const std::string common = "spline --quiet --json --keyframes " + keys +
                             " --at 0,2,4 --steps 4 --eta 0.01 ";
  std::string out, err;
  ASSERT_EQ(testing::RunCli(common + "--init geodesic --output " + dir +
                                "/geodesic_init",
                            &out, &err),
            0)
      << err;
  EXPECT_NE(out.find("\"init\": \"geodesic\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"init_segments\": [{\"from\": 0, \"to\": 2"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("\"ltheta\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"converged\": true"), std::string::npos) << out;
  const double f_geodesic_start = testing::Number(out, "spline_energy");
  ASSERT_EQ(testing::RunCli(common + "--output " + dir + "/ltheta_init", &out,
                            &err),
            0)
      << err;
  EXPECT_NE(out.find("\"init\": \"ltheta\""), std::string::npos) << out;
  const double f_ltheta_start = testing::Number(out, "spline_energy");
  EXPECT_NEAR(f_geodesic_start, f_ltheta_start, 1e-8 * f_ltheta_start);
}

}  // namespace
}  // namespace shellspace
