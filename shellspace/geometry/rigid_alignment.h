// Optimal rigid alignment of two shells with the same vertices (Kabsch).
#ifndef SHELLSPACE_GEOMETRY_RIGID_ALIGNMENT_H_
#define SHELLSPACE_GEOMETRY_RIGID_ALIGNMENT_H_

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// The rigid motion x -> R x + t (det R = +1) minimising sum_i |R p_i + t -
// q_i|^2 over the vertices, applied to `source`; `target` is q.
Positions AlignRigidly(const Positions& source, const Positions& target);

// max_i |p_i - q_i| after AlignRigidly(p, q), divided by the diameter of q's
// bounding box: a scale-free distance up to rigid motion.
double RelativeDistanceUpToRigidMotion(const Positions& p, const Positions& q);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_RIGID_ALIGNMENT_H_
