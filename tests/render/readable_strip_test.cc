// Tests of what makes the film strips readable (render/film_strip.h): what
// the up axis does to the pixels, the whole-image width, the frame labels,
// and the colour map by displacement with its colour bar.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/render/color_ramp.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/render/up_axis.h"
#include "shellspace/render/view.h"
#include "tests/testing/render_fixtures.h"

namespace shellspace {
namespace {

using testing::Box;
using testing::MeshAndMovedCopy;
using testing::UnitSquareMesh;
using testing::IsColor;
using testing::CountUnlike;

RenderOptions Plain(int width, int height) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.supersample = 1;
  options.labels = false;
  return options;
}

// Plain(width, height) coloured by displacement.
RenderOptions DisplacementOptions(int width, int height) {
  RenderOptions options = Plain(width, height);
  options.color = SurfaceColor::kDisplacement;
  return options;
}

std::array<std::uint8_t, 3> Background(const RenderOptions& options) {
  std::array<std::uint8_t, 3> bg;
  for (int c = 0; c < 3; ++c) {
    bg[c] = static_cast<std::uint8_t>(
        std::lround(255 * options.lighting.background[c]));
  }
  return bg;
}

// Width and height of the bounding box of the pixels unlike the background.
std::pair<int, int> CoveredBox(const RgbImage& image,
                               const RenderOptions& options) {
  const auto bg = Background(options);
  int x0 = image.width, x1 = -1, y0 = image.height, y1 = -1;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (IsColor(image.at(x, y), bg)) continue;
      x0 = std::min(x0, x);
      x1 = std::max(x1, x);
      y0 = std::min(y0, y);
      y1 = std::max(y1, y);
    }
  }
  return {x1 - x0 + 1, y1 - y0 + 1};
}

// ---------------------------------------------------------------- up axis

TEST(FilmStripUpAxisTest, AutoStandsAZLongBoxUpright) {
  // A 1 x 1 x 5 box seen from azimuth 45: standing on its long axis it is
  // taller than wide; with +x up it lies on its side, wider than tall.
  const Mesh box = Box(1, 1, 5);
  RenderOptions options = Plain(200, 200);
  options.view = ParseView("45,0");
  const auto [auto_w, auto_h] =
      CoveredBox(RenderFilmStrip({box.positions}, box.faces, options), options);
  EXPECT_GT(auto_h, 2 * auto_w) << auto_w << "x" << auto_h;
  EXPECT_GE(auto_h, 175);  // the long side spans the frame inside the margin
  options.up = UpAxis::kPlusX;
  const auto [x_w, x_h] =
      CoveredBox(RenderFilmStrip({box.positions}, box.faces, options), options);
  EXPECT_GT(x_w, 2 * x_h) << x_w << "x" << x_h;
  // Auto is +z here, pixel for pixel.
  const RgbImage z_up = [&] {
    RenderOptions z = options;
    z.up = UpAxis::kPlusZ;
    return RenderFilmStrip({box.positions}, box.faces, z);
  }();
  options.up = UpAxis::kAuto;
  EXPECT_EQ(RenderFilmStrip({box.positions}, box.faces, options).pixels,
            z_up.pixels);
}

