// The workflows (shellspace/workflows/) on procedural sheets: the digits of
// the front ends' former code paths, the energy split, the stop phases of
// PCA and a failing solve as a status, not an exception.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/workflows/geodesic.h"
#include "shellspace/workflows/mean.h"
#include "shellspace/workflows/pca.h"
#include "shellspace/workflows/regress.h"
#include "shellspace/workflows/shoot.h"
#include "shellspace/workflows/spline.h"
#include "shellspace/workflows/transport.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using workflows::SolveStatus;

// The CLI's defaults: mu = lambda = 1, eta = 1e-4 x the reference's area,
// tolerance 1e-8, 200 iterations, 2 threads.
workflows::MaterialChoice DefaultMaterial(const Mesh& reference) {
  workflows::MaterialChoice choice;
  choice.material.eta = EtaFromRelative(kDefaultRelativeEta, reference);
  return choice;
}

SolverSettings DefaultSettings() {
  return UserSolverSettings(1e-8, 200, 2, /*quiet=*/true, "test");
}

// The bent sheet: a 6 x 4 equilateral sheet of side 0.25 and the same
// sheet rolled onto a cylinder of radius 0.6.
Mesh Sheet() { return MakeEquilateralSheet(6, 4, 0.25); }

workflows::GeodesicOptions BentSheetGeodesic() {
  workflows::GeodesicOptions options;
  options.start = Sheet();
  options.topology = Topology::Build(options.start);
  options.end = RollOntoCylinder(options.start.positions, 0.6);
  options.steps = 4;
  options.material = DefaultMaterial(options.start);
  options.settings = DefaultSettings();
  return options;
}

// Four shapes of the sheet: flat and rolled onto radii 0.6, 1.0 and 2.0.
workflows::PcaOptions FourSheets() {
  workflows::PcaOptions options;
  options.reference = Sheet();
  options.topology = Topology::Build(options.reference);
  options.shapes = {options.reference.positions};
  for (const double radius : {0.6, 1.0, 2.0}) {
    options.shapes.push_back(
        RollOntoCylinder(options.reference.positions, radius));
  }
  options.material = DefaultMaterial(options.reference);
  options.modes = 1;
  // The CLI's --log_steps 2 --exp_steps 4 --max_exp_steps 16.
  options.pca = MakeShellPcaOptions(2, 4, 16, "log", "");
  options.settings = DefaultSettings();
  return options;
}

// The mean of the same four sheets, material and settings.
workflows::MeanOptions MeanOfFourSheets() {
  const workflows::PcaOptions sheets = FourSheets();
  workflows::MeanOptions options;
  options.reference = sheets.reference;
  options.topology = sheets.topology;
  options.shapes = sheets.shapes;
  options.material = sheets.material;
  options.settings = sheets.settings;
  return options;
}

// E_K of the CLI before the workflows (commit 832cb59), on the files that
// WorkflowCliTest's SetUp writes (the sheets of FourSheets() as PLY with 17
// digits, read back bit for bit; the temporary folder is left behind):
//   shellspace geodesic --start sheet.ply --end rolled_0.6.ply --steps 4
//     --output g --json --quiet
// "path_energy": 0.0013510370561477059 (7 iterations, converged),
// "energy_split": {"membrane": 9.137474658097428e-05,
// "bending": 0.0012596623095667316}.
constexpr double kCliPathEnergy = 0.0013510370561477059;
constexpr double kCliMembrane = 9.137474658097428e-05;

