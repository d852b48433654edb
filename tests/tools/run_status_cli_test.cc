// The verdict of the solving verbs (tools/run_status.h): a run that misses
// its stopping criterion writes its outputs and its --json summary with
// "converged": false, prints one line naming what did not converge and
// exits 4; --allow_unconverged turns that line into a warning and exits 0.
// No raw log line of the solvers reaches stderr.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "shellspace/tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::DataPath;
using testing::RunCli;
using testing::TempDir;

const std::string kSquare = DataPath("simple/square4.ply");
const std::string kBent = DataPath("simple/square4_bent.ply");

double Number(const std::string& json, const std::string& key) {
  const std::string needle = "\"" + key + "\": ";
  const auto at = json.find(needle);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(json.c_str() + at + needle.size(), nullptr);
}

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// One line on stderr, "shellspace VERB: not converged: ..." naming `what`.
void ExpectOneNotConvergedLine(const std::string& err, const std::string& verb,
                               const std::string& what) {
  const std::vector<std::string> lines = Lines(err);
  ASSERT_EQ(lines.size(), 1u) << err;
  EXPECT_EQ(lines[0].rfind("shellspace " + verb + ": not converged: ", 0), 0u)
      << err;
  EXPECT_TRUE(Has(lines[0], what)) << err;
}

TEST(RunStatusCliTest, GeodesicCappedAtOneIterationExitsFour) {
  const std::string dir = TempDir();
  const std::string args = "geodesic --quiet --json --steps 4 --start " +
                           kSquare + " --end " + kBent +
                           " --max_iterations 1 --output " + dir + "/g";
  std::string out, err;
  EXPECT_EQ(RunCli(args, &out, &err), 4) << err;
  ExpectOneNotConvergedLine(err, "geodesic", "geodesic: |grad| ");
  EXPECT_TRUE(Has(out, "\"converged\": false")) << out;
  EXPECT_EQ(Number(out, "iterations"), 1) << out;  // one LM iteration in all
  const double g0 = Number(out, "initial_gradient_norm");
  const double g = Number(out, "final_gradient_norm");
  EXPECT_GT(g, 1e-8 * std::max(1.0, g0)) << out;
  EXPECT_NEAR(Number(out, "relative_gradient_norm"), g / g0, 1e-15);
  // The outputs are written all the same.
  EXPECT_TRUE(std::filesystem::exists(dir + "/g/shape_004.ply"));

  // Accepted: exit 0, the same line as a warning.
  EXPECT_EQ(RunCli(args + " --allow_unconverged", &out, &err), 0) << err;
  const std::vector<std::string> lines = Lines(err);
  ASSERT_EQ(lines.size(), 1u) << err;
  EXPECT_EQ(lines[0].rfind("shellspace geodesic: warning: not converged: ", 0),
            0u)
      << err;
}

TEST(RunStatusCliTest, MeanCappedAtOneIterationSaysMaxIterations) {
  const std::string dir = TempDir();
  std::string out, err;
  EXPECT_EQ(RunCli("mean --quiet --json --inputs " + kSquare + "," + kBent +
                       " --max_iterations 1 --output " + dir + "/m.ply",
                   &out, &err),
            4)
      << err;
  ExpectOneNotConvergedLine(err, "mean", "(max iterations)");
  EXPECT_TRUE(Has(out, "\"converged\": false")) << out;
  EXPECT_TRUE(Has(out, "\"termination\": \"max iterations\"")) << out;
  EXPECT_EQ(Number(out, "iterations"), 1) << out;
  EXPECT_EQ(Number(out, "lm_iterations"), 1) << out;
  EXPECT_EQ(Number(out, "newton_iterations"), 0) << out;
  EXPECT_GT(Number(out, "final_gradient_norm"), Number(out, "gradient_target"))
      << out;
  EXPECT_TRUE(std::filesystem::exists(dir + "/m.ply"));
}

TEST(RunStatusCliTest, ConvergedRunsExitZeroAndSayConverged) {
  const std::string dir = TempDir();
  std::string out, err;
  EXPECT_EQ(RunCli("mean --quiet --json --inputs " + kSquare + "," + kBent +
                       " --output " + dir + "/m.ply",
                   &out, &err),
            0)
      << err;
  EXPECT_TRUE(Has(out, "\"converged\": true")) << out;
  EXPECT_TRUE(Has(out, "\"termination\": \"converged\"")) << out;
  EXPECT_EQ(err, "");
  EXPECT_EQ(RunCli("geodesic --quiet --json --steps 4 --start " + kSquare +
                       " --end " + kBent + " --output " + dir + "/g",
                   &out, &err),
            0)
      << err;
  EXPECT_TRUE(Has(out, "\"converged\": true")) << out;
  EXPECT_TRUE(Has(out, "\"uneven_steps\": false")) << out;
  EXPECT_LT(Number(out, "step_energy_ratio"), 1.2) << out;  // K = 4: 1.11
  EXPECT_EQ(err, "");
}

TEST(RunStatusCliTest, RegressionCappedAtOneIterationExitsFour) {
  const std::string dir = TempDir();
  std::string out, err;
  EXPECT_EQ(RunCli("regress --quiet --json --inputs " + kSquare + "," + kBent +
                       " --at 0,2 --steps 2 --sigma 0.5 --max_iterations 1 "
                       "--output " + dir + "/r",
                   &out, &err),
            4)
      << err;
  ExpectOneNotConvergedLine(err, "regress", "after 1 L-BFGS iterations");
  EXPECT_TRUE(Has(out, "\"converged\": false")) << out;
  EXPECT_EQ(Number(out, "iterations"), 1) << out;
  EXPECT_GT(Number(out, "relative_gradient_norm"), 1e-8) << out;
}

}  // namespace
}  // namespace shellspace
