// The `mean` and `pca` verbs on the shared spheres: the shape, the JSON
// report and the files they write, the leave-one-out table, the warning
// about a far input, mode shapes without an EXP solution skipped, and bad
// inputs that fail with one line and no output.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "tests/testing/cli_output.h"
#include "tests/testing/statistics_fixtures.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::DataPath;
using testing::kSpheres;
using testing::LoadData;
using testing::LoadSpheres;
using testing::MakeSpace;
using testing::Number;
using testing::RunCli;
using testing::TempDir;

std::string SphereList(int count) {
  std::string list;
  for (int i = 0; i < count; ++i) {
    list += (i ? "," : "") + DataPath(kSpheres[i]);
  }
  return list;
}

TEST(StatisticsCliTest, MeanWritesTheShapeAndJson) {
  const std::string out = TempDir() + "/M.ply";
  std::string stdout_text, stderr_text;
  ASSERT_EQ(RunCli("mean --inputs " + SphereList(3) + " --output " + out +
                       " --json --quiet",
                   &stdout_text, &stderr_text),
            0)
      << stderr_text;
  EXPECT_TRUE(std::filesystem::exists(out));
  EXPECT_NE(stdout_text.find("\"energy\""), std::string::npos);
  // The written shape is the library's elastic mean, with the CLI's default
  // material: eta = kDefaultRelativeEta (1e-4) x the area of the first input.
  std::vector<Positions> shapes = LoadSpheres();
  shapes.resize(3);
  const Mesh first = LoadData(kSpheres[0]);
  ShellMaterial material;
  material.eta = kDefaultRelativeEta * SurfaceArea(first);
  EXPECT_NEAR(Number(stdout_text, "eta"), material.eta, 1e-15 * material.eta);
  const ElasticMeanResult mean =
      ComputeElasticMean(MakeSpace(first, material), shapes, SolverSettings{});
  EXPECT_LT(RelativeDistanceUpToRigidMotion(ReadMesh(out).positions, mean.mean),
            1e-6);
}

// Runs `pca` with two modes of the four spheres into `dir`, with `options`;
// returns its exit status.
int RunPcaOfSpheres(const std::string& dir, const std::string& options,
                    std::string* stdout_text, std::string* stderr_text) {
  return RunCli("pca --inputs " + SphereList(4) + " --modes 2 --output " + dir +
                    " " + options,
                stdout_text, stderr_text);
}

TEST(StatisticsCliTest, PcaWritesModesAndLeaveOneOutTable) {
  const std::string dir = TempDir() + "/pca";
  std::string stdout_text, stderr_text;
  ASSERT_EQ(RunPcaOfSpheres(dir, "--baseline procrustes --loo --json --quiet",
                            &stdout_text, &stderr_text),
            0)
      << stderr_text;
  for (const char* name :
       {"mean.ply", "mode_1_minus.ply", "mode_1_plus.ply", "mode_2_plus.ply",
        "procrustes_mean.ply", "procrustes_mode_2_minus.ply", "pca.json"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + name)) << name;
  }
  EXPECT_NE(stdout_text.find("\"eigenvalues\""), std::string::npos);
  EXPECT_NE(stdout_text.find("\"leave_one_out\""), std::string::npos);
  EXPECT_NE(stdout_text.find("\"procrustes_vertex_error\""), std::string::npos);
  EXPECT_NE(stdout_text.find("\"log_iterations\""), std::string::npos);
}

TEST(StatisticsCliTest, MeanWarnsAboutAFarInput) {
  // The four spheres twice over and one blown up to twice its size: the big
  // one is far (W[S, mean] more than 10 times the median), the others are
  // not.
  const std::string big = TempDir() + "/big.ply";
  Mesh sphere = LoadData(kSpheres[1]);
  sphere.positions *= 2.0;
  WriteMesh(sphere, big);
  const std::string out = TempDir() + "/far_mean.ply";
  std::string stdout_text, stderr_text;
  ASSERT_EQ(RunCli("mean --inputs " + SphereList(4) + "," + SphereList(4) +
                       "," + big +
                       " --output " + out + " --json",
                   &stdout_text, &stderr_text),
            0)
      << stderr_text;
  EXPECT_NE(stderr_text.find("warning: input " + big + " is far"),
            std::string::npos)
      << stderr_text;
  EXPECT_NE(stdout_text.find("\"far_inputs\": [\"" + big + "\"]"),
            std::string::npos)
      << stdout_text;
  ASSERT_EQ(RunCli("mean --inputs " + SphereList(4) + " --output " + out +
                       " --json",
                   &stdout_text, &stderr_text),
            0);
  EXPECT_EQ(stderr_text.find("warning"), std::string::npos) << stderr_text;
  EXPECT_NE(stdout_text.find("\"far_inputs\": []"), std::string::npos);
}

