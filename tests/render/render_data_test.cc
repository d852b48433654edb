// Tests of the software renderer and `shellspace render` on the shared
// sphere and finger meshes: silhouette coverage of the 162-vertex sphere,
// Gouraud against flat shading, two poses in one strip, deterministic
// PNGs, frame lists checked for compatibility, and the strips the verb
// writes.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <utility>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/render/view.h"
#include "tests/testing/cli_output.h"
#include "tests/testing/render_fixtures.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::CameraOptions;
using testing::CoveredPixels;
using testing::ExpectSphereCoverage;
using testing::PngSize;

using ::shellspace::testing::DataPath;
using ::shellspace::testing::LoadData;
using ::shellspace::testing::RunCli;
using ::shellspace::testing::TempDir;
using testing::Slurp;

TEST(RenderTest, UnitSphereMeshCoversNearlyItsDisc) {
  // 162 vertices: an inscribed silhouette polygon, 2-3 % short of the disc.
  const Mesh sphere = LoadData("sphere/unitSphere1.ply");
  ExpectSphereCoverage(sphere, "front", 0.95, 1.005);
}

TEST(RenderTest, GouraudIsSmootherThanFlat) {
  const Mesh sphere = LoadData("sphere/unitSphere1.ply");
  RenderOptions options = CameraOptions(120, 120);
  options.shading = Shading::kFlat;
  const RgbImage flat =
      RenderFilmStrip({sphere.positions}, sphere.faces, options);
  options.shading = Shading::kGouraud;
  const RgbImage gouraud =
      RenderFilmStrip({sphere.positions}, sphere.faces, options);
  EXPECT_NE(flat.pixels, gouraud.pixels);
  EXPECT_EQ(CoveredPixels(flat, options), CoveredPixels(gouraud, options));
  // Sum of absolute horizontal jumps inside the silhouette: facets make
  // flat shading jumpier.
  auto roughness = [&](const RgbImage& image) {
    long total = 0;
    for (int y = 30; y < 90; ++y) {
      for (int x = 30; x < 89; ++x) {
        total += std::abs(image.at(x + 1, y)[1] - image.at(x, y)[1]);
      }
    }
    return total;
  };
  EXPECT_LT(roughness(gouraud), roughness(flat));
}

TEST(FilmStripTest, TwoPosesGiveDifferentFrames) {
  const Mesh straight = LoadData("finger/finger0.ply");
  const Mesh bent = LoadData("finger/finger1.ply");
  const RenderOptions options = CameraOptions(3 * 160, 160, 2);
  const RgbImage image =
      RenderFilmStrip({straight.positions, bent.positions, straight.positions},
                      straight.faces, options);
  ASSERT_EQ(image.width, 3 * 160);
  ASSERT_EQ(image.height, 160);
  int differing = 0, equal_first_last = 0;
  for (int y = 0; y < 160; ++y) {
    for (int x = 0; x < 160; ++x) {
      for (int c = 0; c < 3; ++c) {
        differing += image.at(x, y)[c] != image.at(x + 160, y)[c];
        equal_first_last += image.at(x, y)[c] == image.at(x + 320, y)[c];
      }
    }
  }
  EXPECT_GT(differing, 300);                   // the bend is visible
  EXPECT_EQ(equal_first_last, 160 * 160 * 3);  // same pose, same camera
  EXPECT_GT(CoveredPixels(image, options, 0, 0, 160, 160), 500);
}

TEST(FilmStripTest, RenderingIsDeterministic) {
  const Mesh finger = LoadData("finger/finger1.ply");
  RenderOptions options = CameraOptions(128, 96, 2);
  options.view = ParseView("iso");
  const std::string dir = TempDir();
  WriteFilmStrip({finger.positions}, finger.faces, options, dir + "/a.png");
  WriteFilmStrip({finger.positions}, finger.faces, options, dir + "/b.png");
  const std::string a = Slurp(dir + "/a.png");
  EXPECT_GT(a.size(), 100u);
  EXPECT_EQ(a, Slurp(dir + "/b.png"));
  EXPECT_EQ(PngSize(dir + "/a.png"), std::make_pair(128, 96));
}

TEST(FrameSequenceTest, ListKeepsOrderAndChecksCompatibility) {
  const std::string a = DataPath("finger/finger1.ply");
  const std::string b = DataPath("finger/finger0.ply");
  const FrameSequence sequence = ReadFrameSequence(a + ", " + b);
  ASSERT_EQ(sequence.paths.size(), 2u);
  EXPECT_EQ(sequence.paths[0], a);
  EXPECT_EQ(sequence.frames[1].rows(), 2046);
  EXPECT_THROW(ReadFrameSequence(a + "," + DataPath("sphere/unitSphere1.ply")),
               InputError);
  EXPECT_THROW(ReadFrameSequence(a + ",," + b), InputError);
  EXPECT_THROW(ReadFrameSequence(""), InputError);
  EXPECT_THROW(ReadFrameSequence(TempDir()), InputError);  // empty directory
  EXPECT_THROW(ReadFrameSequence(TempDir() + "/missing"), InputError);
}

TEST(RenderCliTest, WritesAStrip) {
  const std::string out = TempDir() + "/strip.png";
  std::string stdout_text, stderr_text;
  ASSERT_EQ(RunCli("render --input " + DataPath("finger/finger0.ply") + "," +
                       DataPath("finger/finger1.ply") + " --output " + out +
                       " --width 192 --height 64 --view iso --json",
                   &stdout_text, &stderr_text),
            0)
      << stderr_text;
  // --width is the whole image: two frames of 96 pixels, each 64 high plus
  // a label strip of 12 rows (text scale 1 for 96-pixel frames).
  EXPECT_EQ(PngSize(out), std::make_pair(2 * 96, 64 + 12));
  EXPECT_NE(stdout_text.find("\"frames\": 2"), std::string::npos)
      << stdout_text;
  EXPECT_EQ(testing::Number(stdout_text, "frame_width"), 96);
  EXPECT_EQ(testing::Number(stdout_text, "label_height"), 12);
}

TEST(RenderCliTest, DirectoryInputUsesDefaultSize) {
  const std::string out = TempDir() + "/strip.png";
  std::string err;
  ASSERT_EQ(RunCli("render --quiet --input " + DataPath("sphere") +
                       " --output " + out + " --view=30,-20",
                   nullptr, &err),
            0)
      << err;
  // 320 pixels per column by default, square frames, labels at text scale 2.
  EXPECT_EQ(PngSize(out), std::make_pair(4 * 320, 320 + 24));
}

}  // namespace
}  // namespace shellspace
