#include "shellspace/geometry/validation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>

namespace shellspace {

namespace {

void CheckFinite(const Mesh& mesh, const std::string& name) {
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(mesh.positions(i, c))) {
        throw InputError(name + ": vertex " + std::to_string(i) +
                         " has a non-finite coordinate");
      }
    }
  }
}

// "%.3g" of a number (std::to_string prints 1e-201 as 0.000000).
std::string Short(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

// The energies use up to fourth powers of lengths (det of the first
// fundamental form, its inverse), so coordinates must be far from overflow
// and the mesh far from underflow: |x| <= kLargestCoordinate and a
// bounding-box diagonal >= kSmallestExtent. Anything in between is scaled
// exactly by the calculus (W_mem ~ length^2, W_bend scale-free).
constexpr double kLargestCoordinate = 1e30;
constexpr double kSmallestExtent = 1e-30;

void CheckScale(const Mesh& mesh, const std::string& name) {
  const double largest = mesh.positions.cwiseAbs().maxCoeff();
  if (largest > kLargestCoordinate) {
    throw InputError(name + ": coordinates up to " + Short(largest) +
                     " (at most " + Short(kLargestCoordinate) +
                     ": the energies use fourth powers of lengths and would "
                     "overflow; rescale the mesh)");
  }
  const double extent =
      (mesh.positions.colwise().maxCoeff() - mesh.positions.colwise().minCoeff())
          .norm();
  if (extent < kSmallestExtent) {
    throw InputError(name + ": the mesh spans only " + Short(extent) +
                     " (bounding-box diagonal; at least " +
                     Short(kSmallestExtent) +
                     ": the energies use fourth powers of lengths and would "
                     "underflow; rescale the mesh)");
  }
}

void CheckTriangles(const Mesh& mesh, const Topology& topology,
                    const std::string& name) {
  double mean_sq = 0;
  for (const auto& e : topology.edges) {
    mean_sq += (mesh.vertex(e[0]) - mesh.vertex(e[1])).squaredNorm();
  }
  mean_sq /= std::max<size_t>(1, topology.edges.size());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = mesh.vertex(mesh.faces(f, 0));
    const Eigen::Vector3d b = mesh.vertex(mesh.faces(f, 1));
    const Eigen::Vector3d c = mesh.vertex(mesh.faces(f, 2));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    if (!(area > 1e-12 * mean_sq)) {
      throw InputError(name + ": triangle " + std::to_string(f) +
                       " is degenerate (area " + Short(area) +
                       ", mean squared edge length " + Short(mean_sq) + ")");
    }
  }
}

// Faces with the same three vertices (in either orientation).
void CheckDuplicateFaces(const Mesh& mesh, const std::string& name) {
  std::map<std::array<int, 3>, int> seen;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    std::array<int, 3> key{mesh.faces(f, 0), mesh.faces(f, 1),
                           mesh.faces(f, 2)};
    std::sort(key.begin(), key.end());
    const auto inserted = seen.emplace(key, f);
    if (!inserted.second) {
      throw InputError(name + ": face " + std::to_string(f) +
                       " duplicates face " +
                       std::to_string(inserted.first->second) + " (vertices " +
                       std::to_string(key[0]) + ", " + std::to_string(key[1]) +
                       ", " + std::to_string(key[2]) + ")");
    }
  }
}

void CheckNoIsolatedVertex(const Mesh& mesh, const Topology& topology,
                           const std::string& name) {
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (topology.vertex_faces[v].empty()) {
      throw InputError(name + ": vertex " + std::to_string(v) +
                       " is isolated (in no face); remove it from the mesh");
    }
  }
}

}  // namespace

Topology ValidateMeshStructure(const Mesh& mesh, const std::string& name) {
  if (mesh.num_vertices() == 0 || mesh.num_faces() == 0) {
    throw InputError(
        name + ": mesh has no " +
        std::string(mesh.num_vertices() == 0 ? "vertices" : "faces"));
  }
  CheckFinite(mesh, name);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.faces(f, c);
      if (v < 0 || v >= mesh.num_vertices()) {
        throw InputError(name + ": face " + std::to_string(f) +
                         " references vertex " + std::to_string(v) +
                         ", the mesh has " +
                         std::to_string(mesh.num_vertices()) + " vertices");
      }
    }
  }
  CheckDuplicateFaces(mesh, name);
  Topology topology;
  try {
    topology = Topology::Build(mesh);
  } catch (const InputError& error) {
    throw InputError(name + ": " + error.what());
  }
  CheckNoIsolatedVertex(mesh, topology, name);
  return topology;
}

Topology ValidateShell(const Mesh& mesh, const std::string& name) {
  Topology topology = ValidateMeshStructure(mesh, name);
  CheckScale(mesh, name);
  CheckTriangles(mesh, topology, name);
  return topology;
}

void ValidateShellPositions(const Mesh& mesh, const Topology& topology,
                            const std::string& name) {
  CheckFinite(mesh, name);
  CheckScale(mesh, name);
  CheckTriangles(mesh, topology, name);
}