// The summary reports the input's slivers and the largest area ratio
// |f(s_k)| / |f(s_0)| of one of them along the path, recomputed here from
// the frames; the twin, the sheet without slivers, reports none.
TEST(GeodesicWorkflowTest, TheSummaryReportsHowThePathSwellsTheSlivers) {
  workflows::GeodesicOptions options = BentSheetGeodesic();
  // Vertex 8 (interior) towards the midpoint of the opposite edge of its
  // first triangle: that triangle becomes a sliver, inside its star.
  const int v = 8;
  int a = -1, b = -1;
  for (int f = 0; f < options.start.num_faces() && a < 0; ++f) {
    for (int c = 0; c < 3; ++c) {
      if (options.start.faces(f, c) == v) {
        a = options.start.faces(f, (c + 1) % 3);
        b = options.start.faces(f, (c + 2) % 3);
      }
    }
  }
  ASSERT_GE(a, 0);
  const Eigen::RowVector3d mid =
      0.5 * (options.start.positions.row(a) + options.start.positions.row(b));
  options.start.positions.row(v) =
      mid + 0.005 * (options.start.positions.row(v) - mid);
  options.end = RollOntoCylinder(options.start.positions, 0.6);
  const workflows::GeodesicResult r = workflows::RunGeodesic(options);
  ASSERT_FALSE(r.slivers.faces.empty());
  const auto area = [&](const Positions& x, int f) {
    const Eigen::Vector3d p = x.row(options.start.faces(f, 0)),
                          q = x.row(options.start.faces(f, 1)),
                          w = x.row(options.start.faces(f, 2));
    return 0.5 * (q - p).cross(w - p).norm();
  };
  double largest = 1;
  int face = -1, shape = -1;
  for (const int f : r.slivers.faces) {
    for (size_t k = 1; k < r.path().size(); ++k) {
      const double ratio = area(r.path()[k], f) / area(r.path()[0], f);
      if (ratio > largest) {
        largest = ratio;
        face = f;
        shape = static_cast<int>(k);
      }
    }
  }
  ASSERT_GT(largest, 1);  // the roll stretches the sliver: a real maximum
  EXPECT_NEAR(r.sliver_swelling, largest, 1e-12 * largest);
  EXPECT_EQ(r.sliver_swelling_face, face);
  EXPECT_EQ(r.sliver_swelling_shape, shape);
  const std::string json = workflows::ToJson(r).str();
  EXPECT_NE(json.find("\"input_slivers\": {\"faces\": [" +
                      std::to_string(r.slivers.faces.front())),
            std::string::npos)
      << json;
  EXPECT_NE(json.find("\"largest_swelling\": " + JsonObject::Number(largest)),
            std::string::npos);
  // The twin.
  const workflows::GeodesicResult clean =
      workflows::RunGeodesic(BentSheetGeodesic());
  EXPECT_TRUE(clean.slivers.faces.empty());
  EXPECT_EQ(clean.sliver_swelling, 1);
  EXPECT_EQ(clean.sliver_swelling_face, -1);
  EXPECT_NE(workflows::ToJson(clean).str().find(
                "\"input_slivers\": {\"faces\": []"),
            std::string::npos)
      << workflows::ToJson(clean).str();
}

TEST(GeodesicWorkflowTest, EqualsTheCliDigitsAndItsSplitSumsToTheEnergy) {
  const workflows::GeodesicResult result =
      workflows::RunGeodesic(BentSheetGeodesic());
  ASSERT_EQ(result.status.code, SolveStatus::Code::kConverged)
      << result.status.message;
  EXPECT_TRUE(result.geodesic().converged);
  EXPECT_NEAR(result.path_energy(), kCliPathEnergy, 1e-12);
  EXPECT_EQ(result.path().size(), 5u);
  // The split once, from the path: membrane + bending = E_K, both > 0.
  // (E_K and its parts to 1e-12, as recorded at 832cb59: the Newton
  // finish's forcing of 4a1dd84 moved the membrane part by 8e-15; the CLI
  // of this build is compared digit for digit in WorkflowCliTest.)
  EXPECT_NEAR(result.energy_split.membrane, kCliMembrane, 1e-12);
  EXPECT_GT(result.energy_split.bending, 0);
  EXPECT_NEAR(result.energy_split.total(), result.path_energy(),
              1e-12 * result.path_energy());
  // The summary is made from the result: its E_K is the result's. It is a
  // tree of values to its leaves (no raw text: Python converts it directly).
  EXPECT_FALSE(workflows::ToJson(result).value().ContainsRaw());
  const std::string json = workflows::ToJson(result).str();
  EXPECT_NE(json.find("\"path_energy\": " + JsonObject::Number(
                          result.path_energy())),
            std::string::npos);
  EXPECT_NE(json.find("\"energy_split\": {\"membrane\": " +
                      JsonObject::Number(result.energy_split.membrane)),
            std::string::npos);
}

