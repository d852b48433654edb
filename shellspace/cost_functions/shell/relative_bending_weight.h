// The scale-aware bending weight: eta relative to the size of the reference
// shell.
//
// W = W_mem + eta W_bend. W_mem sums an area density over the reference's
// triangles, so scaling both shells by s multiplies it by s^2; both bending
// models are scale-free (Discrete Shells: sum of (theta - theta_bar)^2
// |e|^2 / A_e; shape operator: the integral of |B - B_bar|^2 dA, B ~ 1/s,
// dA ~ s^2). One absolute eta is therefore a different material on every
// mesh: with eta = 0.01, bending is 0.1 % of W on the faces (about 300 mm
// across) and 98.5 % on the cactus (about 1 unit). With
//
//   eta = relative_eta x area(reference)
//
// W(s S, s S') = s^2 W(S, S') exactly, so a mesh and the same mesh scaled
// by 1000 have the same geodesics, means and splines up to the scale. The
// reference's surface area (not its bounding box) is the size: it is
// invariant under rigid motions.
//
// The default, relative_eta = 1e-4, is a thin shell: eta plays the role of
// the squared thickness delta^2 (W_mem ~ delta, W_bend ~ delta^3), so it is
// a thickness of 1 % of sqrt(area). On the shared meshes bending is then
// 23 % (cactus0 -> cactus9), 33 % (the faces geodesic neutral -> smile) and
// 65 % (finger0 -> finger1) of W: neither term negligible. The earlier
// default 1e-2 (a thickness of 10 % of the size) made the faces 94 %
// bending, a stiff problem whose geodesic crushed small triangles (face 81
// of the faces down to 3e-6 of its area) and did not converge in 240 s;
// at 1e-4 it converges in 9 iterations with no face below 0.6 of its area.
// On the unit-area plates and squares relative_eta is the absolute eta.

#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_RELATIVE_BENDING_WEIGHT_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_RELATIVE_BENDING_WEIGHT_H_

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// The default relative_eta of the command line and the Python module.
inline constexpr double kDefaultRelativeEta = 1e-4;

// The sum of the triangle areas of `mesh` (#V x 3 positions, #F x 3 faces).
double SurfaceArea(const Mesh& mesh);

// relative_eta x SurfaceArea(reference). Throws InputError unless
// relative_eta is finite and >= 0 and the area is positive and finite.
double EtaFromRelative(double relative_eta, const Mesh& reference);

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_RELATIVE_BENDING_WEIGHT_H_
