// A vertex set as per-vertex flags: the form a loop over all vertices reads
// a mask in.
#ifndef SHELLSPACE_GEOMETRY_VERTEX_FLAGS_H_
#define SHELLSPACE_GEOMETRY_VERTEX_FLAGS_H_

#include <vector>

namespace shellspace {

// Per vertex of a mesh of `num_vertices`: 1 if it is in `vertices` (indices
// in [0, num_vertices), as a validated mask has them), else 0.
inline std::vector<char> VertexFlags(int num_vertices,
                                     const std::vector<int>& vertices) {
  std::vector<char> flags(num_vertices, 0);
  for (int v : vertices) flags[v] = 1;
  return flags;
}

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_VERTEX_FLAGS_H_
