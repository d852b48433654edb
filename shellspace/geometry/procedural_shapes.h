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

// The icosahedron inscribed in the sphere of radius `radius` about the
// origin, midpoint-subdivided `level` times with every new vertex projected
// onto the sphere: 20 4^level outward-oriented faces, 10 4^level + 2
// vertices.
Mesh MakeIcosphere(int level, double radius = 1.0);

// A flat sheet of equilateral triangles of side h in the plane z = 0:
// `rows` + 1 rows of `columns` + 1 vertices, row r at y = r h sqrt(3)/2 with
// x = (c + (r odd ? 1/2 : 0)) h, c = 0..columns; 2 columns rows faces,
// oriented with normal +z.
Mesh MakeEquilateralSheet(int columns, int rows, double h);

// Rolls a sheet of the plane z = 0 onto the cylinder of radius R with axis
// parallel to y through (0, 0, -R): (x, y, 0) -> (R sin(x/R), y, R cos(x/R)
// - R), an isometry of the plane onto the cylinder (lengths along the
// surface kept; the triangles' chords shrink).
Positions RollOntoCylinder(const Positions& flat, double radius);

// Each vertex moved by a random tangential vector with uniform direction in
// the plane orthogonal to normals.row(v) and length uniform in [0,
// amplitude] (fixed seed; std::mt19937). `normals` is #V x 3 of unit
// vectors; projecting back onto a surface is the caller's.
Positions JitterTangentially(const Positions& shape, const Positions& normals,
                             double amplitude, unsigned seed);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_PROCEDURAL_SHAPES_H_
