// Edge structure of a triangle mesh: edges, interior-edge flaps, boundary.
#ifndef SHELLSPACE_GEOMETRY_TOPOLOGY_H_
#define SHELLSPACE_GEOMETRY_TOPOLOGY_H_

#include <array>
#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// The four vertices of an interior edge and its two faces. Layout (the
// "edge flap", as in Discrete Shells):
//
//            k (opposite in face_0)
//           / \ .
//          /   \ .
//         i-----j      the shared edge, oriented i -> j as in face_0
//          \   /
//           \ /
//            l (opposite in face_1)
//
// face_0 = (i, j, k) up to cyclic rotation, face_1 = (j, i, l) up to cyclic
// rotation. The signed dihedral angle of the flap is measured with this
// orientation (geometry/element_geometry.h).
struct EdgeFlap {
  int i, j, k, l;
  int face_0, face_1;
};

// Edges of a mesh. `edges[e]` = (min, max) vertex pair; `edge_faces[e]` the one
// or two adjacent faces (second = -1 on the boundary).
struct Topology {
  std::vector<std::array<int, 2>> edges;
  std::vector<std::array<int, 2>> edge_faces;
  std::vector<EdgeFlap> interior_edges;        // one flap per interior edge
  std::vector<int> boundary_edges;             // indices into `edges`
  std::vector<std::vector<int>> vertex_faces;  // faces around each vertex

  // Builds the topology. Throws InputError for out-of-range indices, repeated
  // vertices in a face, an edge shared by more than two faces (non-manifold),
  // or two faces inducing the same orientation on an edge (inconsistently
  // oriented or non-manifold).
  static Topology Build(const Mesh& mesh);
};

// The mean length of the mesh's edges (topology.edges) at its positions.
double MeanEdgeLength(const Mesh& mesh, const Topology& topology);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_TOPOLOGY_H_