TEST(FilmStripUpAxisTest, AutoOnAYLongMeshIsTheOldPicture) {
  const Mesh box = Box(1, 5, 1);
  RenderOptions options = Plain(160, 160);
  options.view = ParseView("iso");
  const RgbImage automatic = RenderFilmStrip({box.positions}, box.faces, options);
  options.up = UpAxis::kPlusY;
  const RgbImage explicit_y = RenderFilmStrip({box.positions}, box.faces, options);
  EXPECT_EQ(automatic.pixels, explicit_y.pixels);
  const auto [w, h] = CoveredBox(explicit_y, options);
  EXPECT_GT(h, w);
  // -y turns the picture upside down: a marker at the +y end moves from
  // the top half to the bottom half.
  Mesh marked = UnitSquareMesh();
  marked.positions.col(1) *= 3;  // y-long
  marked.positions.conservativeResize(7, 3);
  marked.positions.bottomRows(3) << -0.2, 2.6, 0.5, 0.2, 2.6, 0.5, 0, 3, 0.5;
  marked.faces.conservativeResize(3, 3);
  marked.faces.row(2) << 4, 5, 6;
  Mesh marker = marked;
  marker.faces = marked.faces.bottomRows(1);
  options = Plain(100, 100);
  for (UpAxis up : {UpAxis::kPlusY, UpAxis::kMinusY}) {
    options.up = up;
    const RgbImage image =
        RenderFilmStrip({marker.positions}, marker.faces, options);
    const int top = CountUnlike(image, Background(options), 0, 0, 100, 50);
    const int bottom = CountUnlike(image, Background(options), 0, 50, 100, 50);
    if (up == UpAxis::kPlusY) {
      EXPECT_GT(top, 0);
      EXPECT_EQ(bottom, 0);
    } else {
      EXPECT_EQ(top, 0);
      EXPECT_GT(bottom, 0);
    }
  }
}

// ---------------------------------------------------------------- width

TEST(FilmStripWidthTest, WidthIsTheWholeImage) {
  const Mesh square = UnitSquareMesh();
  for (int count : {1, 3, 7}) {
    for (int width : {500, 601, 64}) {
      RenderOptions options = Plain(width, 40);
      const std::vector<Positions> frames(count, square.positions);
      const RgbImage image = RenderFilmStrip(frames, square.faces, options);
      EXPECT_EQ(image.width, width) << count << " frames";
      const FilmStripLayout layout = LayoutFilmStrip(count, options);
      const int columns = std::min(count, 6);
      EXPECT_EQ(layout.columns, columns);
      EXPECT_EQ(layout.frame_width, width / columns);
      EXPECT_EQ(layout.left, (width - columns * (width / columns)) / 2);
      EXPECT_EQ(image.height, layout.rows * 40);
    }
  }
  // 7 frames in 6 columns of 601 / 6 = 100 pixels: 1 background column
  // stays left of the first frame (the remainder's half, rounded down),
  // and the second row holds one frame.
  RenderOptions options = Plain(601, 40);
  const std::vector<Positions> seven(7, square.positions);
  const RgbImage image = RenderFilmStrip(seven, square.faces, options);
  const auto bg = Background(options);
  EXPECT_EQ(CountUnlike(image, bg, 0, 0, 1, image.height), 0);
  EXPECT_GT(CountUnlike(image, bg, 1, 40, 100, 40), 0);
  EXPECT_EQ(CountUnlike(image, bg, 101, 40, 500, 40), 0);
  // Default: 320 per column, frames as high as wide.
  options = Plain(0, 0);
  const FilmStripLayout layout = LayoutFilmStrip(3, options);
  EXPECT_EQ(layout.width, 3 * 320);
  EXPECT_EQ(layout.frame_height, 320);
}

// ---------------------------------------------------------------- labels

TEST(FrameLabelTest, IndexAndTime) {
  EXPECT_EQ(FrameLabel(3, 9), "3  t=0.375");
  EXPECT_EQ(FrameLabel(0, 9), "0  t=0");
  EXPECT_EQ(FrameLabel(8, 9), "8  t=1");
  EXPECT_EQ(FrameLabel(1, 3), "1  t=0.5");
  EXPECT_EQ(FrameLabel(1, 7), "1  t=0.167");
  EXPECT_EQ(FrameLabel(0, 1), "0  t=0");
}

