#include "shellspace/cost_functions/shell/shell_space_renumbering.h"

#include <algorithm>
#include <array>
#include <unordered_map>

#include "shellspace/geometry/locality_order.h"

namespace shellspace {

Positions RenumberedShellSpace::ToRenumbered(const Positions& shape) const {
  Positions out(shape.rows(), 3);
  for (int v = 0; v < shape.rows(); ++v) out.row(new_vertex[v]) = shape.row(v);
  return out;
}

Positions RenumberedShellSpace::ToOriginal(const Positions& shape) const {
  Positions out(shape.rows(), 3);
  for (int v = 0; v < shape.rows(); ++v) out.row(v) = shape.row(new_vertex[v]);
  return out;
}

std::vector<int> RenumberedShellSpace::ToRenumbered(
    const std::vector<int>& vertices) const {
  std::vector<int> out;
  out.reserve(vertices.size());
  for (int v : vertices) out.push_back(new_vertex[v]);
  std::sort(out.begin(), out.end());
  return out;
}

RenumberedShellSpace RenumberForLocality(const ShellSpace& space) {
  const int n = space.num_vertices;
  const Topology& topology = space.topology;
  RenumberedShellSpace r;
  std::vector<std::vector<int>> neighbours(n);
  for (const std::array<int, 2>& e : topology.edges) {
    neighbours[e[0]].push_back(e[1]);
    neighbours[e[1]].push_back(e[0]);
  }
  r.new_vertex = CuthillMcKeeRanks(neighbours);
  r.original_vertex.resize(n);
  for (int v = 0; v < n; ++v) r.original_vertex[r.new_vertex[v]] = v;

  // Faces by their sorted new vertices, ties (none in a valid mesh) by index.
  const int num_faces = static_cast<int>(space.faces.rows());
  std::vector<std::array<int, 3>> key(num_faces);
  for (int f = 0; f < num_faces; ++f) {
    for (int c = 0; c < 3; ++c) key[f][c] = r.new_vertex[space.faces(f, c)];
    std::sort(key[f].begin(), key[f].end());
  }
  r.original_face.resize(num_faces);
  for (int f = 0; f < num_faces; ++f) r.original_face[f] = f;
  std::stable_sort(r.original_face.begin(), r.original_face.end(),
                   [&](int a, int b) { return key[a] < key[b]; });
  Mesh mesh;
  mesh.positions = Positions::Zero(n, 3);
  mesh.faces.resize(num_faces, 3);
  for (int f = 0; f < num_faces; ++f) {
    for (int c = 0; c < 3; ++c) {
      mesh.faces(f, c) = r.new_vertex[space.faces(r.original_face[f], c)];
    }
  }
  const Topology renumbered = Topology::Build(mesh);

  // The caller's interior edge of each renumbered one, by its vertex pair.
  const auto pair_key = [n](int a, int b) {
    return static_cast<long long>(std::min(a, b)) * n + std::max(a, b);
  };
  std::unordered_map<long long, int> interior_edge;
  interior_edge.reserve(topology.interior_edges.size());
  for (size_t e = 0; e < topology.interior_edges.size(); ++e) {
    const EdgeFlap& flap = topology.interior_edges[e];
    interior_edge.emplace(pair_key(flap.i, flap.j), static_cast<int>(e));
  }
  ElementLabels labels;
  labels.vertices = r.original_vertex;
  labels.faces = r.original_face;
  labels.interior_edges.reserve(renumbered.interior_edges.size());
  for (const EdgeFlap& flap : renumbered.interior_edges) {
    labels.interior_edges.push_back(interior_edge.at(
        pair_key(r.original_vertex[flap.i], r.original_vertex[flap.j])));
  }
  r.space = ShellSpace(mesh, renumbered, space.material, labels);
  return r;
}

}  // namespace shellspace
