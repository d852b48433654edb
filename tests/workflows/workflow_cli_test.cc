// The CLI runs the workflows (shellspace/workflows/) on procedural sheets
// written as PLY files (tests/testing/workflow_sheets.h): its E_K and its
// PCA shapes are the workflows' to the digit, and an unconverged log or
// pca exits 4 with one line naming the workflow's solve; and the solve
// statuses' codes and one-line messages.
#include <gtest/gtest.h>

#include <string>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/workflows/geodesic.h"
#include "shellspace/workflows/pca.h"
#include "tests/testing/cli_output.h"
#include "tests/testing/test_support.h"
#include "tests/testing/workflow_sheets.h"

namespace shellspace {
namespace {

using testing::BentSheetGeodesic;
using testing::FourSheets;
using workflows::SolveStatus;

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