TEST(StatisticsCliTest, PcaSkipsModeShapesWithoutAnExpSolution) {
  // At 40 standard deviations the EXP shots of the sphere modes break down
  // (no solution of a step near the extrapolation, for K = 4, 8, 16): those
  // shapes are not written, listed in the JSON, and the rest is written.
  const std::string dir = TempDir() + "/pca_far";
  std::string stdout_text, stderr_text;
  ASSERT_EQ(RunPcaOfSpheres(dir, "--amplitude 40 --eta 0.01 --json",
                            &stdout_text, &stderr_text),
            0)
      << stderr_text;
  const auto begin = stdout_text.find("\"failed_mode_shapes\": [");
  ASSERT_NE(begin, std::string::npos) << stdout_text;
  const std::string failed =
      stdout_text.substr(begin, stdout_text.find(']', begin) - begin);
  EXPECT_NE(failed.find(".ply"), std::string::npos) << failed;  // some
  for (const char* name : {"mode_1_minus.ply", "mode_1_plus.ply",
                           "mode_2_minus.ply", "mode_2_plus.ply"}) {
    const bool listed = failed.find(name) != std::string::npos;
    EXPECT_EQ(std::filesystem::exists(dir + "/" + name), !listed) << name;
    EXPECT_EQ(stderr_text.find(std::string(name) + " not written") !=
                  std::string::npos,
              listed)
        << name;
  }
  EXPECT_TRUE(std::filesystem::exists(dir + "/mean.ply"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/pca.json"));
}

TEST(StatisticsCliTest, BadInputsFailWithOneLineAndNoOutput) {
  const std::string base = TempDir();
  struct Case {
    std::string args, expected;
  };
  const std::vector<Case> cases = {
      {"mean --inputs " + DataPath(kSpheres[0]) + "," +
           DataPath("plate/plate121.ply") + " --output " + base + "/a.ply",
       "plate121"},
      {"mean --inputs " + DataPath(kSpheres[0]) + ",missing.ply --output " +
           base + "/b.ply",
       "missing.ply"},
      {"mean --output " + base + "/c.ply", "--inputs"},
      {"pca --inputs " + SphereList(4) + " --modes 0 --output " + base + "/d",
       "--modes"},
      {"pca --inputs " + SphereList(3) + " --modes 3 --output " + base + "/e",
       "--modes"},
      {"pca --inputs " + SphereList(3) +
           " --modes 1 --baseline linear "
           "--output " +
           base + "/f",
       "--baseline"},
      {"pca --inputs " + SphereList(2) + " --modes 1 --loo --output " + base +
           "/g",
       "at least 3"},
      {"pca --inputs " + SphereList(3) + " --modes 1 --exp_steps 0 --output " +
           base + "/h",
       "--exp_steps"},
      {"mean --inputs " + SphereList(3) + " --threads 0 --output " + base +
           "/i.ply",
       "--threads"},
  };
  for (const Case& c : cases) {
    std::string stdout_text, stderr_text;
    EXPECT_EQ(RunCli(c.args + " --quiet", &stdout_text, &stderr_text), 1)
        << c.args;
    EXPECT_NE(stderr_text.find(c.expected), std::string::npos) << c.args << "\n"
                                                               << stderr_text;
    EXPECT_EQ(std::count(stderr_text.begin(), stderr_text.end(), '\n'), 1)
        << stderr_text;
  }
  for (const char* name :
       {"a.ply", "b.ply", "c.ply", "d", "e", "f", "g", "h", "i.ply"}) {
    EXPECT_FALSE(std::filesystem::exists(base + "/" + name)) << name;
  }
}

}  // namespace
}  // namespace shellspace