// A labelled film strip of `count` frames of the unit square in one row,
// each frame_width x frame_height pixels: its options, image and layout.
struct LabelledSquares {
  LabelledSquares(int count, int frame_width, int frame_height)
      : options(Labelled(Plain(count * frame_width, frame_height))),
        frames(count, square.positions),
        image(RenderFilmStrip(frames, square.faces, options)),
        layout(LayoutFilmStrip(count, options)) {}
  static RenderOptions Labelled(RenderOptions options) {
    options.labels = true;
    return options;
  }
  const Mesh square = UnitSquareMesh();
  const RenderOptions options;
  const std::vector<Positions> frames;
  const RgbImage image;
  const FilmStripLayout layout;
};

TEST(FrameLabelTest, EachFrameHasItsLabelStrip) {
  const LabelledSquares squares(3, 200, 100);
  const RgbImage& image = squares.image;
  const FilmStripLayout& layout = squares.layout;
  RenderOptions options = squares.options;
  ASSERT_EQ(layout.text_scale, 1);  // (200 + 80) / 160
  ASSERT_EQ(layout.label_height, 12);
  EXPECT_EQ(image.height, 100 + 12);
  const auto bg = Background(options);
  std::vector<std::vector<std::uint8_t>> strips;
  for (int k = 0; k < 3; ++k) {
    const int left = layout.FrameLeft(k);
    const int top = layout.FrameTop(k) + layout.frame_height;
    // The label is "k  t=T": about 6 pixels a character, dark ink.
    const int ink = CountUnlike(image, bg, left, top, layout.frame_width,
                                layout.label_height);
    EXPECT_GT(ink, 30) << k;
    // Centred, so the strip's outer quarters stay empty.
    EXPECT_EQ(CountUnlike(image, bg, left, top, 40, layout.label_height), 0);
    std::vector<std::uint8_t> strip;
    for (int y = top; y < top + layout.label_height; ++y) {
      strip.insert(strip.end(), image.at(left, y),
                   image.at(left, y) + 3 * layout.frame_width);
    }
    strips.push_back(strip);
  }
  EXPECT_NE(strips[0], strips[1]);
  EXPECT_NE(strips[1], strips[2]);
  // The pictures above are those of an unlabelled strip.
  options.labels = false;
  const RgbImage plain =
      RenderFilmStrip(squares.frames, squares.square.faces, options);
  EXPECT_EQ(plain.height, 100);
  EXPECT_TRUE(std::equal(plain.pixels.begin(), plain.pixels.end(),
                         image.pixels.begin()));
}

TEST(FrameLabelTest, NarrowFramesShowTheIndexOnly) {
  const LabelledSquares squares(6, 30, 30);
  const RgbImage& image = squares.image;
  const FilmStripLayout& layout = squares.layout;
  const auto bg = Background(squares.options);
  // "3" alone: 5 columns of ink, centred in the 30-pixel cell.
  const int top = layout.frame_height;
  const int left = layout.FrameLeft(3);
  EXPECT_GT(CountUnlike(image, bg, left + 12, top, 6, layout.label_height), 5);
  EXPECT_EQ(CountUnlike(image, bg, left, top, 12, layout.label_height), 0);
  EXPECT_EQ(CountUnlike(image, bg, left + 18, top, 12, layout.label_height), 0);
}

// ---------------------------------------------------------------- colour


// The one colour all pixels of the cell share that are not background, or
// {-1, -1, -1} if they do not share one.
Eigen::Vector3d UniformColor(const RgbImage& image, const RenderOptions& options,
                             int left, int top, int width, int height) {
  const auto bg = Background(options);
  Eigen::Vector3d color(-1, -1, -1);
  for (int y = top; y < top + height; ++y) {
    for (int x = left; x < left + width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      if (IsColor(p, bg)) continue;
      const Eigen::Vector3d c(p[0], p[1], p[2]);
      if (color.x() < 0) {
        color = c;
      } else if (c != color) {
        return Eigen::Vector3d(-1, -1, -1);
      }
    }
  }
  return color;
}

