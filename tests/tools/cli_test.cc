// The per-verb flags of the `shellspace` binary: a verb rejects another
// verb's flag, `--help` lists only the verb's flags and the library's
// defaults, out-of-range values are refused by name, nothing is left
// behind; and `branching construct` against its closed form (procedural,
// no mesh read).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "shellspace/problems/branching/simulation.h"
#include "tests/tools/cli_test_support.h"

namespace shellspace {
namespace {

// `geodesic --start kSquare --end kBent --output OUTPUT`, for the caller to
// append further flags.
std::string GeodesicInto(const std::string& output) {
  return "geodesic --start " + kSquare + " --end " + kBent + " --output " +
         output;
}

TEST(CliTest, BranchingConstructKmIsTheClosedForm) {
  const std::string dir = TempDir() + "/km";
  const std::string json =
      RunOk("branching construct --json --family km --output " + dir);
  // km is the psi-junction cell: with the optimal per-column shift its
  // constant is 7.546124, with u = 0 on the
  // cell edges 3(1 + 2 cos(pi/9)) = 8.638156.
  const double constant = Number(json, "constant");
  EXPECT_NEAR(constant, 7.546124092461, 1e-9) << json;
  EXPECT_NEAR(constant / Number(json, "km_shifted_constant_closed_form"), 1,
              1e-12)
      << json;
  EXPECT_NEAR(Number(json, "constant_zero_edge"),
              3 * (1 + 2 * std::cos(M_PI / 9)), 1e-9)
      << json;
  // constant = (elastic + interfacial) / (eps^(2/3) L^(1/3)), eps = 1e-3
  // (the verb's default), L = 1.
  EXPECT_EQ(Number(json, "epsilon"), 1e-3);
  const double total = Number(json, "elastic") + Number(json, "interfacial");
  EXPECT_NEAR(constant, total / std::pow(1e-3, 2.0 / 3.0), 1e-9 * constant);
  EXPECT_EQ(DirectoryListing(dir),
            (std::vector<std::string>{"pattern.png", "summary.json"}));
  EXPECT_EQ(Slurp(dir + "/summary.json"), json);
}

// A command line the CLI refuses, and a part of the one line it prints.
struct Refusal {
  std::string args, message;
};

// Runs every refusal's command line: each exits with `code` and prints one
// line on stderr holding its message; nothing is left in `dir`.
void ExpectRefusals(const std::vector<Refusal>& refusals, int code,
                    const std::string& dir) {
  for (const Refusal& r : refusals) {
    std::string err;
    EXPECT_EQ(RunCli(r.args, nullptr, &err), code) << r.args;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find(r.message), std::string::npos) << err;
  }
  EXPECT_TRUE(DirectoryListing(dir).empty());
}

TEST(CliTest, AVerbRejectsAnotherVerbsFlag) {
  const std::string dir = TempDir();
  const std::string geodesic = GeodesicInto(dir + "/g");
  ExpectRefusals(
      {
          {geodesic + " --inputs " + kSquare, "--inputs is not a flag of"},
          {geodesic + " --width 10", "--width is not a flag of"},
          {"energy --reference " + kSquare + " --deformed " + kSquare +
               " --steps 3",
           "--steps is not a flag of"},
          {"branching construct --output " + dir + "/b --nx 16",
           "--nx is not a flag of"},
          // Set to the default value: still not a flag of the verb.
          {"render --input " + kSquare + " --output " + dir +
               "/r.png --epsilon 1",
           "--epsilon is not a flag of"},
      },
      2, dir);
}

// The flags listed by `shellspace ARGS --help`.
std::set<std::string> HelpFlags(const std::string& args, std::string* text) {
  EXPECT_EQ(RunCli(args + " --help", text), 0) << args;
  std::set<std::string> flags;
  std::istringstream lines(*text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("  --", 0) != 0) continue;
    flags.insert(line.substr(4, line.find(' ', 4) - 4));
  }
  return flags;
}

