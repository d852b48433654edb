#include "shellspace/render/branching_image.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace shellspace::branching {
namespace {

constexpr std::array<std::uint8_t, 3> kPlus = {235, 140, 40};
constexpr std::array<std::uint8_t, 3> kMinus = {45, 95, 200};
constexpr std::array<std::uint8_t, 3> kInterface = {30, 30, 30};

PlotAxes BranchingAxes(double length, double height, int width_px) {
  PlotAxes axes;
  axes.x_min = 0;
  axes.x_max = length;
  axes.y_min = 0;
  axes.y_max = height;
  axes.x_name = "x  (austenite at x = 0)";
  axes.y_name = "y";
  axes.text_scale =
      std::clamp(static_cast<int>(std::lround(width_px / 450.0)), 1, 3);
  return axes;
}

}  // namespace

RgbImage RenderConstruction(const Construction& construction, double height,
                            int width_px, int height_px) {
  RgbImage image(width_px, height_px);
  const double dx = construction.length / width_px;
  const double dy = height / height_px;
  for (int px = 0; px < width_px; ++px) {
    const double x = (px + 0.5) * dx;
    for (int py = 0; py < height_px; ++py) {
      const double y = height - (py + 0.5) * dy;
      double d = 0.0;
      const int v = construction.VariantAt(x, y, &d);
      std::uint8_t* rgb = image.at(px, py);
      const bool edge = d < 0.6 * dy;
      const std::array<std::uint8_t, 3>& color =
          edge ? kInterface : v > 0 ? kPlus : kMinus;
      for (int c = 0; c < 3; ++c) rgb[c] = color[c];
    }
  }
  return image;
}

RgbImage RenderSlope(const RelaxedField& field, int width_px, int height_px) {
  const RelaxedGrid& g = field.grid;
  RgbImage image(width_px, height_px);
  const std::vector<double>& xs = g.xs();
  for (int px = 0; px < width_px; ++px) {
    const double x = (px + 0.5) * g.length / width_px;
    // Nearest node row.
    int i = static_cast<int>(std::lower_bound(xs.begin(), xs.end(), x) -
                             xs.begin());
    i = std::clamp(i, 1, g.nx);
    if (i > 1 && x - xs[i - 1] < xs[i] - x) --i;
    for (int py = 0; py < height_px; ++py) {
      const double y = (height_px - py - 0.5) * g.height / height_px;
      // The staggered slope j covers [y_j, y_{j+1}].
      int j = static_cast<int>(std::floor(y / g.dy()));
      j = ((j % g.ny) + g.ny) % g.ny;
      const double v = std::clamp(field.uy(i, j), -1.0, 1.0);
      const double a = std::fabs(v);
      const std::array<std::uint8_t, 3>& base = v > 0 ? kPlus : kMinus;
      std::uint8_t* rgb = image.at(px, py);
      for (int c = 0; c < 3; ++c) {
        rgb[c] = static_cast<std::uint8_t>(
            std::lround(a * a * base[c] + (1.0 - a * a) * 255.0));
      }
    }
  }
  return image;
}

RgbImage ConstructionFigure(const Construction& construction, double height,
                            int width_px, int height_px) {
  PlotAxes axes = BranchingAxes(construction.length, height, width_px);
  axes.legend = {{kPlus, "u_y = +1"}, {kMinus, "u_y = -1"},
                 {kInterface, "interface"}};
  return FramePlot(
      RenderConstruction(construction, height, width_px, height_px), axes);
}

RgbImage SlopeFigure(const RelaxedField& field, int width_px, int height_px) {
  PlotAxes axes = BranchingAxes(field.grid.length, field.grid.height, width_px);
  axes.legend = {{kPlus, "u_y = +1"},
                 {{255, 255, 255}, "u_y = 0"},
                 {kMinus, "u_y = -1"}};
  return FramePlot(RenderSlope(field, width_px, height_px), axes);
}

}  // namespace shellspace::branching
