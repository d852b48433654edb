#include "shellspace/geometry/procedural_shapes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>

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

Mesh MakeIcosphere(int level, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::RowVector3d> points = {
      {-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
      {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> faces = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : points) p.normalize();
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      points.push_back((points[a] + points[b]).normalized());
      const int id = static_cast<int>(points.size()) - 1;
      midpoint.emplace(key, id);
      return id;
    };
    std::vector<std::array<int, 3>> finer;
    finer.reserve(4 * faces.size());
    for (const auto& f : faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({ab, f[1], bc});
      finer.push_back({ca, bc, f[2]});
      finer.push_back({ab, bc, ca});
    }
    faces.swap(finer);
  }
  Mesh mesh;
  mesh.positions.resize(points.size(), 3);
  for (size_t v = 0; v < points.size(); ++v) {
    mesh.positions.row(v) = radius * points[v];
  }
  mesh.faces.resize(faces.size(), 3);
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) mesh.faces(f, c) = faces[f][c];
  }
  return mesh;
}

Mesh MakeEquilateralSheet(int columns, int rows, double h) {
  Mesh mesh;
  const int per_row = columns + 1;
  mesh.positions.resize((rows + 1) * per_row, 3);
  for (int r = 0; r <= rows; ++r) {
    for (int c = 0; c <= columns; ++c) {
      mesh.positions.row(r * per_row + c) << (c + (r % 2 ? 0.5 : 0.0)) * h,
          r * h * std::sqrt(3.0) / 2, 0.0;
    }
  }
  mesh.faces.resize(2 * columns * rows, 3);
  int f = 0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      const int a = r * per_row + c, b = a + 1;         // row r
      const int d = (r + 1) * per_row + c, e = d + 1;  // row r + 1
      if (r % 2 == 0) {  // row r + 1 shifted right: a b d, b e d
        mesh.faces.row(f++) << a, b, d;
        mesh.faces.row(f++) << b, e, d;
      } else {  // row r shifted right: a e d, a b e
        mesh.faces.row(f++) << a, e, d;
        mesh.faces.row(f++) << a, b, e;
      }
    }
  }
  return mesh;
}

Positions RollOntoCylinder(const Positions& flat, double radius) {
  Positions out(flat.rows(), 3);
  for (int v = 0; v < flat.rows(); ++v) {
    const double phi = flat(v, 0) / radius;
    out.row(v) << radius * std::sin(phi), flat(v, 1),
        radius * std::cos(phi) - radius;
  }
  return out;
}

Positions JitterTangentially(const Positions& shape, const Positions& normals,
                             double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double pi = std::acos(-1.0);
  Positions out = shape;
  for (int v = 0; v < shape.rows(); ++v) {
    const Eigen::Vector3d n = normals.row(v).transpose();
    Eigen::Vector3d t1 = n.unitOrthogonal();
    const Eigen::Vector3d t2 = n.cross(t1);
    const double angle = 2 * pi * unit(rng);
    const double length = amplitude * unit(rng);
    out.row(v) +=
        (length * (std::cos(angle) * t1 + std::sin(angle) * t2)).transpose();
  }
  return out;
}

}  // namespace shellspace
