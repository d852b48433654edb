#include "shellspace/problems/branching/field_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "shellspace/geometry/mesh.h"

namespace shellspace::branching {

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

void WriteTextFile(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary);
    out << text;
    if (!out) throw InputError("cannot write " + path);
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw InputError("cannot write " + path);
  }
}

std::string FieldCsv(const RelaxedField& field) {
  const RelaxedGrid& g = field.grid;
  std::ostringstream out;
  out.precision(12);
  out << "i,j,x,y,u,u_y\n";
  for (int i = 0; i <= g.nx; ++i) {
    for (int j = 0; j < g.ny; ++j) {
      out << i << ',' << j << ',' << g.x(i) << ',' << g.y(j) << ','
          << field.at(i, j) << ',' << field.uy(i, j) << '\n';
    }
  }
  return out.str();
}

std::string InterfaceCsv(const RelaxedField& field,
                         const std::vector<int>& counts) {
  std::ostringstream out;
  out.precision(12);
  out << "i,x,interfaces\n";
  for (size_t k = 0; k < counts.size(); ++k) {
    out << k + 1 << ',' << field.grid.x(static_cast<int>(k) + 1) << ','
        << counts[k] << '\n';
  }
  return out.str();
}

}  // namespace shellspace::branching