void CheckCompatible(const Mesh& mesh, const std::string& name,
                     const Mesh& other, const std::string& other_name) {
  const std::string prefix =
      "incompatible connectivity of " + name + " and " + other_name + ": ";
  if (mesh.num_vertices() != other.num_vertices()) {
    throw InputError(prefix + std::to_string(mesh.num_vertices()) + " vs " +
                     std::to_string(other.num_vertices()) + " vertices");
  }
  if (mesh.num_faces() != other.num_faces()) {
    throw InputError(prefix + std::to_string(mesh.num_faces()) + " vs " +
                     std::to_string(other.num_faces()) + " faces");
  }
  for (int f = 0; f < mesh.num_faces(); ++f) {
    bool same = false;
    for (int shift = 0; shift < 3 && !same; ++shift) {
      same = true;
      for (int c = 0; c < 3; ++c) {
        same &= mesh.faces(f, c) == other.faces(f, (c + shift) % 3);
      }
    }
    if (!same) {
      throw InputError(prefix + "face " + std::to_string(f) + " differs");
    }
  }
}

SliverFaces FindSliverFaces(const Mesh& mesh) {
  SliverFaces slivers;
  const int m = static_cast<int>(mesh.faces.rows());
  if (m == 0) return slivers;
  std::vector<double> area(m), degrees(m);
  double mean = 0;
  for (int f = 0; f < m; ++f) {
    const Eigen::Vector3d a = mesh.positions.row(mesh.faces(f, 0)).transpose();
    const Eigen::Vector3d b = mesh.positions.row(mesh.faces(f, 1)).transpose();
    const Eigen::Vector3d c = mesh.positions.row(mesh.faces(f, 2)).transpose();
    area[f] = 0.5 * (b - a).cross(c - a).norm();
    mean += area[f] / m;
    double smallest = 180;
    const Eigen::Vector3d corners[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d u = corners[(i + 1) % 3] - corners[i];
      const Eigen::Vector3d v = corners[(i + 2) % 3] - corners[i];
      const double angle =
          std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / M_PI;
      smallest = std::min(smallest, angle);
    }
    degrees[f] = smallest;
  }
  for (int f = 0; f < m; ++f) {
    const double fraction = mean > 0 ? area[f] / mean : 0;
    slivers.smallest_area_fraction =
        std::min(slivers.smallest_area_fraction, fraction);
    slivers.smallest_degrees = std::min(slivers.smallest_degrees, degrees[f]);
    if (fraction < kSliverAreaFraction || degrees[f] < kSliverMinDegrees) {
      slivers.faces.push_back(f);
    }
  }
  // Folds: the faces of each interior edge, by the edge's sorted vertices.
  std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;
  for (int f = 0; f < m; ++f) {
    for (int c = 0; c < 3; ++c) {
      const int i = mesh.faces(f, c), j = mesh.faces(f, (c + 1) % 3);
      faces_of_edge[{std::min(i, j), std::max(i, j)}].push_back(f);
    }
  }
  const auto normal = [&](int f) {
    const Eigen::Vector3d a = mesh.positions.row(mesh.faces(f, 0)).transpose();
    const Eigen::Vector3d b = mesh.positions.row(mesh.faces(f, 1)).transpose();
    const Eigen::Vector3d c = mesh.positions.row(mesh.faces(f, 2)).transpose();
    return Eigen::Vector3d((b - a).cross(c - a));
  };
  for (const auto& [edge, faces] : faces_of_edge) {
    if (faces.size() != 2) continue;
    const Eigen::Vector3d n0 = normal(faces[0]), n1 = normal(faces[1]);
    const double degrees =
        std::atan2(n0.cross(n1).norm(), n0.dot(n1)) * 180.0 / M_PI;
    if (!std::isfinite(degrees)) continue;
    slivers.largest_fold_degrees =
        std::max(slivers.largest_fold_degrees, degrees);
    if (degrees > kFoldDegrees) {
      slivers.folds.emplace_back(std::min(faces[0], faces[1]),
                                 std::max(faces[0], faces[1]));
    }
  }
  std::sort(slivers.folds.begin(), slivers.folds.end());
  return slivers;
}

std::string SliverFaces::Describe() const {
  std::string text;
  if (!faces.empty()) text = DescribeSlivers();
  if (!folds.empty()) {
    char rule[96];
    std::snprintf(rule, sizeof rule,
                  " (triangles turned more than %g degrees against each "
                  "other): faces ",
                  kFoldDegrees);
    text += std::string(text.empty() ? "" : "; ") +
            std::to_string(folds.size()) + " folded edge" +
            (folds.size() > 1 ? "s" : "") + rule;
    for (size_t i = 0; i < folds.size() && i < 8; ++i) {
      text += (i ? ", " : "") + std::to_string(folds[i].first) + " and " +
              std::to_string(folds[i].second);
    }
    if (folds.size() > 8) text += ", ...";
  }
  return text;
}

std::string SliverFaces::DescribeSlivers() const {
  char rule[96];
  std::snprintf(rule, sizeof rule,
                " (area below %g%% of the mean or an angle below %g "
                "degree): ",
                100 * kSliverAreaFraction, kSliverMinDegrees);
  std::string text = std::to_string(faces.size()) + " sliver triangle" +
                     (faces.size() > 1 ? "s" : "") + rule;
  for (size_t i = 0; i < faces.size() && i < 8; ++i) {
    text += (i ? ", " : "") + std::to_string(faces[i]);
  }
  if (faces.size() > 8) text += ", ...";
  return text;
}

}  // namespace shellspace
