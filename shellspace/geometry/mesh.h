// A triangle mesh with fixed connectivity: a "shell" of docs/math.md.
#ifndef SHELLSPACE_GEOMETRY_MESH_H_
#define SHELLSPACE_GEOMETRY_MESH_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <stdexcept>
#include <string>
#include <vector>

namespace shellspace {

// Nodal positions of a shell, one row (x, y, z) per vertex. Row-major so that
// the coordinates of vertex i are the contiguous doubles data() + 3 i: these
// are the per-vertex Ceres parameter blocks.
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
// Vertex indices of the triangles, counter-clockwise (outward normal by the
// right-hand rule), one row per face.
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

// A triangle mesh: positions plus connectivity. All shells of one problem
// share `faces`; only `positions` differ.
struct Mesh {
  Positions positions;
  Faces faces;

  int num_vertices() const { return static_cast<int>(positions.rows()); }
  int num_faces() const { return static_cast<int>(faces.rows()); }
  Eigen::Vector3d vertex(int i) const { return positions.row(i).transpose(); }
};

// Every user-facing input problem (unreadable file, non-manifold mesh,
// incompatible connectivity, bad flag value ...) is reported by throwing this,
// with a one-line message naming the problem. The CLI prints it and exits 1.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message)
      : std::runtime_error(message) {}
};

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_MESH_H_