TEST(GeodesicWorkflowTest, LogIsKTimesTheFirstStep) {
  const workflows::LogResult result = workflows::RunLog(BentSheetGeodesic());
  ASSERT_TRUE(result.geodesic.status.ok());
  const ShellPath& path = result.geodesic.path();
  const Positions expected = 4.0 * (path[1] - path[0]);
  EXPECT_LT((result.log - expected).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_DOUBLE_EQ(result.log_max_norm, expected.cwiseAbs().maxCoeff());
}

// A bad word is bad input (InputError naming the option with its prefix),
// not a status.
TEST(GeodesicWorkflowTest, BadOptionsAreInputErrors) {
  workflows::GeodesicOptions options = BentSheetGeodesic();
  options.multires = "sometimes";
  options.option_prefix = "--";
  try {
    workflows::RunGeodesic(options);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--multires"), std::string::npos)
        << e.what();
  }
  options = BentSheetGeodesic();
  options.steps = 0;
  EXPECT_THROW(workflows::RunGeodesic(options), InputError);
}

// A solve that misses its criterion is a status with one line, not an
// exception: one iteration cannot reach the tolerance.
TEST(GeodesicWorkflowTest, AnUnconvergedSolveIsAStatusNotAThrow) {
  workflows::GeodesicOptions options = BentSheetGeodesic();
  options.settings.max_iterations = 1;
  workflows::GeodesicResult result;
  ASSERT_NO_THROW(result = workflows::RunGeodesic(options));
  ASSERT_EQ(result.status.code, SolveStatus::Code::kNotConverged)
      << SolveStatusName(result.status.code) << ": " << result.status.message;
  ASSERT_EQ(result.status.failures.size(), 1u);
  EXPECT_EQ(result.status.message.rfind("geodesic: |grad| ", 0), 0u)
      << result.status.message;
  EXPECT_NE(result.status.message.find("after 1 iterations"),
            std::string::npos)
      << result.status.message;
  EXPECT_EQ(result.status.message.find('\n'), std::string::npos);
  EXPECT_FALSE(result.geodesic().converged);
  EXPECT_EQ(result.path().size(), 5u);
  // The log names the geodesic as the log's.
  const workflows::LogResult log = workflows::RunLog(options);
  EXPECT_EQ(log.geodesic.status.message.rfind("log: the geodesic: |grad| ", 0),
            0u)
      << log.geodesic.status.message;
}

// A mean whose solve stops short is a status too; the stop poll seen by a
// solve is the run's stop state.
TEST(MeanWorkflowTest, AStoppedMeanIsAStatusWithItsState) {
  workflows::MeanOptions options = MeanOfFourSheets();
  options.settings.stop = [] { return true; };
  workflows::MeanResult result;
  ASSERT_NO_THROW(result = workflows::RunMean(options));
  EXPECT_TRUE(result.stopped);
  EXPECT_EQ(result.status.code, SolveStatus::Code::kStopped);
  EXPECT_FALSE(result.mean.converged);
  ASSERT_EQ(result.status.failures.size(), 1u);
  EXPECT_EQ(result.status.failures[0].rfind("elastic mean: |grad| ", 0), 0u)
      << result.status.failures[0];
}

// The mean and the first mode shape of the CLI before the workflows (commit
// 832cb59), on the files of WorkflowCliTest:
//   shellspace pca --inputs sheet.ply,rolled_0.6.ply,rolled_1.ply,rolled_2.ply
//     --modes 1 --output p --json --quiet
// p/mean.ply and p/mode_1_plus.ply: the sum of the squares of all
// coordinates and vertex 17's z; "eigenvalues"[0] of its summary. The
// Newton finish's forcing of 4a1dd84 moved the LOG and EXP solves within
// their tolerance: the mode shape by 4e-9, the eigenvalue by 2.5e-7
// relative (the mean not at all); the CLI of this build is compared digit
// for digit in WorkflowCliTest.PcaWritesTheWorkflowsShapes.
constexpr double kCliMeanSquares = 40.56464366574963;
constexpr double kCliMeanZ17 = 0.09707285835091392;
constexpr double kCliModePlusSquares = 40.11099133625926;
constexpr double kCliModePlusZ17 = 0.10805843098157757;
constexpr double kCliFirstEigenvalue = 0.0019444427306022302;

TEST(PcaWorkflowTest, MeanAndFirstModeShapeEqualTheCli) {
  const workflows::PcaOptions options = FourSheets();
  const workflows::PcaResult result = workflows::RunPca(options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  EXPECT_EQ(result.stopped_in, "");
  ASSERT_TRUE(result.model.has_value());
  const Positions* mean = result.Shape("mean");
  const Positions* plus = result.Shape("mode_1_plus");
  ASSERT_NE(mean, nullptr);
  ASSERT_NE(plus, nullptr);
  ASSERT_NE(result.Shape("mode_1_minus"), nullptr);
  EXPECT_EQ(result.Shape("mode_2_plus"), nullptr);  // modes = 1
  EXPECT_NEAR(mean->squaredNorm(), kCliMeanSquares, 1e-12);
  EXPECT_NEAR((*mean)(17, 2), kCliMeanZ17, 1e-14);
  EXPECT_NEAR(plus->squaredNorm(), kCliModePlusSquares, 1e-6);
  EXPECT_NEAR((*plus)(17, 2), kCliModePlusZ17, 1e-7);
  EXPECT_NEAR(result.model->eigenvalues(0), kCliFirstEigenvalue,
              1e-5 * kCliFirstEigenvalue);
  EXPECT_TRUE(result.failed_shapes.empty());
  EXPECT_FALSE(workflows::ToJson(result, options).value().ContainsRaw());
  const std::string json = workflows::ToJson(result, options).str();
  EXPECT_NE(json.find("\"modes\": 1"), std::string::npos) << json;
}

// A stop request before the first solve ends the run in the mean's phase:
// the mean alone, stopped_in "mean", status kStopped.
TEST(PcaWorkflowTest, AStoppedRunReturnsTheMeanAndThePhase) {
  workflows::PcaOptions options = FourSheets();
  options.settings.stop = [] { return true; };
  const workflows::PcaResult result = workflows::RunPca(options);
  EXPECT_EQ(result.stopped_in, "mean");
  EXPECT_TRUE(result.stopped);
  EXPECT_EQ(result.status.code, SolveStatus::Code::kStopped);
  ASSERT_EQ(result.shapes.size(), 1u);
  EXPECT_EQ(result.shapes[0].first, "mean");
  EXPECT_FALSE(result.model.has_value());
  const std::string json = workflows::ToJson(result, options).str();
  EXPECT_NE(json.find("\"stopped_in\": \"mean\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"modes\": 0"), std::string::npos) << json;
}

// A poll that turns true only after the mean's solve: the run ends in a
// later phase, never with a mode.
TEST(PcaWorkflowTest, AStopAfterTheMeanEndsInALaterPhase) {
  workflows::PcaOptions options = FourSheets();
  const workflows::PcaResult full = workflows::RunPca(options);
  ASSERT_TRUE(full.status.ok());
  // Stop at the first poll after the mean's solve: count the polls of a
  // mean alone.
  workflows::MeanOptions mean_options;
  mean_options.reference = options.reference;
  mean_options.topology = options.topology;
  mean_options.shapes = options.shapes;
  mean_options.material = options.material;
  mean_options.settings = options.settings;
  auto polls = std::make_shared<int>(0);
  mean_options.settings.stop = [polls] {
    ++*polls;
    return false;
  };
  const workflows::MeanResult mean = workflows::RunMean(mean_options);
  ASSERT_TRUE(mean.status.ok());
  ASSERT_GT(*polls, 0);
  const int mean_polls = *polls;
  auto count = std::make_shared<int>(0);
  options.settings.stop = [count, mean_polls] {
    return ++*count > mean_polls;
  };
  const workflows::PcaResult result = workflows::RunPca(options);
  EXPECT_EQ(result.stopped_in, "displacements");
  EXPECT_EQ(result.status.code, SolveStatus::Code::kStopped);
  ASSERT_EQ(result.shapes.size(), 1u);
  // The mean is the unstopped run's.
  EXPECT_EQ((result.shapes[0].second - full.mean.mean).cwiseAbs().maxCoeff(),
            0.0);
}

TEST(MeanWorkflowTest, SplitSumsToTheMeanEnergy) {
  workflows::MeanOptions options = MeanOfFourSheets();
  const workflows::MeanResult result = workflows::RunMean(options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  // The split is that of the mean's objective sum_i W[S_i, mean] (the
  // inputs as references): its total is the solver's energy, and its
  // membrane part is evaluated here independently. The reversed order
  // W[mean, S_i] (what the summary split before) is another number.
  const ShellSpace space(options.reference, options.topology,
                         options.material.material);
  double membrane = 0, reversed = 0;
  for (const Positions& shape : options.shapes) {
    membrane += EvaluateDeformationEnergy(space, shape, result.mean.mean)
                    .membrane;
    reversed +=
        EvaluateDeformationEnergy(space, result.mean.mean, shape).total;
  }
  EXPECT_NEAR(result.energy_split.membrane, membrane, 1e-15);
  EXPECT_NEAR(result.energy_split.total(), result.mean.energy,
              1e-12 * result.mean.energy);
  EXPECT_GT(std::abs(reversed - result.mean.energy), 1e-6 * reversed);
  EXPECT_GT(result.energy_split.bending, 0);
  EXPECT_FALSE(workflows::ToJson(result).value().ContainsRaw());
}

// A shot from the geodesic's first two shapes: K + 1 shapes starting with
// them, every EXP step solved, the shot's split summing to its E_K.
TEST(ShootWorkflowTest, ShotFromAGeodesicsFirstStep) {
  const workflows::GeodesicOptions geodesic_options = BentSheetGeodesic();
  const workflows::GeodesicResult geodesic =
      workflows::RunGeodesic(geodesic_options);
  ASSERT_TRUE(geodesic.status.ok());
  workflows::ShootOptions options;
  options.first = geodesic.start;
  options.topology = geodesic_options.topology;
  options.second = geodesic.path()[1];
  options.steps = 4;
  options.material = geodesic_options.material;
  options.settings = DefaultSettings();
  const workflows::ShootResult result = workflows::RunShoot(options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.path().size(), 5u);
  EXPECT_EQ(result.path()[0], geodesic.path()[0]);
  EXPECT_EQ(result.path()[1], geodesic.path()[1]);
  ASSERT_EQ(result.shot.exp_steps.size(), 3u);
  for (const ExpStepResult& step : result.shot.exp_steps) {
    EXPECT_TRUE(step.solved);
  }
  EXPECT_NEAR(result.energy_split.total(), result.shot.path_energy,
              1e-12 * result.shot.path_energy);
  EXPECT_FALSE(workflows::ToJson(result).value().ContainsRaw());
  options.steps = 0;
  EXPECT_THROW(workflows::RunShoot(options), InputError);
}

// Transport of a zero variation is zero (to the EXP solves' accuracy);
// epsilon must be positive.
TEST(TransportWorkflowTest, ZeroStaysZeroAndBadEpsilonIsInput) {
  const workflows::GeodesicOptions geodesic_options = BentSheetGeodesic();
  const workflows::GeodesicResult geodesic =
      workflows::RunGeodesic(geodesic_options);
  ASSERT_TRUE(geodesic.status.ok());
  workflows::TransportOptions options;
  options.first = geodesic.start;
  options.topology = geodesic_options.topology;
  options.path = geodesic.path();
  options.variation = geodesic.start.positions;
  options.material = geodesic_options.material;
  options.settings = DefaultSettings();
  const workflows::TransportResult result = workflows::RunTransport(options);
  ASSERT_TRUE(result.status.ok()) << result.status.message;
  ASSERT_EQ(result.shapes().size(), geodesic.path().size());
  for (size_t k = 0; k < result.shapes().size(); ++k) {
    EXPECT_LT((result.shapes()[k] - geodesic.path()[k]).cwiseAbs().maxCoeff(),
              1e-5)
        << "frame " << k;
  }
  for (const double epsilon : {0.0, -1.0, std::nan("")}) {
    options.epsilon = epsilon;
    EXPECT_THROW(workflows::RunTransport(options), InputError) << epsilon;
  }
}

// The regression of the CLI before the workflows (commit 1cc4f27, whose
// regress verb was that of 832cb59), on the files of WorkflowCliTest:
//   shellspace regress --inputs sheet.ply,rolled_1.ply,rolled_0.6.ply
//     --at 0,2,4 --steps 4 --sigma 1 --max_iterations 5 --output r --json
// exits 4 (not converged after 5 L-BFGS iterations) with "objective":
// 14.263225887182728, "spline_energy": 14.25779633380303,
// "energy_split": {"membrane": 0.3277188182028495, ...}.
constexpr double kCliRegressObjective = 14.263225887182728;
constexpr double kCliRegressSplineEnergy = 14.25779633380303;
constexpr double kCliRegressMembrane = 0.3277188182028495;

TEST(RegressWorkflowTest, EqualsTheCliDigitsAndIsNotConverged) {
  const workflows::PcaOptions sheets = FourSheets();
  workflows::RegressOptions options;
  options.reference = sheets.reference;
  options.topology = sheets.topology;
  options.inputs = {sheets.shapes[0], sheets.shapes[2], sheets.shapes[1]};
  options.at = {0, 2, 4};
  options.steps = 4;
  options.sigma = 1;
  options.material = sheets.material;
  // The CLI's settings: the outer L-BFGS at --max_iterations 5, the
  // midpoint solves to 1e-10 in at most 200 iterations.
  options.settings.inner = DefaultSettings();
  options.settings.inner.gradient_tolerance = 1e-10;
  options.settings.inner.max_iterations = 200;
  options.settings.max_iterations = 5;
  options.settings.gradient_tolerance = 1e-8;
  const workflows::RegressResult result = workflows::RunRegress(options);
  EXPECT_EQ(result.status.code, SolveStatus::Code::kNotConverged);
  EXPECT_EQ(result.status.message.rfind("regress: relative gradient ", 0), 0u)
      << result.status.message;
  EXPECT_NEAR(result.spline.objective, kCliRegressObjective,
              1e-12 * kCliRegressObjective);
  EXPECT_NEAR(result.spline.spline_energy, kCliRegressSplineEnergy,
              1e-12 * kCliRegressSplineEnergy);
  EXPECT_NEAR(result.energy_split.membrane, kCliRegressMembrane,
              1e-12 * kCliRegressMembrane);
  options.sigma = -1;
  EXPECT_THROW(workflows::RunRegress(options), InputError);
}

// The splines of the CLI before the spline workflow (commit 66b2642, whose
// spline verb was that of 832cb59), on the files of WorkflowCliTest:
//   shellspace spline --keyframes sheet.ply,rolled_1.ply,rolled_0.6.ply
//     --at 0,2,4 --steps 4 --method M --max_iterations 3 --output s --json
// nonlinear: exit 4 (3 L-BFGS iterations), "spline_energy":
// 0.0006148546899275184, energy_split "membrane": 9.933615809719777e-05;
// ltheta: exit 0, "spline_energy": 0.0006193429321353981, "membrane":
// 9.954466905005312e-05. The nonlinear digits agree to 1e-10 since the
// path Hessian sums an element's two diagonal contributions before
// scattering them, in a locality order of the elements (the same matrix up
// to round-off, which three L-BFGS iterations from an unconverged start
// carry to about 1e-11 relative); the ltheta ones to 1e-11: its energy's
// midpoints are geodesic solves to |grad| 1e-10, which since the staged
// globalisation of SolveGeodesic reach that tolerance by another route of
// LM and Newton steps than that CLI's (2.5e-12 relative apart).
workflows::SplineOptions ThreeKeyframes(const std::string& method) {
  const workflows::PcaOptions sheets = FourSheets();
  workflows::SplineOptions options;
  options.reference = sheets.reference;
  options.topology = sheets.topology;
  options.keyframes = {sheets.shapes[0], sheets.shapes[2], sheets.shapes[1]};
  options.at = {0, 2, 4};
  options.steps = 4;
  options.method = method;
  options.material = sheets.material;
  // The CLI's: the initial path's solves and the midpoints at most 200
  // iterations each, the midpoints to 1e-10, the L-BFGS 3 iterations.
  options.init_settings = DefaultSettings();
  options.init_settings.max_iterations = 200;
  options.settings.inner = DefaultSettings();
  options.settings.inner.gradient_tolerance = 1e-10;
  options.settings.inner.max_iterations = 200;
  options.settings.max_iterations = 3;
  options.settings.gradient_tolerance = 1e-8;
  return options;
}

TEST(SplineWorkflowTest, EqualsTheCliDigitsForBothMethods) {
  struct Case {
    std::string method;
    double spline_energy, membrane;
    SolveStatus::Code code;
    double tolerance;  // relative
  };
  const std::vector<Case> cases = {
      {"nonlinear", 0.0006148546899275184, 9.933615809719777e-05,
       SolveStatus::Code::kNotConverged, 1e-10},
      {"ltheta", 0.0006193429321353981, 9.954466905005312e-05,
       SolveStatus::Code::kConverged, 1e-11},
  };
  for (const Case& c : cases) {
    const workflows::SplineResult result =
        workflows::RunSpline(ThreeKeyframes(c.method));
    EXPECT_EQ(result.status.code, c.code) << c.method << ": "
                                          << result.status.message;
    EXPECT_TRUE(result.energy_evaluated);
    EXPECT_EQ(result.optimised, c.method == "nonlinear");
    EXPECT_NEAR(result.spline.spline_energy, c.spline_energy,
                c.tolerance * c.spline_energy)
        << c.method;
    EXPECT_NEAR(result.energy_split.membrane, c.membrane,
                c.tolerance * c.membrane)
        << c.method;
    EXPECT_FALSE(workflows::ToJson(result, 0).value().ContainsRaw());
  }
}

TEST(SplineWorkflowTest, TheLThetaPathAloneAndBadMethods) {
  workflows::SplineOptions options = ThreeKeyframes("ltheta");
  options.evaluate_energy = false;
  const workflows::SplineResult alone = workflows::RunSpline(options);
  EXPECT_TRUE(alone.status.ok()) << alone.status.message;
  EXPECT_FALSE(alone.energy_evaluated);
  EXPECT_EQ(alone.path().size(), 5u);
  const std::string json = workflows::ToJson(alone, 0).str();
  EXPECT_NE(json.find("\"termination\": \"not optimised\""),
            std::string::npos)
      << json;
  options.init = SplineInit::kGeodesic;
  options.option_prefix = "--";
  try {
    workflows::RunSpline(options);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--init geodesic needs --method nonlinear (--method ltheta is "
              "the LΘA spline itself)");
  }
  options.method = "cubic";
  EXPECT_THROW(workflows::RunSpline(options), InputError);
}

// The CLI runs the same workflow: its E_K is RunGeodesic's to the digit,
// and a log or pca whose solve misses its criterion exits 4 with one line
// naming the workflow's solve.
class WorkflowCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::TempDir();
    const workflows::PcaOptions sheets = FourSheets();
    const char* const names[] = {"sheet", "rolled_0.6", "rolled_1",
                                 "rolled_2"};
    for (int i = 0; i < 4; ++i) {
      WriteMesh(Mesh{sheets.shapes[i], sheets.reference.faces},
                File(names[i]));
    }
  }
  std::string File(const std::string& name) const {
    return dir_ + "/" + name + ".ply";
  }
  std::string dir_;
};

TEST_F(WorkflowCliTest, GeodesicPrintsTheWorkflowsEnergy) {
  std::string out, err;
  ASSERT_EQ(testing::RunCli("geodesic --start " + File("sheet") + " --end " +
                                File("rolled_0.6") + " --steps 4 --output " +
                                dir_ + "/g --json --quiet",
                            &out, &err),
            0)
      << err;
  const workflows::GeodesicResult result =
      workflows::RunGeodesic(BentSheetGeodesic());
  EXPECT_NE(out.find("\"path_energy\": " +
                     JsonObject::Number(result.path_energy()) + ","),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("\"energy_split\": " +
                     workflows::EnergySplitJson(result.energy_split).str()),
            std::string::npos)
      << out;
}

TEST_F(WorkflowCliTest, PcaWritesTheWorkflowsShapes) {
  std::string out, err;
  ASSERT_EQ(testing::RunCli("pca --modes 1 --inputs " + File("sheet") + "," +
                                File("rolled_0.6") + "," + File("rolled_1") +
                                "," + File("rolled_2") + " --output " + dir_ +
                                "/p --json --quiet",
                            &out, &err),
            0)
      << err;
  workflows::PcaOptions options = FourSheets();
  const workflows::PcaResult result = workflows::RunPca(options);
  ASSERT_TRUE(result.status.ok());
  for (const char* name : {"mean", "mode_1_minus", "mode_1_plus"}) {
    const Mesh written = ReadMesh(dir_ + "/p/" + name + ".ply");
    ASSERT_NE(result.Shape(name), nullptr) << name;
    EXPECT_EQ((written.positions - *result.Shape(name)).cwiseAbs().maxCoeff(),
              0.0)
        << name;
  }
  EXPECT_NE(out.find("\"eigenvalues\": [" +
                     JsonObject::Number(result.model->eigenvalues(0))),
            std::string::npos)
      << out;
}

TEST_F(WorkflowCliTest, UnconvergedSolvesExitFourWithOneLine) {
  struct Case {
    std::string args;
    std::string line;  // how stderr begins
  };
  const std::string inputs = File("sheet") + "," + File("rolled_0.6") + "," +
                             File("rolled_1") + "," + File("rolled_2");
  const std::vector<Case> cases = {
      {"log --start " + File("sheet") + " --end " + File("rolled_0.6") +
           " --steps 4 --output " + dir_ + "/log.ply",
       "shellspace log: not converged: log: the geodesic: |grad| "},
      {"mean --inputs " + inputs + " --output " + dir_ + "/mean.ply",
       "shellspace mean: not converged: elastic mean: |grad| "},
      {"pca --modes 1 --inputs " + inputs + " --output " + dir_ + "/pca",
       "shellspace pca: not converged: the elastic mean: |grad| "},
  };
  for (const Case& c : cases) {
    std::string out, err;
    EXPECT_EQ(testing::RunCli(c.args + " --max_iterations 1 --quiet", &out,
                              &err),
              4)
        << c.args << "\n" << err;
    EXPECT_EQ(err.rfind(c.line, 0), 0u) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  }
}

// The status of failure lines and a stop, and of a solve that could not run.
TEST(SolveStatusTest, CodesAndOneLineMessages) {
  struct Case {
    std::vector<std::string> failures;
    bool stopped;
    SolveStatus::Code code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{}, false, SolveStatus::Code::kConverged, ""},
      {{"a: x"}, false, SolveStatus::Code::kNotConverged, "a: x"},
      {{"a: x", "b: y"}, false, SolveStatus::Code::kNotConverged, "a: x; b: y"},
      {{}, true, SolveStatus::Code::kStopped, "stopped by request"},
      {{"a: x"}, true, SolveStatus::Code::kStopped, "a: x"},
  };
  for (const Case& c : cases) {
    const SolveStatus status = workflows::StatusOf(c.failures, c.stopped);
    EXPECT_EQ(status.code, c.code) << c.message;
    EXPECT_EQ(status.message, c.message);
    EXPECT_EQ(status.failures, c.failures);
    EXPECT_EQ(status.ok(), c.code == SolveStatus::Code::kConverged);
  }
  const SolveStatus failed =
      workflows::FailedStatus("elastic mean", "Residual evaluation failed.");
  EXPECT_TRUE(failed.failed());
  EXPECT_FALSE(failed.ok());
  EXPECT_EQ(failed.message, "elastic mean failed: Residual evaluation failed.");
  EXPECT_STREQ(workflows::SolveStatusName(failed.code), "failed");
}

}  // namespace
}  // namespace shellspace
