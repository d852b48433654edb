// A vertex set as per-vertex flags: the form a loop over all vertices reads
// a mask in.
#ifndef SHELLSPACE_GEOMETRY_VERTEX_FLAGS_H_
#define SHELLSPACE_GEOMETRY_VERTEX_FLAGS_H_

#include <Eigen/Core>
#include <algorithm>
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

// max |g| over the three coordinates of every vertex whose flag is 0 (g
// has 3 flags.size() entries, vertex after vertex); 0 if there is none.
inline double UnflaggedMaxNorm(const Eigen::VectorXd& g,
                               const std::vector<char>& flags) {
  double norm = 0;
  for (int v = 0; v < static_cast<int>(flags.size()); ++v) {
    if (!flags[v])
      norm = std::max(norm, g.segment<3>(3 * v).cwiseAbs().maxCoeff());
  }
  return norm;
}

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_VERTEX_FLAGS_H_
