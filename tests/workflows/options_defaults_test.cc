// One default per option: the library's Options and settings structs hold
// the same defaults as the CLI's flags (docs/cli.md, generated from the
// flag tables and checked current by ctest docs_cli_reference; the Python
// keywords are checked against the same file by
// tests/python/test_docstrings.py), so a default changed in one place and
// not the other fails here.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/problems/splines/spline_initial_path.h"
#include "shellspace/problems/statistics/shell_pca.h"
#include "shellspace/solvers/solver_settings.h"
#include "shellspace/workflows/geodesic.h"
#include "shellspace/workflows/solve_choice_words.h"
#include "shellspace/workflows/pca.h"
#include "shellspace/workflows/regress.h"
#include "shellspace/workflows/shoot.h"
#include "shellspace/workflows/spline.h"
#include "shellspace/workflows/transport.h"

namespace shellspace {
namespace {

using Defaults = std::map<std::string, std::map<std::string, std::string>>;

// {verb: {flag: the text after "default: " up to "; valid"}}.
Defaults ReadCliDefaults(std::istream& in) {
  Defaults defaults;
  std::string line, verb, flag;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) {
      verb = line.substr(3);
      flag.clear();
    } else if (line.rfind("  --", 0) == 0) {
      flag = line.substr(4, line.find(' ', 4) - 4);
    } else if (line.rfind("      default: ", 0) == 0 && !flag.empty()) {
      std::string value = line.substr(15);
      value = value.substr(0, value.find("; valid"));
      defaults[verb][flag] = value;
    }
  }
  return defaults;
}

const Defaults& CliDefaults() {
  static const Defaults defaults = [] {
    std::ifstream in(std::string(SHELLSPACE_SOURCE_DIR) + "/docs/cli.md");
    return ReadCliDefaults(in);
  }();
  return defaults;
}

// The flag's default as the number or word the library holds.
::testing::AssertionResult SameDefault(const std::string& verb,
                                       const std::string& flag,
                                       const std::string& library) {
  const auto v = CliDefaults().find(verb);
  if (v == CliDefaults().end() || !v->second.count(flag))
    return ::testing::AssertionFailure() << "no --" << flag << " of " << verb;
  const std::string& cli = v->second.at(flag);
  if (cli == library) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << verb << " --" << flag << ": the CLI's default " << cli
         << ", the library's " << library;
}
::testing::AssertionResult SameDefault(const std::string& verb,
                                       const std::string& flag,
                                       double library) {
  const auto v = CliDefaults().find(verb);
  if (v == CliDefaults().end() || !v->second.count(flag))
    return ::testing::AssertionFailure() << "no --" << flag << " of " << verb;
  const std::string& cli = v->second.at(flag);
  char* end = nullptr;
  const double value = std::strtod(cli.c_str(), &end);
  if (end != cli.c_str() && *end == '\0' && value == library)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << verb << " --" << flag << ": the CLI's default " << cli
         << ", the library's " << library;
}

TEST(OptionsDefaultsTest, TheReaderFindsFlagsAndDefaults) {
  std::istringstream in(
      "## geodesic\n\n```\nflags of geodesic:\n"
      "  --steps (int32)  number of time steps\n"
      "      default: 8; valid: an integer in [1, 100000]\n"
      "  --init (string)  the initial path\n      default: auto\n");
  const Defaults d = ReadCliDefaults(in);
  EXPECT_EQ(d.at("geodesic").at("steps"), "8");
  EXPECT_EQ(d.at("geodesic").at("init"), "auto");
  ASSERT_GT(CliDefaults().size(), 15u);  // the real file was read
}

TEST(OptionsDefaultsTest, ACliDefaultOtherThanTheLibrarysFails) {
  EXPECT_FALSE(SameDefault("geodesic", "steps", 9.0));
  EXPECT_FALSE(SameDefault("geodesic", "multires", "off"));
  EXPECT_FALSE(SameDefault("geodesic", "no_such_flag", 1.0));
}

TEST(OptionsDefaultsTest, GeodesicLogShootTransport) {
  const workflows::GeodesicOptions geodesic;
  for (const char* verb : {"geodesic", "log"}) {
    EXPECT_TRUE(SameDefault(verb, "steps", geodesic.steps));
    EXPECT_TRUE(SameDefault(verb, "linear_solver",
                            PathLinearSolverWord(geodesic.linear_solver)));
    EXPECT_TRUE(SameDefault(verb, "lm", GeodesicLmWord(geodesic.lm)));
    EXPECT_TRUE(SameDefault(verb, "init", GeodesicInitName(geodesic.init)));
  }
  EXPECT_TRUE(SameDefault("geodesic", "multires",
                          MultiresolutionWord(geodesic.multires)));
  EXPECT_TRUE(SameDefault("shoot", "steps", workflows::ShootOptions().steps));
  EXPECT_TRUE(SameDefault("transport", "epsilon",
                          workflows::TransportOptions().epsilon));
}

TEST(OptionsDefaultsTest, SplineRegressPca) {
  const workflows::SplineOptions spline;
  EXPECT_TRUE(SameDefault("spline", "steps", spline.steps));
  EXPECT_TRUE(SameDefault("spline", "method",
                          workflows::SplineMethodName(spline.method)));
  EXPECT_TRUE(SameDefault("spline", "init", SplineInitName(spline.init)));
  const workflows::RegressOptions regress;
  EXPECT_TRUE(SameDefault("regress", "steps", regress.steps));
  EXPECT_TRUE(SameDefault("regress", "sigma", regress.sigma));
  const workflows::PcaOptions pca;
  EXPECT_TRUE(SameDefault("pca", "modes", pca.modes));
  EXPECT_TRUE(SameDefault("pca", "amplitude", pca.amplitude));
  const ShellPcaOptions shell_pca;
  EXPECT_TRUE(SameDefault("pca", "displacement",
                          DisplacementKindName(shell_pca.displacement)));
  EXPECT_TRUE(SameDefault("pca", "log_steps", shell_pca.steps));
  EXPECT_TRUE(SameDefault("pca", "max_exp_steps", shell_pca.max_exp_steps));
}

// The material and the solver settings every solving verb shares.
TEST(OptionsDefaultsTest, MaterialAndSolverOfEverySolvingVerb) {
  const ShellMaterial material;
  const SolverSettings settings;
  for (const char* verb : {"geodesic", "log", "shoot", "transport", "spline",
                           "regress", "mean", "pca"}) {
    EXPECT_TRUE(SameDefault(verb, "mu", material.mu));
    EXPECT_TRUE(SameDefault(verb, "lambda", material.lambda));
    EXPECT_TRUE(SameDefault(verb, "relative_eta", kDefaultRelativeEta));
    EXPECT_TRUE(
        SameDefault(verb, "bending", BendingModelName(material.bending_model)));
    EXPECT_TRUE(SameDefault(verb, "tolerance", settings.gradient_tolerance));
    EXPECT_TRUE(SameDefault(verb, "max_iterations", settings.max_iterations));
    EXPECT_TRUE(SameDefault(verb, "threads", settings.num_threads));
  }
}

}  // namespace
}  // namespace shellspace
