// Optimal rigid alignment of two shells with the same vertices (Kabsch).
#ifndef SHELLSPACE_GEOMETRY_RIGID_ALIGNMENT_H_
#define SHELLSPACE_GEOMETRY_RIGID_ALIGNMENT_H_

#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// A rigid motion x -> R x + t (det R = +1), applied to the rows of a
// #V x 3 array.
struct RigidMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::RowVector3d translation = Eigen::RowVector3d::Zero();
  Positions Apply(const Positions& x) const;
  // The motion's fraction tau in [0, 1] about `centre` c: rotation by tau
  // times its angle about its axis through c, and c moved by tau times its
  // displacement: x -> R^tau (x - c) + c + tau (R c + t - c). tau = 0 is
  // the identity, tau = 1 the motion itself (to round-off).
  RigidMotion Fraction(double tau, const Eigen::RowVector3d& centre) const;
  RigidMotion Inverse() const;  // x -> R^T (x - t)
};

// The rigid motion minimising sum_i |R p_i + t - q_i|^2 over the vertices
// (Kabsch), p = `source`, q = `target` (#V x 3 each).
RigidMotion FitRigidMotion(const Positions& source, const Positions& target);

// FitRigidMotion(source, target) applied to `source`.
Positions AlignRigidly(const Positions& source, const Positions& target);

// One rigid motion per group of vertices (the connected components of a
// mesh with several: each moves on its own without changing any energy).
struct ComponentwiseRigidMotion {
  std::vector<std::vector<int>> groups;  // vertex indices, disjoint
  std::vector<RigidMotion> motions;      // one per group
  Positions Apply(const Positions& x) const;  // rows outside every group stay
};

// FitRigidMotion of each group's rows of `source` onto the same rows of
// `target`.
ComponentwiseRigidMotion FitRigidMotions(
    const Positions& source, const Positions& target,
    const std::vector<std::vector<int>>& groups);

// max_i |p_i - q_i| after AlignRigidly(p, q), divided by the diameter of q's
// bounding box: a scale-free distance up to rigid motion.
double RelativeDistanceUpToRigidMotion(const Positions& p, const Positions& q);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_RIGID_ALIGNMENT_H_
