#include "tests/testing/render_fixtures.h"

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

}  // namespace shellspace::testing
