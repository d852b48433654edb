// Midpoint subdivision of shells with one connectivity: large test meshes
// generated from the shared data (each triangle split into four).
#ifndef SHELLSPACE_GEOMETRY_SUBDIVISION_H_
#define SHELLSPACE_GEOMETRY_SUBDIVISION_H_

#include <array>
#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// One level of midpoint subdivision of `faces` (#F x 3 on `num_vertices`
// vertices): vertex v keeps index v; the midpoint of edge e = (i, j) becomes
// vertex num_vertices + e; triangle (a, b, c) becomes (a, m_ab, m_ca),
// (m_ab, b, m_bc), (m_ca, m_bc, c), (m_ab, m_bc, m_ca), orientation kept.
struct MidpointSubdivision {
  Faces faces;                              // #4F x 3
  std::vector<std::array<int, 2>> parents;  // per new vertex: edge (i, j)
  int num_coarse_vertices = 0;

  explicit MidpointSubdivision(const Faces& coarse, int num_vertices);
  int num_vertices() const {
    return num_coarse_vertices + static_cast<int>(parents.size());
  }
  // The subdivided shape: old vertices in place, midpoints of the edges.
  Positions Apply(const Positions& coarse) const;
  // The vertices of the subdivided mesh in `mask` (old ones kept) plus the
  // midpoints whose two endpoints are both in it; sorted.
  std::vector<int> CarryMask(const std::vector<int>& mask) const;
};

// The vertices within `rings` edge steps of `seed` (the seed itself at 0),
// sorted: a "k-ring" Dirichlet mask around one vertex.
std::vector<int> VertexRing(const Faces& faces, int num_vertices, int seed,
                            int rings);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_SUBDIVISION_H_
