// The film-strip flags on the command line: `render --up`, `--labels`,
// `--color` and the whole-image --width, and a bad --up or --color on a
// verb that solves first (refused before any work, no file written).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "tests/testing/render_fixtures.h"
#include "tests/tools/cli_test_support.h"

namespace shellspace {
namespace {

using testing::PngSize;

const std::string kCactus =
    DataPath("cactus/cactus0.ply") + "," + DataPath("cactus/cactus9.ply");

// Runs `render` with `args`, which must succeed; returns its --json.
std::string Render(const std::string& args) {
  std::string out, err;
  EXPECT_EQ(RunCli("render --json --input " + kCactus + " " + args, &out, &err),
            0)
      << args << "\n" << err;
  return out;
}

TEST(FilmStripCliTest, UpAxisAutoStandsTheCactusOnZ) {
  const std::string dir = TempDir();
  const std::string z = Render("--output " + dir + "/z.png --up z --width 300");
  EXPECT_NE(z.find("\"up\": \"z\""), std::string::npos) << z;
  EXPECT_EQ(Number(z, "width"), 300);
  EXPECT_EQ(Number(z, "frame_width"), 150);
  const std::string automatic =
      Render("--output " + dir + "/auto.png --width 300");
  EXPECT_NE(automatic.find("\"up\": \"z\""), std::string::npos) << automatic;
  EXPECT_EQ(Slurp(dir + "/auto.png"), Slurp(dir + "/z.png"));
  const std::string y = Render("--output " + dir + "/y.png --up y --width 300");
  EXPECT_NE(y.find("\"up\": \"y\""), std::string::npos) << y;
  EXPECT_NE(Slurp(dir + "/y.png"), Slurp(dir + "/z.png"));
  // 150-pixel frames: text scale 1, 12 label rows under the 150 rows.
  EXPECT_EQ(PngSize(dir + "/z.png"), std::make_pair(300, 150 + 12));
}

TEST(FilmStripCliTest, LabelsOffAndColourByDisplacement) {
  const std::string dir = TempDir();
  const std::string plain =
      Render("--output " + dir + "/plain.png --width 640 --labels=false");
  EXPECT_NE(plain.find("\"labels\": false"), std::string::npos) << plain;
  EXPECT_EQ(PngSize(dir + "/plain.png"), std::make_pair(640, 320));
  const std::string colored = Render("--output " + dir +
                                     "/color.png --width 640 --color "
                                     "displacement --labels=false");
  EXPECT_NE(colored.find("\"color\": \"displacement\""), std::string::npos)
      << colored;
  // The colour bar: 14 rows at text scale 2.
  EXPECT_EQ(PngSize(dir + "/color.png"), std::make_pair(640, 320 + 28));
}

TEST(FilmStripCliTest, BadUpOrColourIsOneLineAndNoFile) {
  const std::string dir = TempDir();
  const std::string square = DataPath("simple/square4.ply");
  const std::string bent = DataPath("simple/square4_bent.ply");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"render --input " + kCactus + " --output " + dir + "/a.png --up bogus",
       "--up"},
      {"render --input " + kCactus + " --output " + dir + "/a.png --up xy",
       "--up"},
      {"render --input " + kCactus + " --output " + dir +
           "/a.png --color rainbow",
       "--color"},
      {"render --input " + kCactus + " --output " + dir +
           "/a.png --width 1 --labels=false",
       "width"},
      {"geodesic --start " + square + " --end " + bent + " --steps 4 --output " +
           dir + "/path --png " + dir + "/a.png --up bogus",
       "--up"},
  };
  for (const auto& [args, name] : cases) {
    std::string err;
    EXPECT_EQ(RunCli(args, nullptr, &err), 1) << args;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find(name), std::string::npos) << err;
    EXPECT_TRUE(std::filesystem::is_empty(dir)) << args;
  }
  std::string err;
  RunCli("render --input " + kCactus + " --output " + dir + "/a.png --up bogus",
         nullptr, &err);
  EXPECT_NE(err.find("expected auto, x, y, z, -x, -y or -z"), std::string::npos)
      << err;
}

TEST(FilmStripCliTest, PathVerbsTakeTheFlags) {
  const std::string dir = TempDir();
  const std::string square = DataPath("simple/square4.ply");
  const std::string bent = DataPath("simple/square4_bent.ply");
  std::string err;
  ASSERT_EQ(RunCli("geodesic --quiet --start " + square + " --end " + bent +
                       " --steps 2 --output " + dir + "/path --png " + dir +
                       "/strip.png --up z --color displacement",
                   nullptr, &err),
            0)
      << err;
  // Three frames of 320 pixels, labels (24 rows) and the colour bar (28).
  EXPECT_EQ(PngSize(dir + "/strip.png"), std::make_pair(3 * 320, 320 + 24 + 28));
}

}  // namespace
}  // namespace shellspace
