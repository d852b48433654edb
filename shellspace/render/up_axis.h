// The up axis of the renderer: which world direction points up on screen.
#ifndef SHELLSPACE_RENDER_UP_AXIS_H_
#define SHELLSPACE_RENDER_UP_AXIS_H_

#include <string>

#include <Eigen/Core>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// A signed coordinate axis, or kAuto (resolved from the vertices by
// AutoUpAxis).
enum class UpAxis { kAuto, kPlusX, kMinusX, kPlusY, kMinusY, kPlusZ, kMinusZ };

// Parses "auto", "x", "y", "z", "+x", "+y", "+z", "-x", "-y" or "-z"
// (case-insensitive, surrounding blanks ignored). Throws InputError with a
// one-line message for anything else.
UpAxis ParseUpAxis(const std::string& text);

// "auto", "x", "-x", "y", "-y", "z" or "-z" (what ParseUpAxis reads back).
std::string UpAxisName(UpAxis axis);

// The up axis a mesh with these vertices gets under kAuto: the coordinate
// axis closest to the principal axis of largest extent, i.e. the
// eigenvector e of the largest eigenvalue of the vertex covariance
//   C = (1/n) sum_i (p_i - mean)(p_i - mean)^T
// snapped to the coordinate axis of its largest |component|. Its sign: with
// `faces` given and the surface open, the end away from the boundary is up
// (scans and cut-outs are open where they were cut off the rest: the neck
// of a face, the stem of a plant), i.e. the negative axis if the mean
// boundary vertex lies more than 0.1 % of the axis' extent above the mean
// vertex; otherwise (closed, no faces, or no clear side) the positive end
// is up. Pass the axis explicitly to override. No clear long axis,
// i.e. the two largest eigenvalues within 0.1 % of each other (a sphere, a
// square plate) or fewer than two distinct vertices, gives +y, the default
// of a fixed up axis. Ties between components (within 1e-9) prefer y, then
// z, then x. Throws InputError if a coordinate is not finite. Never returns
// kAuto.
UpAxis AutoUpAxis(const Positions& vertices, const Faces* faces = nullptr);

// `requested`, or AutoUpAxis(first_frame, faces) for kAuto.
UpAxis ResolveUpAxis(UpAxis requested, const Positions& first_frame,
                     const Faces* faces = nullptr);

// The unit world vector of a signed axis. Throws std::invalid_argument for
// kAuto.
Eigen::Vector3d UpDirection(UpAxis axis);

// The rotation R (a signed permutation, det +1) the renderer applies to the
// world before the view angles (view.h): the smallest rotation taking
// UpDirection(axis) to +y, i.e. R p for
//   +y   p                  (the identity: today's pictures)
//   +x   (-p_y,  p_x, p_z)  (a quarter turn about z; +z stays towards a
//   -x   ( p_y, -p_x, p_z)   front viewer)
//   +z   ( p_x,  p_z, -p_y) (a quarter turn about x; the front view then
//   -z   ( p_x, -p_z,  p_y)  looks along +y for +z, along -y for -z)
//   -y   (-p_x, -p_y, p_z)  (a half turn; about z, so +z stays in front)
// Throws std::invalid_argument for kAuto.
Eigen::Matrix3d UpRotation(UpAxis axis);

}  // namespace shellspace

#endif  // SHELLSPACE_RENDER_UP_AXIS_H_
