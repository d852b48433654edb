// Tests of the axes around a picture (render/plot_axes.h), as the
// branching pictures use them: tick values and labels, and the frame, ticks,
// labels and legend where the header says they are.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "shellspace/render/bitmap_font.h"
#include "shellspace/render/plot_axes.h"
#include "tests/testing/render_fixtures.h"

namespace shellspace {
namespace {

using testing::IsColor;
using testing::CountUnlike;

TEST(PlotAxesTest, NiceTicksAndLabels) {
  const std::vector<double> unit = NiceTicks(0, 1);
  ASSERT_EQ(unit.size(), 6u);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(unit[k], 0.2 * k, 1e-12);
  const std::vector<double> half = NiceTicks(0, 2);
  ASSERT_EQ(half.size(), 5u);
  EXPECT_DOUBLE_EQ(half[1], 0.5);
  EXPECT_DOUBLE_EQ(half.back(), 2);
  const std::vector<double> short_range = NiceTicks(0, 0.62);
  ASSERT_EQ(short_range.size(), 7u);  // 0, 0.1, ..., 0.6
  EXPECT_NEAR(short_range.back(), 0.6, 1e-12);
  EXPECT_GE(NiceTicks(0.31, 0.33).size(), 2u);
  EXPECT_EQ(NiceTicks(3, 3), (std::vector<double>{3}));
  EXPECT_EQ(TickLabel(0.25, 0.05), "0.25");
  EXPECT_EQ(TickLabel(2, 1), "2");
  EXPECT_EQ(TickLabel(0.4, 0.2), "0.4");
  EXPECT_EQ(TickLabel(0.75, 0.25), "0.75");
  EXPECT_EQ(TickLabel(1e-5, 2e-6), "1e-05");
}

TEST(PlotAxesTest, FrameTicksAndLegendWhereDocumented) {
  RgbImage picture(200, 100);
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 200; ++x) {
      std::uint8_t* p = picture.at(x, y);
      p[0] = 200, p[1] = 10, p[2] = 10;
    }
  }
  PlotAxes axes;
  axes.x_max = 2;  // ticks 0, 0.5, 1, 1.5, 2 at columns 0, 50, 100, 150, 199
  axes.y_max = 1;  // ticks 0, 0.2, ... at rows 99, 80, 60, 40, 20, 0
  axes.text_scale = 2;
  axes.legend = {{{10, 200, 10}, "green"}, {{10, 10, 200}, "blue"}};
  PlotPlacement at;
  const RgbImage image = FramePlot(picture, axes, &at);
  const std::array<std::uint8_t, 3> ink = {40, 40, 40};
  const std::array<std::uint8_t, 3> white = {255, 255, 255};
  const int line = 1, tick = 6, s = 2;
  ASSERT_GT(at.left, 0);
  ASSERT_GT(at.top, 0);
  // The picture, unchanged.
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 200; ++x) {
      ASSERT_TRUE(IsColor(image.at(at.left + x, at.top + y), {200, 10, 10}));
    }
  }
  // The frame just outside it.
  EXPECT_TRUE(IsColor(image.at(at.left - 1, at.top + 37), ink));
  EXPECT_TRUE(IsColor(image.at(at.left + 200, at.top + 37), ink));
  EXPECT_TRUE(IsColor(image.at(at.left + 77, at.top - 1), ink));
  EXPECT_TRUE(IsColor(image.at(at.left + 77, at.top + 100), ink));
  // x ticks below the frame; nothing between them.
  for (int column : {0, 50, 100, 150, 199}) {
    for (int j = 0; j < tick; ++j) {
      EXPECT_TRUE(IsColor(image.at(at.left + column, at.top + 100 + line + j),
                          ink))
          << column;
    }
  }
  EXPECT_TRUE(IsColor(image.at(at.left + 25, at.top + 100 + line + 1), white));
  // y ticks left of it.
  for (int row : {99, 80, 60, 40, 20, 0}) {
    for (int i = 1; i <= tick; ++i) {
      EXPECT_TRUE(IsColor(image.at(at.left - line - i, at.top + row), ink))
          << row;
    }
  }
  EXPECT_TRUE(IsColor(image.at(at.left - line - 2, at.top + 70), white));
  // Tick labels under the x ticks (rows below the ticks) and left of the y
  // ticks carry ink.
  EXPECT_GT(CountUnlike(image, white, at.left - 20, at.top + 100 + line + tick,
                        40, TextHeight(s) + s),
            10);
  EXPECT_GT(CountUnlike(image, white, 0, at.top + 50, at.left - line - tick,
                        20),
            10);
  // The legend: swatches of the entries' colours right of the frame, top
  // aligned with the picture, 9 text_scale apart.
  const int legend = at.left + 200 + line + 4 * s;
  EXPECT_TRUE(IsColor(image.at(legend + 3 * s, at.top + 3 * s), {10, 200, 10}));
  EXPECT_TRUE(IsColor(image.at(legend + 3 * s, at.top + 9 * s + 3 * s),
                      {10, 10, 200}));
  EXPECT_TRUE(IsColor(image.at(legend, at.top), ink));  // outline
  EXPECT_GT(CountUnlike(image, white, legend + 9 * s, at.top, 5 * 6 * s,
                        TextHeight(s)),
            10);
  EXPECT_GE(image.width, legend + 9 * s + TextWidth("green", s));
}

}  // namespace
}  // namespace shellspace
