// The CLI on bad masks of the shared square, on outputs that would
// overwrite an input or cannot be written, and on sizes above the memory
// bound: one line on stderr naming the file or the flag, a non-zero exit, no
// file created, no file changed (testing::ExpectRejected: the tree's names,
// sizes, modification times and content hashes before and after).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/testing/cli_output.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::ExpectRejected;

TEST(BadInputCliTest, EveryBadMaskIsRejectedWithOneLine) {
  const std::string dir = testing::TempDir();
  const std::string square = testing::DataPath("simple/square4.ply");
  std::filesystem::create_directory(dir + "/mask_dir");
  const auto write = [&dir](const std::string& name, const std::string& bytes) {
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  };
  const std::string masks[] = {
      dir + "/mask_dir",
      write("binary.txt", std::string("0\n\x00\x01\xfe\x7f", 6)),
      write("high.txt", "0\n\xff\xfe\n"),
      write("float.txt", "0\n2.5\n"),
      write("range.txt", "0\n5\n"),
  };
  for (const std::string& mask : masks) {
    ExpectRejected("deform --reference " + square + " --mask " + mask +
                       " --targets " + square + " --output " + dir + "/out.ply",
                   mask, dir);
  }
  // The error echoes no raw byte.
  std::string err;
  testing::RunCli("deform --reference " + square + " --mask " + masks[2] +
                      " --targets " + square + " --output " + dir + "/out.ply",
                  nullptr, &err);
  EXPECT_NE(err.find("high.txt:2: not a vertex index: '\\xff\\xfe'"),
            std::string::npos)
      << err;
  for (char c : err) EXPECT_TRUE(c == '\n' || (c >= 0x20 && c < 0x7f));
}