TEST(DisplacementColorTest, FirstFrameHasTheFirstColourAndMovedTheLast) {
  // A flat square (one shade everywhere) and the same square moved towards
  // the viewer: every vertex moves by D = 0.5, the largest displacement.
  const Mesh square = UnitSquareMesh();
  const RenderOptions options = DisplacementOptions(2 * 100, 100);
  const RgbImage image =
      RenderFilmStrip(MeshAndMovedCopy(square, 2, 0.5), square.faces, options);
  const Eigen::Vector3d first = UniformColor(image, options, 0, 0, 100, 100);
  const Eigen::Vector3d last = UniformColor(image, options, 100, 0, 100, 100);
  ASSERT_GE(first.minCoeff(), 0) << "frame 0 is not one colour";
  ASSERT_GE(last.minCoeff(), 0) << "frame 1 is not one colour";
  // The same shade s times the ramp's ends (to the 8-bit rounding).
  const Eigen::Vector3d r0 = 255 * RampColor(0), r1 = 255 * RampColor(1);
  const double s = first.dot(r0) / r0.squaredNorm();
  EXPECT_GT(s, 0.5);
  EXPECT_LT((first - s * r0).cwiseAbs().maxCoeff(), 1.0) << first.transpose();
  EXPECT_LT((last - s * r1).cwiseAbs().maxCoeff(), 1.0) << last.transpose();
}

TEST(DisplacementColorTest, AMovedVertexIsTheWarmCorner) {
  // Vertex 2, the (+x, +y) corner, moves out of the plane by 0.4 in the
  // last frame; vertex 0 at (-x, -y) stays.
  const Mesh square = UnitSquareMesh();
  Positions bent = square.positions;
  bent(2, 2) = 0.4;
  const RenderOptions options = DisplacementOptions(2 * 100, 100);
  const RgbImage image =
      RenderFilmStrip({square.positions, bent}, square.faces, options);
  // Pixels next to the corners of the square (90 x 90 at 5..95).
  const std::uint8_t* warm = image.at(100 + 93, 6);
  const std::uint8_t* cool = image.at(100 + 6, 93);
  EXPECT_LT(2 * warm[2], warm[0]);  // yellow: much more red than blue
  EXPECT_GT(cool[2], cool[0]);      // violet: more blue than red
  // In frame 0 nothing has moved: the same corner is violet.
  EXPECT_GT(image.at(93, 6)[2], image.at(93, 6)[0]);
}

TEST(DisplacementColorTest, ColourBarUnderTheStrip) {
  const Mesh square = UnitSquareMesh();
  const std::vector<Positions> frames = MeshAndMovedCopy(square, 0, 1);
  RenderOptions options = DisplacementOptions(2 * 320, 200);
  const RgbImage image = RenderFilmStrip(frames, square.faces, options);
  const FilmStripLayout layout = LayoutFilmStrip(2, options);
  ASSERT_EQ(layout.legend_height, 14 * 2);
  EXPECT_EQ(image.height, 200 + layout.legend_height);
  // The bar runs through the ramp: both end colours appear in the strip.
  auto byte = [](double v) {
    return static_cast<std::uint8_t>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
  };
  std::array<std::uint8_t, 3> c0, c1;
  for (int c = 0; c < 3; ++c) {
    c0[c] = byte(RampColor(0)[c]);
    c1[c] = byte(RampColor(1)[c]);
  }
  int first = 0, last = 0;
  for (int y = 200; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      first += IsColor(image.at(x, y), c0);
      last += IsColor(image.at(x, y), c1);
    }
  }
  EXPECT_GT(first, 0);
  EXPECT_GT(last, 0);
  // Without the colour map there is no bar.
  options.color = SurfaceColor::kPlain;
  EXPECT_EQ(RenderFilmStrip(frames, square.faces, options).height, 200);
  EXPECT_EQ(ParseSurfaceColor("Displacement"), SurfaceColor::kDisplacement);
  EXPECT_EQ(ParseSurfaceColor("plain"), SurfaceColor::kPlain);
  EXPECT_THROW(ParseSurfaceColor("rainbow"), InputError);
}

}  // namespace
}  // namespace shellspace
