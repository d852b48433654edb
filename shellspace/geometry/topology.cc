#include "shellspace/geometry/topology.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace shellspace {

namespace {

// A map from vertex pairs (a, b), a, b >= 0, to ints: open addressing with
// linear probing in one flat table sized for `capacity` pairs (load at most
// 1/2), no erase. On a mesh's 3 #F half-edges it replaces std::map's node
// per pair (an allocation and a cache miss per lookup).
class PairTable {
 public:
  explicit PairTable(size_t capacity) {
    int bits = 4;
    while ((size_t{1} << bits) < 2 * capacity) ++bits;
    shift_ = 64 - bits;
    keys_.assign(size_t{1} << bits, kEmpty);
    values_.resize(keys_.size());
  }
  // The value of (a, b), or nullptr if absent.
  const int* Find(int a, int b) const {
    const uint64_t key = Key(a, b);
    for (size_t i = Home(key);; i = (i + 1) & (keys_.size() - 1)) {
      if (keys_[i] == key) return &values_[i];
      if (keys_[i] == kEmpty) return nullptr;
    }
  }
  // Stores (a, b) -> value unless (a, b) is present; the stored value, and
  // whether it was inserted.
  std::pair<int*, bool> Emplace(int a, int b, int value) {
    const uint64_t key = Key(a, b);
    for (size_t i = Home(key);; i = (i + 1) & (keys_.size() - 1)) {
      if (keys_[i] == key) return {&values_[i], false};
      if (keys_[i] == kEmpty) {
        keys_[i] = key;
        values_[i] = value;
        return {&values_[i], true};
      }
    }
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t{0};
  static uint64_t Key(int a, int b) {
    return (uint64_t{static_cast<uint32_t>(a)} << 32) |
           static_cast<uint32_t>(b);
  }
  size_t Home(uint64_t key) const {  // Fibonacci hashing
    return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  int shift_ = 60;
  std::vector<uint64_t> keys_;
  std::vector<int> values_;
};

// Throws InputError unless face f's vertices lie in [0, n) and are distinct.
void CheckFace(const Mesh& mesh, int f, int n) {
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
}

// Adds face f's three half-edges to `half_edges` (directed (a, b) -> face)
// and its edges to topo->edges and topo->edge_faces (`edge_index`: (min,
// max) -> edge); throws InputError for a half-edge already present or an
// edge with a third face.
void AddFaceEdges(const Mesh& mesh, int f, PairTable* half_edges,
                  PairTable* edge_index, Topology* topo) {
  for (int s = 0; s < 3; ++s) {
    const int u = mesh.faces(f, s), w = mesh.faces(f, (s + 1) % 3);
    const auto half_edge = half_edges->Emplace(u, w, f);
    if (!half_edge.second) {
      throw InputError("non-manifold or inconsistently oriented edge (" +
                       std::to_string(u) + ", " + std::to_string(w) +
                       ") in faces " + std::to_string(*half_edge.first) +
                       " and " + std::to_string(f));
    }
    const auto key = std::make_pair(std::min(u, w), std::max(u, w));
    const auto edge = edge_index->Emplace(key.first, key.second,
                                          static_cast<int>(topo->edges.size()));
    if (edge.second) {
      topo->edges.push_back({key.first, key.second});
      topo->edge_faces.push_back({f, -1});
    } else {
      auto& ef = topo->edge_faces[*edge.first];
      if (ef[1] != -1) {
        throw InputError("non-manifold edge (" + std::to_string(key.first) +
                         ", " + std::to_string(key.second) +
                         ") shared by more than two faces");
      }
      ef[1] = f;
    }
  }
}

// The vertex of face f that is neither u nor w (-1 if none).
int OppositeVertex(const Mesh& mesh, int f, int u, int w) {
  for (int c = 0; c < 3; ++c) {
    const int v = mesh.faces(f, c);
    if (v != u && v != w) return v;
  }
  return -1;
}

// Fills topo->boundary_edges and topo->interior_edges (one flap per edge
// with two faces, oriented as in its face_0) from its edges and
// `half_edges`.
void BuildFlaps(const Mesh& mesh, const PairTable& half_edges, Topology* topo) {
  for (int e = 0; e < static_cast<int>(topo->edges.size()); ++e) {
    const auto& ef = topo->edge_faces[e];
    if (ef[1] == -1) {
      topo->boundary_edges.push_back(e);
      continue;
    }
    const int u = topo->edges[e][0], w = topo->edges[e][1];
    // Orient i -> j as in face_0.
    int f0 = ef[0], f1 = ef[1];
    int i = u, j = w;
    const int* face_of_uw = half_edges.Find(u, w);
    if (face_of_uw != nullptr && *face_of_uw == f0) {
      i = u, j = w;
    } else {
      i = w, j = u;
    }
    EdgeFlap flap;
    flap.i = i;
    flap.j = j;
    flap.face_0 = f0;
    flap.face_1 = f1;
    flap.k = OppositeVertex(mesh, f0, i, j);
    flap.l = OppositeVertex(mesh, f1, i, j);
    topo->interior_edges.push_back(flap);
  }
}

}  // namespace

Topology Topology::Build(const Mesh& mesh) {
  Topology topo;
  const int n = mesh.num_vertices();
  topo.vertex_faces.assign(n, {});
  const size_t half_edge_count = 3 * static_cast<size_t>(mesh.num_faces());
  // Directed half-edge (a, b) -> face containing it with that orientation.
  PairTable half_edges(half_edge_count);
  PairTable edge_index(half_edge_count);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    CheckFace(mesh, f, n);
    for (int c = 0; c < 3; ++c) {
      topo.vertex_faces[mesh.faces(f, c)].push_back(f);
    }
    AddFaceEdges(mesh, f, &half_edges, &edge_index, &topo);
  }
  BuildFlaps(mesh, half_edges, &topo);
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
