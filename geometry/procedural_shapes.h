// Procedural shells for demos and tests (no data files needed).
#ifndef SHELLSPACE_GEOMETRY_PROCEDURAL_SHAPES_H_
#define SHELLSPACE_GEOMETRY_PROCEDURAL_SHAPES_H_

#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// A capsule-shaped "finger": an open-bottomed tube of radius `radius` and
// length `length` along +y (bottom ring at y = 0), closed on top by a
// hemispherical cap; `around` vertices per ring, `rings` rings on the tube,
// `cap_rings` on the cap plus one pole. Outward-oriented triangles.
Mesh MakeFinger(double radius = 0.5, double length = 4.0, int around = 24,
                int rings = 24, int cap_rings = 6);

// Vertex indices of the bottom `count` rings of MakeFinger (the base held
// fixed in the demo).
std::vector<int> FingerBaseVertices(int around = 24, int count = 2);

// Bends a shape about the z-axis line x = R, y = 0 with R = length / angle:
// a point at height y in [0, length] is rotated by angle * y / length, so the
// axis x = 0 becomes a circular arc of length `length` turning by `angle`
// radians toward +x (points above `length` rotate rigidly with the top).
Positions BendAlongY(const Positions& shape, double length, double angle);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_PROCEDURAL_SHAPES_H_
