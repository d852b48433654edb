// Input validation of shells: one-line InputError for every defect.
#ifndef SHELLSPACE_GEOMETRY_VALIDATION_H_
#define SHELLSPACE_GEOMETRY_VALIDATION_H_

#include <string>
#include <utility>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"

namespace shellspace {

// The checks of a mesh that do not depend on the triangles' shapes: at least
// one vertex and one face, every coordinate finite, every face a triangle of
// three distinct in-range vertices, no two faces with the same three
// vertices (in either orientation), every edge in at most two faces with
// opposite orientations (manifold, consistently oriented), and no isolated
// vertex (one in no face: it would be a free, unconstrained variable of every
// energy; such a vertex is rejected, not kept). io/mesh_io.h's ReadMesh runs
// these on every mesh it reads. `name` (usually the file path) prefixes the
// one-line InputError, which names the element (vertex i, face f, edge (a,
// b); 0-based). Returns the topology.
Topology ValidateMeshStructure(const Mesh& mesh, const std::string& name);

// ValidateMeshStructure, a scale the energies can compute with (every
// |coordinate| <= 1e30 and a bounding-box diagonal >= 1e-30: they use fourth
// powers of lengths) and no degenerate triangle (area <= 1e-12 times the
// mean squared edge length). Returns the topology.
Topology ValidateShell(const Mesh& mesh, const std::string& name);

// The checks of ValidateShell that depend on the positions (finite
// coordinates, scale, no degenerate triangle) for a mesh whose connectivity is
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

// The normal of face f of the shape x, unnormalised: (b - a) x (c - a),
// twice the triangle's area long.
inline Eigen::Vector3d FaceNormal(const Faces& faces, const Positions& x,
                                  int f) {
  const Eigen::Vector3d a = x.row(faces(f, 0)).transpose();
  const Eigen::Vector3d b = x.row(faces(f, 1)).transpose();
  const Eigen::Vector3d c = x.row(faces(f, 2)).transpose();
  return (b - a).cross(c - a);
}

// Sliver triangles: a triangle whose area is below kSliverAreaFraction of
// the mesh's mean triangle area or whose smallest angle is below
// kSliverMinDegrees. Legal input, but a path may crush such a triangle;
// the geodesic's steps never shrink a triangle below a tenth of its area
// at once (kStepMinAreaFraction), and a sliver is named up front.
// A folded edge: its two triangles turned more than kFoldDegrees against
// each other (normals that far apart: the flap nearly shut, its dihedral
// angle near +-pi). Legal too; the bending energy measures the change of
// such an angle across atan2's branch cut as the small turn it is
// (DihedralAngleChange), but a path may still shut the fold.
inline constexpr double kSliverAreaFraction = 0.01;
inline constexpr double kSliverMinDegrees = 1.0;
inline constexpr double kFoldDegrees = 170.0;
struct SliverFaces {
  std::vector<int> faces;      // in increasing order
  double smallest_area_fraction = 1;  // of the mean area, over all faces
  double smallest_degrees = 60;       // smallest angle over all faces
  // Folded edges as the pairs of their faces (lower index first), in
  // increasing order.
  std::vector<std::pair<int, int>> folds;
  double largest_fold_degrees = 0;  // over all interior edges
  bool empty() const { return faces.empty() && folds.empty(); }
  // "3 sliver triangles (area below 1% of the mean or an angle below 1
  // degree): 12, 40, 77" (at most 8 listed) and/or "2 folded edges
  // (triangles turned more than 170 degrees against each other): faces 5
  // and 9, 30 and 31", or "" if there are none.
  std::string Describe() const;

 private:
  std::string DescribeSlivers() const;
};
SliverFaces FindSliverFaces(const Mesh& mesh);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_VALIDATION_H_
