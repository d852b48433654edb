// Tests of the software renderer and `shellspace render` on meshes made
// here: camera framing, silhouette coverage, orientation, lighting sides,
// film-strip layout, frame sequences and input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/render/camera.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/render/view.h"
#include "tests/testing/render_fixtures.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::CameraOptions;
using testing::CoveredPixels;
using testing::ExpectSphereCoverage;
using testing::MeshAndMovedCopy;

using ::shellspace::testing::DataPath;
using ::shellspace::testing::RunCli;
using ::shellspace::testing::TempDir;

// The square [-1, 1]^2 x {z} with outward normal +z, two triangles.
Mesh Square(double z = 0) {
  Mesh mesh;
  mesh.positions.resize(4, 3);
  mesh.positions << -1, -1, z, 1, -1, z, 1, 1, z, -1, 1, z;
  mesh.faces.resize(2, 3);
  mesh.faces << 0, 1, 2, 0, 2, 3;
  return mesh;
}

// A closed latitude-longitude sphere of the given radius about the origin.
Mesh UvSphere(int rings, int segments, double radius) {
  Mesh mesh;
  const int n = 2 + (rings - 1) * segments;
  mesh.positions.resize(n, 3);
  mesh.positions.row(0) << 0, radius, 0;
  mesh.positions.row(n - 1) << 0, -radius, 0;
  for (int r = 1; r < rings; ++r) {
    const double theta = M_PI * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * M_PI * s / segments;
      mesh.positions.row(1 + (r - 1) * segments + s)
          << radius * std::sin(theta) * std::cos(phi),
          radius * std::cos(theta), radius * std::sin(theta) * std::sin(phi);
    }
  }
  auto index = [&](int r, int s) {
    return 1 + (r - 1) * segments + s % segments;
  };
  std::vector<Eigen::Vector3i> faces;
  for (int s = 0; s < segments; ++s) {
    faces.emplace_back(0, index(1, s + 1), index(1, s));
    faces.emplace_back(n - 1, index(rings - 1, s), index(rings - 1, s + 1));
    for (int r = 1; r + 1 < rings; ++r) {
      faces.emplace_back(index(r, s), index(r, s + 1), index(r + 1, s));
      faces.emplace_back(index(r, s + 1), index(r + 1, s + 1), index(r + 1, s));
    }
  }
  mesh.faces.resize(faces.size(), 3);
  for (size_t f = 0; f < faces.size(); ++f) mesh.faces.row(f) = faces[f];
  return mesh;
}

// Mean of (x, y) over covered pixels of the whole image.
Eigen::Vector2d CoveredCentroid(const RgbImage& image,
                                const RenderOptions& options, int left,
                                int width) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int count = 0;
  const auto bg = (255 * options.lighting.background).array().round().eval();
  for (int y = 0; y < image.height; ++y) {
    for (int x = left; x < left + width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      if (p[0] != bg[0] || p[1] != bg[1] || p[2] != bg[2]) {
        sum += Eigen::Vector2d(x + 0.5, y + 0.5);
        ++count;
      }
    }
  }
  return count ? Eigen::Vector2d(sum / count) : Eigen::Vector2d(-1, -1);
}

// ---------------------------------------------------------------- views

TEST(ParseViewTest, NamedViews) {
  EXPECT_DOUBLE_EQ(ParseView("front").azimuth, 0);
  EXPECT_DOUBLE_EQ(ParseView("front").elevation, 0);
  EXPECT_DOUBLE_EQ(ParseView("side").azimuth, 90);
  EXPECT_DOUBLE_EQ(ParseView("TOP").elevation, 90);
  EXPECT_DOUBLE_EQ(ParseView("iso").azimuth, 45);
  EXPECT_NEAR(ParseView("iso").elevation, 35.2644, 1e-4);
  const ViewAngles v = ParseView(" -30 , 20.5");
  EXPECT_DOUBLE_EQ(v.azimuth, -30);
  EXPECT_DOUBLE_EQ(v.elevation, 20.5);
}

TEST(ParseViewTest, RejectsBadViews) {
  for (const char* bad : {"", "diagonal", "30", "30,", ",20", "30,20,1",
                          "30,91", "nan,0", "30,abc"}) {
    EXPECT_THROW(ParseView(bad), InputError) << bad;
  }
}

