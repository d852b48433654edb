// The rotation-blend path between two shells: every triangle turns and
// stretches by the interpolated polar factors of its deformation gradient,
// and each inner shape is the shell that fits those triangles best in the
// least-squares sense (a Poisson-type reconstruction). A bend or a twist
// is followed as a rotation, not cut short as a chord: the linear
// interpolation of a bend by 120 degrees shortens the inner side far below
// either end and can turn its triangles over; this path does not.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_ROTATION_BLEND_PATH_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_ROTATION_BLEND_PATH_H_

#include <Eigen/Core>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"

namespace shellspace {

// The K + 1 = steps + 1 shapes s_0 = start, ..., s_K = end of the
// rotation-blend path (docs/math.md, "Path energy and discrete geodesics"):
//  1. Without a mask, the rigid motion from end to start is removed first
//     (RigidBlendFrame: end' = R end + c); with a mask the end is used as
//     it is.
//  2. Per face f, the deformation gradient F_f = [e1' e2' n'] [e1 e2 n]^-1
//     (edges from the face's first vertex, unit normal; start -> end') is
//     split F_f = R_f U_f (polar factors, U_f symmetric positive definite),
//     and R_f = exp([w_f]x). The rotation vectors w_f are taken on the
//     branch (|w_f| or |w_f| - 2 pi along the axis) nearest to a
//     neighbouring face's, face by face out from the least rotated face of
//     each component, so that a twist does not flip by 2 pi between faces.
//  3. At t = k / K every face wants F_f(t) = exp(t [w_f]x) ((1 - t) I +
//     t U_f). The shape x minimises
//       sum_f sum_{edges ab of f} |x_b - x_a - F_f(t) (X_b - X_a)|^2
//                                 / |X_b - X_a|^2
//       + eps sum_v |x_v - l_v|^2,
//     X = start, l = (1 - t) start + t end' (the linear blend), eps = 1e-9 x
//     the mean edge weight (it fixes the translation of each component
//     without a masked vertex and nothing else); masked vertices are held
//     at l_v. One sparse LDL^T factorisation serves every frame and
//     coordinate.
//  4. Without a mask, x is moved by the fraction t of the rigid motion
//     back to the end (RigidBlendFrame::Move).
// A pure rigid motion gives rigid motions of the start (every F_f = R, all
// U_f = I); a path between shapes that differ by a stretch alone is the
// linear path up to the fit.
// `start`, `end`: #V x 3; `faces` #F x 3 with `topology` built from them;
// `fixed_vertices`: the mask (empty: none). steps >= 1. Empty if the
// reconstruction's matrix cannot be factored (it is positive definite by
// construction; this is a guard, not an expected outcome).
std::vector<Positions> RotationBlendPath(
    const Faces& faces, const Topology& topology, const Positions& start,
    const Positions& end, int steps, const std::vector<int>& fixed_vertices);

// The shapes of steps 3 and 4 of RotationBlendPath at the given times t,
// any real t: t = 2 carries the motion from start to end on as far again
// beyond the end (each face turned by twice its rotation, stretched by
// 2 U_f - I; without a mask the rigid motion continued by slerp): the
// initial guess of an EXP step that the linear extrapolation 2 end - start
// would distort (a turn by an angle a carried on as a chord lengthens the
// radius by sqrt(5 - 4 cos a)). Masked vertices are held at
// (1 - t) start + t end. Empty if the fit's matrix cannot be factored.
std::vector<Positions> RotationBlendShapes(
    const Faces& faces, const Topology& topology, const Positions& start,
    const Positions& end, const std::vector<double>& times,
    const std::vector<int>& fixed_vertices);

// Per face of `faces`, the rotation factor R of the deformation gradient
// F = [e1' e2' n'] [e1 e2 n]^-1 = R U from `from` to `to` (#V x 3 each;
// the identity for a degenerate face of `from`).
std::vector<Eigen::Matrix3d> FaceRotations(const Faces& faces,
                                           const Positions& from,
                                           const Positions& to);

// A path from `start` to `end` (#V x 3 on `faces`, K = guide.size() - 1
// steps) whose triangles turn as a guide says: guide[k][f] is the rotation
// face f should have at s_k (k = 0..K; from a coarser geodesic, the rotation
// of the coarse face nearest to f, FaceRotations). With R_f U_f the polar
// factors of face f from start to end and d_f the rotation vector of
// guide[K][f]^T R_f (what the guide misses of the face's own end rotation),
// s_k (t = k / K) fits, as step 3 of RotationBlendPath,
//   F_f(t) = guide[k][f] exp(t [d_f]x) ((1 - t) I + t U_f),
// with anchors[k] (#V x 3) in place of the linear blend: the masked
// vertices are held there and the eps term fixes the translation to it.
// anchors[0] and anchors[K] are not used. Empty if the fit's matrix cannot
// be factored.
std::vector<Positions> RotationGuidedPath(
    const Faces& faces, const Positions& start, const Positions& end,
    const std::vector<std::vector<Eigen::Matrix3d>>& guide,
    const std::vector<Positions>& anchors,
    const std::vector<int>& fixed_vertices);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_ROTATION_BLEND_PATH_H_
