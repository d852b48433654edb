#include "tests/testing/render_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "shellspace/render/film_strip.h"
#include "shellspace/render/view.h"
#include "tests/testing/cli_output.h"

namespace shellspace::testing {

Mesh Box(double a, double b, double c) {
  Mesh mesh;
  mesh.positions.resize(8, 3);
  for (int i = 0; i < 8; ++i) {
    mesh.positions.row(i) << (i & 1 ? a : 0), (i & 2 ? b : 0), (i & 4 ? c : 0);
  }
  mesh.faces.resize(12, 3);
  mesh.faces << 0, 2, 1, 1, 2, 3,  // z = 0
      4, 5, 6, 5, 7, 6,            // z = c
      0, 1, 4, 1, 5, 4,            // y = 0
      2, 6, 3, 3, 6, 7,            // y = b
      0, 4, 2, 2, 4, 6,            // x = 0
      1, 3, 5, 3, 7, 5;            // x = a
  return mesh;
}

Mesh UnitSquareMesh() {
  Mesh mesh;
  mesh.positions.resize(4, 3);
  mesh.positions << -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0;
  mesh.faces.resize(2, 3);
  mesh.faces << 0, 1, 2, 0, 2, 3;
  return mesh;
}

std::vector<Positions> MeshAndMovedCopy(const Mesh& mesh, int axis,
                                        double shift) {
  Positions moved = mesh.positions;
  moved.col(axis).array() += shift;
  return {mesh.positions, moved};
}

bool IsColor(const std::uint8_t* p, const std::array<std::uint8_t, 3>& color) {
  return p[0] == color[0] && p[1] == color[1] && p[2] == color[2];
}

int CountUnlike(const RgbImage& image, const std::array<std::uint8_t, 3>& color,
                int left, int top, int width, int height) {
  int count = 0;
  for (int y = top; y < top + height; ++y) {
    for (int x = left; x < left + width; ++x) {
      count += !IsColor(image.at(x, y), color);
    }
  }
  return count;
}

std::pair<int, int> PngSize(const std::string& path) {
  const std::string bytes = Slurp(path);
  if (bytes.size() < 24 || bytes.compare(1, 3, "PNG") != 0) return {-1, -1};
  auto word = [&](int at) {
    int value = 0;
    for (int k = 0; k < 4; ++k) {
      value = value * 256 + static_cast<unsigned char>(bytes[at + k]);
    }
    return value;
  };
  return {word(16), word(20)};
}

RenderOptions CameraOptions(int width, int height, int supersample) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.supersample = supersample;
  options.up = UpAxis::kPlusY;
  options.labels = false;
  return options;
}

int CoveredPixels(const RgbImage& image, const RenderOptions& options,
                  int left, int top, int width, int height) {
  if (width < 0) width = image.width;
  if (height < 0) height = image.height;
  const auto& bg = options.lighting.background;
  const int r = static_cast<int>(std::lround(255 * bg.x()));
  const int g = static_cast<int>(std::lround(255 * bg.y()));
  const int b = static_cast<int>(std::lround(255 * bg.z()));
  int count = 0;
  for (int y = top; y < top + height; ++y) {
    for (int x = left; x < left + width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      if (p[0] != r || p[1] != g || p[2] != b) ++count;
    }
  }
  return count;
}

void ExpectSphereCoverage(const Mesh& sphere, const std::string& view,
                          double low, double high) {
  const int size = 240;
  RenderOptions options = CameraOptions(size, size);
  options.view = ParseView(view);
  const RgbImage image =
      RenderFilmStrip({sphere.positions}, sphere.faces, options);
  double radius = 0;
  for (int i = 0; i < sphere.num_vertices(); ++i) {
    radius = std::max(radius, sphere.positions.row(i).norm());
  }
  double extent = 2 * radius;
  if (view == "front") {
    const Eigen::RowVector3d box = sphere.positions.colwise().maxCoeff() -
                                   sphere.positions.colwise().minCoeff();
    extent = std::max(box.x(), box.y());
  }
  const double scale = 0.9 * size / extent;
  const double expected = M_PI * std::pow(scale * radius, 2) / (size * size);
  const double actual =
      static_cast<double>(CoveredPixels(image, options)) / (size * size);
  EXPECT_GT(actual / expected, low) << view << " " << actual << " " << expected;
  EXPECT_LT(actual / expected, high)
      << view << " " << actual << " " << expected;
}

}  // namespace shellspace::testing