TEST(CameraTest, ViewFramesLookAlongTheNamedAxis) {
  Eigen::Vector3d right, up, forward;
  ViewFrame(ParseView("front"), &right, &up, &forward);
  EXPECT_TRUE(forward.isApprox(Eigen::Vector3d(0, 0, -1)));
  EXPECT_TRUE(up.isApprox(Eigen::Vector3d(0, 1, 0)));
  EXPECT_TRUE(right.isApprox(Eigen::Vector3d(1, 0, 0)));
  ViewFrame(ParseView("side"), &right, &up, &forward);
  EXPECT_TRUE(forward.isApprox(Eigen::Vector3d(-1, 0, 0)));
  EXPECT_TRUE(up.isApprox(Eigen::Vector3d(0, 1, 0)));
  ViewFrame(ParseView("top"), &right, &up, &forward);
  EXPECT_TRUE(forward.isApprox(Eigen::Vector3d(0, -1, 0)));
  EXPECT_TRUE(right.isApprox(Eigen::Vector3d(1, 0, 0)));
  // Right-handed: right x up = towards the viewer.
  ViewFrame(ViewAngles{37, -21}, &right, &up, &forward);
  EXPECT_TRUE(right.cross(up).isApprox(-forward));
  EXPECT_NEAR(right.norm(), 1, 1e-12);
  EXPECT_NEAR(up.dot(forward), 0, 1e-12);
}

TEST(CameraTest, FrameBoxFitsTheBoxIntoTheMargins) {
  const Camera camera =
      FrameBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 2, 1),
               ParseView("front"), 200, 100, 0.05);
  // Width limits: 4 units -> 180 pixels.
  EXPECT_NEAR(camera.scale, 45, 1e-12);
  const Eigen::Vector3d lo = camera.Project(Eigen::Vector3d(0, 0, 1));
  const Eigen::Vector3d hi = camera.Project(Eigen::Vector3d(4, 2, 0));
  EXPECT_NEAR(lo.x(), 10, 1e-9);
  EXPECT_NEAR(hi.x(), 190, 1e-9);
  EXPECT_NEAR(lo.y(), 95, 1e-9);  // y = 0 at the bottom (rows grow down)
  EXPECT_NEAR(hi.y(), 5, 1e-9);
  EXPECT_LT(lo.z(), hi.z());  // z = 1 is nearer to a front viewer
}

TEST(CameraTest, FrameVerticesTouchesTheMargins) {
  // A tilted segment's vertices in the iso view: the camera centres their
  // projection and fits the longer projected side exactly into the margins.
  Positions points(3, 3);
  points << 0, 0, 0, 1, 2, 3, -2, 0.5, 1;
  const Positions shifted = points.rowwise() + Eigen::RowVector3d(5, -1, 2);
  const Camera camera =
      FrameVertices({points, shifted}, ParseView("iso"), 300, 200, 0.1);
  double lo_x = 1e9, hi_x = -1e9, lo_y = 1e9, hi_y = -1e9;
  for (const Positions* p :
       {static_cast<const Positions*>(&points), &shifted}) {
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d q = camera.Project(p->row(i).transpose());
      lo_x = std::min(lo_x, q.x());
      hi_x = std::max(hi_x, q.x());
      lo_y = std::min(lo_y, q.y());
      hi_y = std::max(hi_y, q.y());
    }
  }
  EXPECT_NEAR(lo_x + hi_x, 300, 1e-9);
  EXPECT_NEAR(lo_y + hi_y, 200, 1e-9);
  EXPECT_TRUE(std::abs(hi_x - lo_x - 240) < 1e-9 ||
              std::abs(hi_y - lo_y - 160) < 1e-9);
  EXPECT_LE(hi_x - lo_x, 240 + 1e-9);
  EXPECT_LE(hi_y - lo_y, 160 + 1e-9);
}

// ---------------------------------------------------------------- coverage

