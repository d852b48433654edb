#include "shellspace/geometry/procedural_shapes.h"

#include <algorithm>
#include <cmath>

namespace shellspace {

Mesh MakeFinger(double radius, double length, int around, int rings,
                int cap_rings) {
  const double pi = std::acos(-1.0);
  std::vector<Eigen::RowVector3d> points;
  // Tube rings r = 0..rings-1 at y in [0, length], then cap rings.
  const int total_rings = rings + cap_rings;
  for (int r = 0; r < total_rings; ++r) {
    double y, rho;
    if (r < rings) {
      y = length * r / (rings - 1);
      rho = radius;
    } else {
      const double phi = 0.5 * pi * (r - rings + 1) / (cap_rings + 1);
      y = length + radius * std::sin(phi);
      rho = radius * std::cos(phi);
    }
    for (int a = 0; a < around; ++a) {
      const double t = 2 * pi * a / around;
      points.emplace_back(rho * std::cos(t), y, -rho * std::sin(t));
    }
  }
  points.emplace_back(0, length + radius, 0);  // pole
  std::vector<std::array<int, 3>> faces;
  auto id = [&](int r, int a) { return r * around + (a % around); };
  for (int r = 0; r + 1 < total_rings; ++r) {
    for (int a = 0; a < around; ++a) {
      faces.push_back({id(r, a), id(r, a + 1), id(r + 1, a + 1)});
      faces.push_back({id(r, a), id(r + 1, a + 1), id(r + 1, a)});
    }
  }
  const int pole = static_cast<int>(points.size()) - 1;
  for (int a = 0; a < around; ++a) {
    faces.push_back({id(total_rings - 1, a), id(total_rings - 1, a + 1), pole});
  }
  Mesh mesh;
  mesh.positions.resize(points.size(), 3);
  for (size_t i = 0; i < points.size(); ++i) mesh.positions.row(i) = points[i];
  mesh.faces.resize(faces.size(), 3);
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) mesh.faces(f, c) = faces[f][c];
  }
  return mesh;
}

std::vector<int> FingerBaseVertices(int around, int count) {
  std::vector<int> base;
  for (int i = 0; i < around * count; ++i) base.push_back(i);
  return base;
}

Positions BendAlongY(const Positions& shape, double length, double angle) {
  const double bend_radius = length / angle;
  Positions out = shape;
  for (int i = 0; i < shape.rows(); ++i) {
    const double x = shape(i, 0), y = shape(i, 1);
    const double alpha = angle * std::clamp(y, 0.0, length) / length;
    const double beyond = std::max(0.0, y - length);
    const double r = bend_radius - x;
    // Point on the rotated cross-section plus the rigid continuation.
    out(i, 0) = bend_radius - r * std::cos(alpha) + beyond * std::sin(alpha);
    out(i, 1) = r * std::sin(alpha) + beyond * std::cos(alpha);
  }
  return out;
}

}  // namespace shellspace
