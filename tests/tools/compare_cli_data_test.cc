// `shellspace compare`: the numbers of CompareShapes, exit 0 when equal
// within the tolerances, 1 with one "differ" line otherwise, and one error
// line for mismatched sides.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/shape_comparison.h"
#include "tests/tools/cli_test_support.h"

namespace shellspace {
namespace {

int Lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

TEST(CompareCliTest, TwoMeshes) {
  std::string out, err;
  ASSERT_EQ(RunCli("compare --json --a " + kSquare + " --b " + kSquare, &out, &err), 0)
      << err;
  EXPECT_TRUE(testing::Bool(out, "equal")) << out;
  EXPECT_EQ(Number(out, "max_distance"), 0.0);
  EXPECT_EQ(RunCli("compare --json --a " + kSquare + " --b " + kBent, &out, &err), 1);
  // W[a, b] with the CLI's default material.
  const Mesh square = testing::LoadData("simple/square4.ply");
  const testing::ShellPair pair =
      testing::LoadPair("simple/square4.ply", "simple/square4_bent.ply",
                        testing::CliDefaultMaterial(square));
  const ShapeComparison c =
      CompareShapes(pair.space, {pair.start.positions}, {pair.end.positions});
  EXPECT_NEAR(Number(out, "max_distance"), c.max_distance, 1e-12) << out;
  EXPECT_NEAR(Number(out, "energy_a_to_b"), c.energy_a_to_b,
              1e-12 * c.energy_a_to_b);
  EXPECT_FALSE(testing::Bool(out, "equal"));
  EXPECT_EQ(Lines(err), 1) << err;
  EXPECT_NE(err.find("compare: differ: relative max distance"), std::string::npos)
      << err;
  // A tolerance above the distance makes them equal.
  EXPECT_EQ(RunCli("compare --quiet --tolerance 10 --a " + kSquare + " --b " + kBent,
                   &out, &err),
            0)
      << err;
}

TEST(CompareCliTest, TwoPathDirectories) {
  const std::string dir = testing::TempDir();
  for (const char* run : {"one", "two"}) {
    std::string err;
    ASSERT_EQ(RunCli("geodesic --quiet --steps 4 --start " + kSquare + " --end " +
                         kBent + " --output " + dir + "/" + run,
                     nullptr, &err),
              0)
        << err;
  }
  std::string out, err;
  // Two runs of one deterministic solve: equal to the last digit.
  ASSERT_EQ(RunCli("compare --json --tolerance 0 --energy_tolerance 0 --a " + dir +
                       "/one --b " + dir + "/two",
                   &out, &err),
            0)
      << err << out;
  EXPECT_EQ(Number(out, "frames"), 5);
  EXPECT_EQ(Number(out, "relative_energy_difference"), 0.0);
  // Against the linear path: the same ends, another E_K.
  ShellPath linear = LinearPath(ReadMesh(kSquare).positions,
                                ReadMesh(kBent).positions, 4);
  WriteFrames(dir + "/linear", ReadMesh(kSquare).faces, linear);
  EXPECT_EQ(RunCli("compare --json --a " + dir + "/one --b " + dir + "/linear",
                   &out, &err),
            1);
  EXPECT_GT(Number(out, "relative_energy_difference"), 1e-6) << out;
  EXPECT_NE(err.find("differ"), std::string::npos) << err;
  // Mismatched frame counts: one error line.
  EXPECT_EQ(RunCli("compare --a " + dir + "/one --b " + kSquare, &out, &err), 1);
  EXPECT_EQ(Lines(err), 1) << err;
  EXPECT_NE(err.find("frame(s)"), std::string::npos) << err;
}

}  // namespace
}  // namespace shellspace