TEST(RenderTest, SquareFillsTheFramedArea) {
  // The square projects to exactly 90 x 90 pixel centres in a 100 x 100
  // frame with a 5 % margin.
  const Mesh square = Square();
  RenderOptions options = CameraOptions(100, 100);
  RgbImage image = RenderFilmStrip({square.positions}, square.faces, options);
  EXPECT_EQ(CoveredPixels(image, options), 90 * 90);
  // A wide frame: the height limits the scale, the square stays square.
  options = CameraOptions(200, 100);
  image = RenderFilmStrip({square.positions}, square.faces, options);
  EXPECT_EQ(CoveredPixels(image, options), 90 * 90);
  EXPECT_EQ(CoveredPixels(image, options, 0, 0, 55, 100), 0);
  EXPECT_EQ(CoveredPixels(image, options, 145, 0, 55, 100), 0);
  // Seen edge-on from the side, a flat square covers nothing.
  options.view = ParseView("side");
  image = RenderFilmStrip({square.positions}, square.faces, options);
  EXPECT_EQ(CoveredPixels(image, options), 0);
}

TEST(RenderTest, FineSphereCoversItsDisc) {
  // 64 segments: the silhouette polygon has > 99.5 % of the disc's area.
  const Mesh sphere = UvSphere(32, 64, 1.0);
  ExpectSphereCoverage(sphere, "front", 0.99, 1.005);
  ExpectSphereCoverage(sphere, "iso", 0.99, 1.01);
  ExpectSphereCoverage(sphere, "-70,-35", 0.99, 1.01);
}

// ---------------------------------------------------------------- orientation

TEST(RenderTest, PlusYIsUpAndPlusXIsRightInTheFrontView) {
  // The square plus a second, small triangle placed at +x +y in its corner.
  Mesh mesh = Square();
  mesh.positions.conservativeResize(7, 3);
  mesh.positions.row(4) << 0.6, 0.6, 0.5;
  mesh.positions.row(5) << 1.0, 0.6, 0.5;
  mesh.positions.row(6) << 1.0, 1.0, 0.5;
  mesh.faces.conservativeResize(3, 3);
  mesh.faces.row(2) << 4, 5, 6;
  // Only the little triangle.
  Mesh corner = mesh;
  corner.faces = mesh.faces.bottomRows(1);
  RenderOptions options = CameraOptions(100, 100);
  const RgbImage image =
      RenderFilmStrip({corner.positions}, corner.faces, options);
  const int total = CoveredPixels(image, options);
  EXPECT_GT(total, 0);
  // Framed by the box of all vertices: the triangle is in the top right.
  EXPECT_EQ(CoveredPixels(image, options, 50, 0, 50, 50), total);
}

TEST(RenderTest, NearerSurfaceHidesFartherOne) {
  // A small square at z = 1 (outer side towards a front viewer: bluish) in
  // front of a large one at z = -1 turned around (inner side: warm). Whatever
  // the drawing order, the z-buffer shows the near square in the middle.
  Mesh both = Square(1);
  both.positions.leftCols(2) *= 0.5;
  Mesh far = Square(-1);
  far.faces.col(1).swap(far.faces.col(2));
  both.positions.conservativeResize(8, 3);
  both.positions.bottomRows(4) = far.positions;
  both.faces.conservativeResize(4, 3);
  both.faces.bottomRows(2) = far.faces.array() + 4;
  Mesh reversed = both;  // far first
  reversed.faces.topRows(2) = both.faces.bottomRows(2);
  reversed.faces.bottomRows(2) = both.faces.topRows(2);
  const RenderOptions options = CameraOptions(64, 64);
  const RgbImage a = RenderFilmStrip({both.positions}, both.faces, options);
  const RgbImage b =
      RenderFilmStrip({reversed.positions}, reversed.faces, options);
  EXPECT_EQ(a.pixels, b.pixels);
  for (const RgbImage* image : {&a, &b}) {
    EXPECT_GT(image->at(32, 32)[2], image->at(32, 32)[0]);  // near, bluish
    EXPECT_GT(image->at(6, 32)[0], image->at(6, 32)[2]);    // far, warm
  }
}

