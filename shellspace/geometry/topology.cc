#include "shellspace/geometry/topology.h"

#include <map>
#include <string>

namespace shellspace {

Topology Topology::Build(const Mesh& mesh) {
  Topology topo;
  const int n = mesh.num_vertices();
  topo.vertex_faces.assign(n, {});
  // Directed half-edge (a, b) -> face containing it with that orientation.
  std::map<std::pair<int, int>, int> half_edges;
  std::map<std::pair<int, int>, int> edge_index;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.faces(f, c);
      if (v < 0 || v >= n) {
        throw InputError("face " + std::to_string(f) + " references vertex " +
                         std::to_string(v) + " but the mesh has " +
                         std::to_string(n) + " vertices");
      }
    }
    const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    if (a == b || b == c || a == c) {
      throw InputError("face " + std::to_string(f) +
                       " repeats a vertex (degenerate triangle)");
    }
    for (int v : {a, b, c}) topo.vertex_faces[v].push_back(f);
    for (int s = 0; s < 3; ++s) {
      const int u = mesh.faces(f, s), w = mesh.faces(f, (s + 1) % 3);
      if (!half_edges.emplace(std::make_pair(u, w), f).second) {
        throw InputError("non-manifold or inconsistently oriented edge (" +
                         std::to_string(u) + ", " + std::to_string(w) +
                         ") in faces " + std::to_string(half_edges[{u, w}]) +
                         " and " + std::to_string(f));
      }
      const auto key = std::make_pair(std::min(u, w), std::max(u, w));
      auto it = edge_index.find(key);
      if (it == edge_index.end()) {
        edge_index.emplace(key, static_cast<int>(topo.edges.size()));
        topo.edges.push_back({key.first, key.second});
        topo.edge_faces.push_back({f, -1});
      } else {
        auto& ef = topo.edge_faces[it->second];
        if (ef[1] != -1) {
          throw InputError("non-manifold edge (" + std::to_string(key.first) +
                           ", " + std::to_string(key.second) +
                           ") shared by more than two faces");
        }
        ef[1] = f;
      }
    }
  }
  auto opposite = [&](int f, int u, int w) {
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.faces(f, c);
      if (v != u && v != w) return v;
    }
    return -1;
  };
  for (int e = 0; e < static_cast<int>(topo.edges.size()); ++e) {
    const auto& ef = topo.edge_faces[e];
    if (ef[1] == -1) {
      topo.boundary_edges.push_back(e);
      continue;
    }
    const int u = topo.edges[e][0], w = topo.edges[e][1];
    // Orient i -> j as in face_0.
    int f0 = ef[0], f1 = ef[1];
    int i = u, j = w;
    if (half_edges.count({u, w}) && half_edges.at({u, w}) == f0) {
      i = u, j = w;
    } else {
      i = w, j = u;
    }
    EdgeFlap flap;
    flap.i = i;
    flap.j = j;
    flap.face_0 = f0;
    flap.face_1 = f1;
    flap.k = opposite(f0, i, j);
    flap.l = opposite(f1, i, j);
    topo.interior_edges.push_back(flap);
  }
  return topo;
}

double MeanEdgeLength(const Mesh& mesh, const Topology& topology) {
  double sum = 0;
  for (const auto& e : topology.edges) {
    sum += (mesh.positions.row(e[0]) - mesh.positions.row(e[1])).norm();
  }
  return topology.edges.empty() ? 0.0 : sum / topology.edges.size();
}

}  // namespace shellspace
