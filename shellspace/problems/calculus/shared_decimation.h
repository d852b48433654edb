// Decimation of several shells that share one connectivity (docs/math.md,
// "Multiresolution"): one coarse connectivity for all of them, chosen by the
// quadric error summed over every shape.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_SHARED_DECIMATION_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_SHARED_DECIMATION_H_

#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// The coarse level of a decimation. Half-edge collapses only: every coarse
// vertex is a fine vertex that survived, at its fine position in every shape.
struct SharedDecimation {
  std::vector<int> survivors;  // coarse vertex i is fine vertex survivors[i]
  Faces faces;                 // #Fc x 3, coarse vertex indices
  // The coarse shells: shape s restricted to the survivors (#survivors x 3).
  std::vector<Positions> shapes;

  int num_vertices() const { return static_cast<int>(survivors.size()); }
};

// Collapses half-edges of the shared connectivity `faces` until at most
// `target_vertices` remain (or no collapse is legal). The priority of a
// collapse v0 -> v1 is the quadric error summed over the shapes,
//   sum_s (Q_s[v0] + Q_s[v1])(x_s(v1)),
// Q_s[v] the area-weighted sum of the squared distances to the planes of the
// faces of shape s merged into v (Garland-Heckbert, per shape). A collapse is
// illegal if, in any shape, it turns a remaining face's normal by more than
// 60 degrees or shrinks its area below 1e-3 of its old area; vertices in
// `locked` (e.g. a Dirichlet mask) always survive, and OpenMesh keeps the
// surface manifold and its boundary. `shapes` are #V x 3 each, at least one;
// faces counter-clockwise as in geometry/mesh.h, and the coarse faces keep
// that orientation. Throws InputError if the connectivity is not a manifold
// triangle mesh or a shape has the wrong size.
SharedDecimation DecimateShared(const Faces& faces,
                                const std::vector<Positions>& shapes,
                                int target_vertices,
                                const std::vector<int>& locked = {});

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_SHARED_DECIMATION_H_