TEST(CliTest, HelpListsOnlyTheVerbsFlags) {
  std::string text;
  const std::set<std::string> geodesic = HelpFlags("geodesic", &text);
  const std::set<std::string> expected = {"start",
                                          "end",
                                          "steps",
                                          "output",
                                          "mask",
                                          "png",
                                          "gltf",
                                          "html",
                                          "report",
                                          "mu",
                                          "lambda",
                                          "eta",
                                          "relative_eta",
                                          "bending",
                                          "membrane",
                                          "tolerance",
                                          "max_iterations",
                                          "threads",
                                          "quiet",
                                          "json",
                                          "multires",
                                          "linear_solver",
                                          "lm",
                                          "init",
                                          "time_limit",
                                          "minloglevel",
                                          "allow_unconverged",
                                          "up",
                                          "labels",
                                          "color"};
  EXPECT_EQ(geodesic, expected) << text;
  // Default and valid range of a numeric flag.
  EXPECT_NE(text.find("default: 8; valid: an integer in [1, 100000]"),
            std::string::npos)
      << text;
  // --epsilon means one thing in transport, another in branching.
  std::string transport, branching;
  EXPECT_TRUE(HelpFlags("transport", &transport).count("epsilon"));
  EXPECT_TRUE(HelpFlags("branching simulate", &branching).count("epsilon"));
  EXPECT_NE(transport.find("transport step epsilon"), std::string::npos);
  EXPECT_NE(branching.find("twin-boundary"), std::string::npos);
  EXPECT_EQ(transport.find("twin-boundary"), std::string::npos);
  EXPECT_NE(branching.find("default: 0.001"), std::string::npos) << branching;
  EXPECT_FALSE(HelpFlags("branching simulate", &branching).count("family"));
  EXPECT_TRUE(HelpFlags("branching construct", &branching).count("family"));
  // Every verb's help works and lists --json or --output.
  for (const char* verb :
       {"energy", "deform", "shoot", "log", "spline", "regress", "mean", "pca",
        "render", "export", "demo"}) {
    const std::set<std::string> flags = HelpFlags(verb, &text);
    EXPECT_TRUE(flags.count("json") || flags.count("output")) << verb;
    EXPECT_FALSE(flags.count("inputs") && flags.count("start")) << verb;
  }
}

// The default `--help` prints for `flag` ("" if none is printed).
std::string HelpDefault(const std::string& text, const std::string& flag) {
  const size_t line = text.find("\n  --" + flag + " (");
  if (line == std::string::npos) return "";
  const size_t begin = text.find("default: ", line);
  if (begin == std::string::npos) return "";
  const size_t end = text.find_first_of(";\n", begin);
  return text.substr(begin + 9, end - begin - 9);
}

// `branching simulate`'s flag defaults are the library's SimulationSettings
// (the Python keywords take theirs from it; --height 0 stands for its 0.5).
TEST(CliTest, BranchingSimulateDefaultsAreTheLibrarys) {
  std::string text;
  HelpFlags("branching simulate", &text);
  const branching::SimulationSettings library;
  const auto str = [](auto value) {
    std::ostringstream out;
    out << value;
    return out.str();
  };
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"epsilon", str(library.epsilon)},
      {"length", str(library.length)},
      {"nx", str(library.nx)},
      {"ny", str(library.ny)},
      {"init", library.init},
      {"delta", str(library.delta)},
      {"grading", str(library.grading)},
      {"continuation", str(library.continuation)},
      {"periods", str(library.periods)},
      {"init_seed", str(library.seed)},
      {"lm_iterations", str(library.max_iterations)}};
  for (const auto& [flag, value] : expected) {
    EXPECT_EQ(HelpDefault(text, flag), value) << flag;
  }
  EXPECT_EQ(HelpDefault(text, "no_such_flag"), "");
  EXPECT_EQ(library.height, 0.5);
}

TEST(CliTest, OutOfRangeFlagsAreRejectedByName) {
  const std::string dir = TempDir();
  const std::string geodesic = GeodesicInto(dir + "/g");
  ExpectRefusals(
      {
          {geodesic + " --steps 0",
           "--steps must be an integer in [1, 100000], got 0"},
          {geodesic + " --tolerance 2",
           "--tolerance must be a number (0, 1), got 2"},
          {"energy --reference " + kSquare + " --deformed " + kSquare +
               " --eta nan",
           "--eta must be a number >= 0, got nan"},
          {"transport --path " + dir + " --variation " + kSquare +
               " --output " + dir + "/t --epsilon 0",
           "--epsilon must be a number > 0, got 0"},
          {"geodesic --end " + kBent + " --output " + dir + "/g",
           "--start is required"},
      },
      1, dir);
}

}  // namespace
}  // namespace shellspace
