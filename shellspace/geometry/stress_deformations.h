// Smooth non-rigid deformations and rigid motions of a whole shape, for
// making second poses of single-pose meshes (the stress corpus of
// bench/stress_corpus.sh, and tests). Each acts in the shape's principal
// frame: its centroid c and the principal axes a_1 (longest extent),
// a_2, a_3 of the vertex covariance (PrincipalFrame).
#ifndef SHELLSPACE_GEOMETRY_STRESS_DEFORMATIONS_H_
#define SHELLSPACE_GEOMETRY_STRESS_DEFORMATIONS_H_

#include <cstdint>
#include <string>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// Centroid, orthonormal principal axes (columns, by decreasing variance,
// right-handed) and the extent [s_min, s_max] of the vertices along a_1.
struct PrincipalFrame {
  Eigen::Vector3d centroid;
  Eigen::Matrix3d axes;
  double s_min = 0, s_max = 0;
};
PrincipalFrame ComputePrincipalFrame(const Positions& shape);

// A bend of `degrees` along the longest axis: with local coordinates
// s = (x - c) . a_1 - (s_min + s_max) / 2, u = (x - c) . a_2,
// w = (x - c) . a_3, length L = s_max - s_min, phi = theta s / L and
// R = L / theta,
//   x' = c + (R - u) sin(phi) a_1 + (R - (R - u) cos(phi)) a_2 + w a_3:
// the axis u = w = 0 becomes a circular arc of the same length turning by
// theta; each cross-section stays rigid and perpendicular to the arc.
Positions BendAlongLongestAxis(const Positions& shape, double degrees);

// A twist of `degrees` about the longest axis: the cross-section at s is
// rotated about a_1 by theta (s - s_min) / L (the end s_min stays).
Positions TwistAboutLongestAxis(const Positions& shape, double degrees);

// A local pull: every vertex moves along a_2 by
// strength D exp(-|x - p|^2 / (2 (D / 8)^2)), D the bounding-box diagonal
// and p the vertex farthest along +a_2 (a bump pulled out of the surface).
Positions LocalPull(const Positions& shape, double strength);

// The rigid motion x -> R (x - c) + c + t with R the rotation by `degrees`
// about a unit axis and t a translation of length 0.25 D in a direction,
// both drawn from a fixed generator seeded with `seed` (the same on every
// platform: a 64-bit linear congruential generator, not <random>'s
// distributions).
Positions RandomRigidMotion(const Positions& shape, double degrees,
                            std::uint64_t seed);

// The named deformation `kind` at `strength`: "none" (the shape itself),
// "bend" (degrees), "twist"
// (degrees), "pull" (fraction of D), "rigid" (degrees), each followed by
// the rigid motion RandomRigidMotion(., 30, seed) unless kind is "rigid"
// or with_rigid_motion is false. Throws InputError for another kind.
Positions DeformForCorpus(const Positions& shape, const std::string& kind,
                          double strength, bool with_rigid_motion,
                          std::uint64_t seed);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_STRESS_DEFORMATIONS_H_
