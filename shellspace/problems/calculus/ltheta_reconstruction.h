// The LΘA coordinates of a shell (docs/math.md, "Riemannian splines"): edge
// lengths, triangle areas and dihedral angles, and the reconstruction of a
// shell from prescribed values by a sum of squares. Used by the LΘA spline
// (problems/splines/ltheta_spline.h) and by the LΘA initial path of a geodesic
// (geodesic_initial_path.h).
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_LTHETA_RECONSTRUCTION_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_LTHETA_RECONSTRUCTION_H_

#include <ceres/solver.h>

#include <Eigen/Core>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {

// The L, Θ, A coordinates of a shell: lengths of space.topology.edges, areas
// of space.faces, signed dihedral angles (DihedralAngle, in (-pi, pi]) of
// space.topology.interior_edges.
struct LThetaQuantities {
  Eigen::VectorXd lengths;
  Eigen::VectorXd areas;
  Eigen::VectorXd dihedrals;
};

// Residual weights of the reconstruction, from a reference shell (L, A):
// edge 1/L_e, area 1/sqrt(A_f), dihedral sqrt(3 eta L_e^2 / (A_f1 + A_f2)).
struct LThetaWeights {
  Eigen::VectorXd edge;
  Eigen::VectorXd area;
  Eigen::VectorXd dihedral;
};

LThetaQuantities ComputeLThetaQuantities(const ShellSpace& space,
                                         const Positions& shape);

// Throws InputError if the reference has a zero-length edge or a zero-area
// triangle.
LThetaWeights LThetaResidualWeights(const ShellSpace& space,
                                    const Positions& reference);

// Reconstructs a shell with the prescribed quantities: minimises the LΘA
// sum of squares above (dihedral terms skipped if eta = 0) by sparse LM from
// `initial`, with the vertices of `fixed_vertices` held at their positions in
// `initial` or, if it is empty, the rigid motions pinned at three vertices of
// `initial` (PinRigidMotions). The result is in the gauge of that pin; it is
// not re-aligned.
Positions ReconstructFromLTheta(const ShellSpace& space,
                                const LThetaQuantities& target,
                                const LThetaWeights& weights,
                                const Positions& initial,
                                const SolverSettings& settings,
                                ceres::Solver::Summary* summary = nullptr,
                                const std::vector<int>& fixed_vertices = {});

// The rigid-motion-aware blend of two shells with the same connectivity at
// fraction t in [0, 1] (thesis §6.3.1): b is rigidly aligned to a (Kabsch,
// b' = R b + c), the positions are blended linearly, (1 - t) a + t b', and
// the blend is moved by the fraction t of the rigid motion back to b
// (rotation slerped from I to R^T about a's centroid, centroid moved
// linearly). a at t = 0, b at t = 1; the plain linear interpolation
// (1 - t) a + t b when a and b are rigidly aligned; it never shrinks a shape
// that only rotates (the linear interpolation of a rotation by pi passes
// through a flat shape).
Positions BlendRigidly(const Positions& a, const Positions& b, double t);

// The rigid motion of BlendRigidly, for blends other than the linear one:
// Aligned() is b moved onto a (b' = R b + c, Kabsch), Move(x, t) moves a
// shape x given in a's frame by the fraction t of the motion back to b
// (rotation slerped from I to R^T about a's centroid, centroid moved by
// t (centroid_b - centroid_a)). BlendRigidly(a, b, t) is
// Move((1 - t) a + t Aligned(), t) in exact arithmetic; it keeps its own
// order of operations (the digits of the paths and splines made from it
// would change with the compiler's contractions otherwise).
class RigidBlendFrame {
 public:
  RigidBlendFrame(const Positions& a, const Positions& b);
  const Positions& Aligned() const { return aligned_; }
  Positions Move(const Positions& x, double t) const;

 private:
  Eigen::Matrix3d rotation_;  // R
  Eigen::Vector3d centroid_a_, centroid_b_;
  Positions aligned_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_LTHETA_RECONSTRUCTION_H_
