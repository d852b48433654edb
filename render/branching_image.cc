#include "shellspace/render/branching_image.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace shellspace::branching {

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
      if (edge) {
        rgb[0] = 30, rgb[1] = 30, rgb[2] = 30;
      } else if (v > 0) {
        rgb[0] = 235, rgb[1] = 140, rgb[2] = 40;
      } else {
        rgb[0] = 45, rgb[1] = 95, rgb[2] = 200;
      }
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
      const double base[3] = {v > 0 ? 235.0 : 45.0, v > 0 ? 140.0 : 95.0,
                              v > 0 ? 40.0 : 200.0};
      std::uint8_t* rgb = image.at(px, py);
      for (int c = 0; c < 3; ++c) {
        rgb[c] = static_cast<std::uint8_t>(
            std::lround(a * a * base[c] + (1.0 - a * a) * 255.0));
      }
    }
  }
  return image;
}

}  // namespace shellspace::branching