TEST(RenderTest, BackFacesAreTintedDifferently) {
  const Mesh square = Square();
  RenderOptions options = CameraOptions(50, 50);
  const RgbImage front =
      RenderFilmStrip({square.positions}, square.faces, options);
  options.view = ParseView("back");
  const RgbImage back =
      RenderFilmStrip({square.positions}, square.faces, options);
  const std::uint8_t* f = front.at(25, 25);
  const std::uint8_t* b = back.at(25, 25);
  EXPECT_GT(f[2], f[0]);  // bluish outer side
  EXPECT_GT(b[0], b[2]);  // warm inner side
}

TEST(RenderTest, LightComesFromUpperLeft) {
  const Mesh sphere = UvSphere(24, 48, 1.0);
  const RenderOptions options = CameraOptions(100, 100);
  const RgbImage image =
      RenderFilmStrip({sphere.positions}, sphere.faces, options);
  auto brightness = [&](int x, int y) {
    const std::uint8_t* p = image.at(x, y);
    return p[0] + p[1] + p[2];
  };
  EXPECT_GT(brightness(35, 35), brightness(65, 65) + 60);
  EXPECT_GT(brightness(40, 50), brightness(60, 50));
}

// ---------------------------------------------------------------- strips

TEST(FilmStripTest, CameraIsFixedAcrossFrames) {
  // The same square moved right by 2: the second frame shows it further
  // right than the first, both at half the scale of a lone square.
  const Mesh square = Square();
  const RenderOptions options = CameraOptions(2 * 120, 120);
  const RgbImage image =
      RenderFilmStrip(MeshAndMovedCopy(square, 0, 2), square.faces, options);
  const Eigen::Vector2d c0 = CoveredCentroid(image, options, 0, 120);
  const Eigen::Vector2d c1 = CoveredCentroid(image, options, 120, 120);
  // Box [-1, 3] x [-1, 1] into 108 pixels: 27 px/unit, box centre x = 1 at
  // pixel 60; the squares are centred at x = 60 - 27 and 120 + 60 + 27.
  EXPECT_NEAR(c0.x(), 33, 0.5);
  EXPECT_NEAR(c1.x(), 207, 0.5);
  EXPECT_NEAR(c0.y(), 60, 0.5);
  EXPECT_EQ(CoveredPixels(image, options, 0, 0, 120, 120), 54 * 54);
  EXPECT_EQ(CoveredPixels(image, options, 120, 0, 120, 120), 54 * 54);
}

TEST(FilmStripTest, LayoutWrapsIntoRows) {
  const Mesh square = Square();
  RenderOptions options = CameraOptions(3 * 40, 30);
  RgbImage image =
      RenderFilmStrip({square.positions, square.positions, square.positions},
                      square.faces, options);
  EXPECT_EQ(image.width, 3 * 40);
  EXPECT_EQ(image.height, 30);
  const std::vector<Positions> eight(8, square.positions);
  options = CameraOptions(6 * 40, 30);  // 6 columns of the 8 frames
  image = RenderFilmStrip(eight, square.faces, options);
  EXPECT_EQ(image.width, 6 * 40);
  EXPECT_EQ(image.height, 2 * 30);
  const int per_frame = CoveredPixels(image, options, 0, 0, 40, 30);
  EXPECT_GT(per_frame, 0);
  EXPECT_EQ(CoveredPixels(image, options, 40, 30, 40, 30), per_frame);
  // The cells after the eighth frame stay empty.
  EXPECT_EQ(CoveredPixels(image, options, 80, 30, 160, 30), 0);
  EXPECT_EQ(CoveredPixels(image, options), 8 * per_frame);
}

TEST(FilmStripTest, RejectsBadInput) {
  const Mesh square = Square();
  RenderOptions options = CameraOptions(10, 10);
  EXPECT_THROW(RenderFilmStrip({}, square.faces, options), InputError);
  EXPECT_THROW(RenderFilmStrip({square.positions, square.positions.topRows(3)},
                               square.faces, options),
               InputError);
  Faces bad = square.faces;
  bad(1, 2) = 4;
  EXPECT_THROW(RenderFilmStrip({square.positions}, bad, options), InputError);
  Positions nan = square.positions;
  nan(0, 0) = std::nan("");
  EXPECT_THROW(RenderFilmStrip({nan}, square.faces, options), InputError);
  for (const auto& [w, h] : {std::pair{-1, 10}, {10, -1}, {100000, 10}, {10, 9000}}) {
    options = CameraOptions(w, h);
    EXPECT_THROW(RenderFilmStrip({square.positions}, square.faces, options),
                 InputError);
  }
  // Fewer pixels than columns.
  EXPECT_THROW(RenderFilmStrip({square.positions, square.positions},
                               square.faces, CameraOptions(1, 10)),
               InputError);
  const Mesh other = UvSphere(4, 4, 1);
  EXPECT_THROW(WriteFilmStrip({square, other}, CameraOptions(10, 10),
                              TempDir() + "/x.png"),
               InputError);
}