// Outputs that are inputs (also through a symbolic or a hard link, or
// spelled differently), directories that hold inputs or the user's files,
// outputs that cannot be written, sizes above the memory bound, bad
// --time_limit values: each rejected before any work.
TEST(BadInputCliTest, OutputsThatWouldOverwriteOrCannotBeWrittenAreRejected) {
  namespace fs = std::filesystem;
  const std::string d = testing::TempDir();
  const std::string a = d + "/a.ply", b = d + "/b.ply";
  fs::copy_file(testing::DataPath("simple/square4.ply"), a);
  fs::copy_file(testing::DataPath("simple/square4_bent.ply"), b);
  fs::create_symlink(a, d + "/link.ply");
  fs::create_hard_link(a, d + "/hard.ply");
  std::ofstream(d + "/mask.txt") << "1\n2\n3\n4\n";
  std::ofstream(d + "/file.txt") << "mine\n";
  fs::create_directory(d + "/mine");
  std::ofstream(d + "/mine/notes.txt") << "mine\n";
  // A previous run's output directory, and a transport input path.
  ASSERT_EQ(testing::RunCli("geodesic --quiet --steps 2 --start " + a +
                            " --end " + b + " --output " + d + "/g"),
            0);
  const std::string ab = " --start " + a + " --end " + b;
  const std::string deform = "deform --quiet --reference " + a + " --mask " +
                             d + "/mask.txt --targets " + b;
  struct Case {
    std::string args, message;
  };
  std::vector<Case> cases = {
      {deform + " --output " + a,
       "--output " + a + " is also the input --reference"},
      {deform + " --output " + d + "/link.ply",
       "is also the input --reference"},
      {deform + " --output " + d + "/mask.txt", "is also the input --mask"},
      {deform + " --output " + d + "/mine",
       "--output " + d + "/mine is a directory"},
      {"log --quiet" + ab + " --output " + b, "is also the input --end"},
      {"log --quiet" + ab + " --output " + d + "/hard.ply",
       "is also the input --start"},
      {"log --quiet" + ab + " --output " + d + "/./b.ply",
       "is also the input --end"},
      {"mean --quiet --inputs " + a + "," + b + " --output " + b,
       "is also the input --inputs"},
      {"render --input " + a + "," + b + " --output " + a,
       "is also the input --input"},
      {"render --input " + d + "/g --output " + d + "/g/shape_001.ply",
       "is also the input --input"},
      {"geodesic --quiet" + ab + " --output " + d + "/out --png " + a,
       "--png " + a + " is also the input --start"},
      {"geodesic --quiet" + ab + " --output " + d, "holds the input --start"},
      {"geodesic --quiet" + ab + " --output " + d + "/mine",
       "holds notes.txt, which no run writes"},
      {"geodesic --quiet" + ab + " --output " + d + "/file.txt",
       "file.txt is not a directory"},
      {"geodesic --quiet" + ab + " --output " + d + "/missing/out",
       "/missing does not exist"},
      {"geodesic --quiet" + ab + " --output " + d + "/out --png " + d +
           "/missing/s.png",
       "/missing does not exist"},
      {"geodesic --quiet" + ab + " --output " + d + "/g --png " + d +
           "/g/s.png",
       "is inside --output"},
      {"geodesic --quiet" + ab + " --output " + d + "/out --png " + d + "/mine",
       "is a directory"},
      {"geodesic --quiet" + ab + " --output " + d + "/out --png " + d +
           "/file.txt/s.png",
       "file.txt is not a directory"},
      {"shoot --quiet --first " + a + " --second " + b + " --output " + a,
       "holds the input --first"},
      {"transport --quiet --path " + d + "/g --variation " + a + " --output " +
           d + "/g",
       "holds the input --path"},
      {"transport --quiet --path " + d + "/g --variation " + a + " --output " +
           d + "/g/../g/",
       "holds the input --path"},
      {"transport --quiet --path " + d + "/g --variation " + a + " --output " +
           d,
       "holds the input --path"},
      {"spline --quiet --keyframes " + a + "," + b + "," + a +
           " --at 0,1,2 --steps 2 --output " + d,
       "holds the input --keyframes"},
      {"regress --quiet --inputs " + a + "," + b +
           " --at 0,2 --steps 2 --output " + d + "/g --png " + b,
       "is also the input --inputs"},
      {"pca --quiet --modes 1 --inputs " + a + "," + b + "," + a +
           " --output " + d,
       "holds the input --inputs"},
      {"demo --quiet --output " + d + "/mine", "holds notes.txt"},
      {"branching construct --output " + d + "/file.txt",
       "file.txt is not a directory"},
      {"geodesic --quiet" + ab + " --steps 10000 --output " + d + "/out",
       "--steps 10000 on 5 vertices needs about"},
      {"log --quiet" + ab + " --steps 100000 --output " + d + "/log.ply",
       "--steps 100000 on 5 vertices needs about"},
      {"shoot --quiet --first " + a + " --second " + b +
           " --steps 200000 --output " + d + "/s",
       "--steps must be an integer in [1, 100000]"},
      {"branching simulate --nx 4096 --ny 8192 --output " + d + "/br",
       "nodes) needs about"},
      {"geodesic --quiet" + ab + " --output " + d + "/out --time_limit -1",
       "--time_limit must be a number >= 0"},
      {"mean --quiet --inputs " + a + "," + b + " --output " + d +
           "/m.ply --time_limit nan",
       "--time_limit must be a number >= 0, got nan"},
  };
  // Dimensional branching flags far outside [1e-12, 1e12] (energy nan or
  // constant inf with exit 0 before).
  cases.push_back({"branching simulate --height 1e-300 --output " + d + "/br",
                   "--height must be 0 or a number in [1e-12, 1e+12], got 1e-300"});
  cases.push_back({"branching construct --length 1e-300 --output " + d + "/br",
                   "--length must be a number [1e-12, 1e+12], got 1e-300"});
  cases.push_back({"branching construct --epsilon 1e20 --output " + d + "/br",
                   "--epsilon must be a number [1e-12, 1e+12], got 1e+20"});
  // The simulation's own checks (problems/branching/simulation.h) under the
  // flag's name, before any work.
  cases.push_back({"branching simulate --init needles --output " + d + "/br",
                   "--init: must be laminate, random, km, needle or lens, got "
                   "'needles'"});
  cases.push_back(
      {"branching simulate --delta_extrapolation 1 --output " + d + "/br",
       "--delta_extrapolation must be 0 or an integer in [2, 16], got 1"});
  for (const Case& c : cases) ExpectRejected(c.args, c.message, d);
  EXPECT_EQ(cases.size(), 39u);
}

}  // namespace
}  // namespace shellspace
