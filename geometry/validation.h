// Input validation of shells: one-line InputError for every defect.
#ifndef SHELLSPACE_GEOMETRY_VALIDATION_H_
#define SHELLSPACE_GEOMETRY_VALIDATION_H_

#include <string>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"

namespace shellspace {

// Checks that every coordinate is finite, every face is a triangle of three
// distinct in-range vertices, every edge has at most two faces with opposite
// orientations (manifold, consistently oriented), and no triangle is
// degenerate (area <= 1e-12 times the mean squared edge length). `name`
// (usually the file path) prefixes the error. Returns the topology.
Topology ValidateShell(const Mesh& mesh, const std::string& name);

// The checks of ValidateShell that depend on the positions (finite
// coordinates, no degenerate triangle) for a mesh whose connectivity is
// known to be that of `topology` (a pose of an already validated shell, see
// CheckCompatible): does not build the topology again.
void ValidateShellPositions(const Mesh& mesh, const Topology& topology,
                            const std::string& name);

// Checks that `other` has the connectivity of `mesh`: the same vertex count
// and the same oriented triangles, face by face, up to a cyclic rotation of
// each face's vertices (a rotation that flips orientation, or another
// triangle, is an error). Rotated faces of `other` are not changed; callers
// use `mesh.faces`.
void CheckCompatible(const Mesh& mesh, const std::string& name,
                     const Mesh& other, const std::string& other_name);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_VALIDATION_H_