// ---------------------------------------------------------------- inputs

TEST(FrameSequenceTest, NaturalOrder) {
  EXPECT_TRUE(NaturalLess("shape_2.ply", "shape_10.ply"));
  EXPECT_FALSE(NaturalLess("shape_10.ply", "shape_2.ply"));
  EXPECT_TRUE(NaturalLess("shape_000.ply", "shape_001.ply"));
  EXPECT_TRUE(NaturalLess("a.ply", "b.ply"));
  EXPECT_TRUE(NaturalLess("a", "a1"));
  EXPECT_FALSE(NaturalLess("a1", "a1"));
}

TEST(FrameSequenceTest, DirectoryListsMeshesInNaturalOrder) {
  const std::string dir = TempDir();
  const Mesh square = Square();
  for (const char* name : {"shape_10.ply", "shape_2.off", "shape_1.OBJ"}) {
    WriteMesh(square, dir + "/" + name);
  }
  std::ofstream(dir + "/notes.txt") << "not a mesh\n";
  std::filesystem::create_directory(dir + "/sub.ply");
  const std::vector<std::string> files = ListFrameFiles(dir);
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0], dir + "/shape_1.OBJ");
  EXPECT_EQ(files[1], dir + "/shape_2.off");
  EXPECT_EQ(files[2], dir + "/shape_10.ply");
  const FrameSequence sequence = ReadFrameSequence(dir);
  EXPECT_EQ(sequence.frames.size(), 3u);
  EXPECT_EQ(sequence.faces.rows(), 2);
}

// ---------------------------------------------------------------- CLI

TEST(RenderCliTest, ErrorsExitOneWithoutOutput) {
  const std::string dir = TempDir();
  const std::string out = dir + "/strip.png";
  const std::string finger = DataPath("finger/finger0.ply");
  const std::vector<std::string> cases = {
      "--input " + dir + "/missing --output " + out,
      "--input " + dir + " --output " + out,  // no meshes in it
      "--input " + finger + "," + DataPath("sphere/unitSphere1.ply") +
          " --output " + out,
      "--input " + finger + " --output " + out + " --view sideways",
      "--input " + finger + " --output " + out + " --shading phong",
      "--input " + finger + " --output " + out + " --width -5",
      "--input " + finger + " --output " + out + " --height 2.5",
      "--input " + finger,  // no --output
      "--output " + out,    // no --input
  };
  for (const std::string& args : cases) {
    std::string err;
    EXPECT_EQ(RunCli("render " + args, nullptr, &err), 1) << args;
    EXPECT_NE(err.find("error: "), std::string::npos) << args << ": " << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
    EXPECT_FALSE(std::filesystem::exists(out + ".tmp")) << args;
  }
}

// A bad --view or --shading is named as the flag, then the library's reason
// (it once read "--bad shading 'phong' (expected flat or gouraud)").
TEST(RenderCliTest, BadViewAndShadingNameTheirFlag) {
  const std::string base = "render --input " + DataPath("finger/finger0.ply") +
                           " --output " + TempDir() + "/strip.png";
  std::string err;
  EXPECT_EQ(RunCli(base + " --shading phong", nullptr, &err), 1);
  EXPECT_NE(err.find("error: --shading: the shading must be flat or gouraud, "
                     "got 'phong'"),
            std::string::npos)
      << err;
  EXPECT_EQ(RunCli(base + " --view sideways", nullptr, &err), 1);
  EXPECT_NE(err.find("error: --view: bad view 'sideways'"), std::string::npos)
      << err;
}

}  // namespace
}  // namespace shellspace
