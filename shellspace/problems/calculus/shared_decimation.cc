#include "shellspace/problems/calculus/shared_decimation.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>

namespace shellspace {

namespace {

struct DoubleTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

// A plane quadric: Q(x) = x^T A x + 2 b.x + c, stored as a symmetric 4 x 4.
using Quadric = Eigen::Matrix4d;

double QuadricError(const Quadric& q, const Eigen::RowVector3d& x) {
  const Eigen::Vector4d h(x(0), x(1), x(2), 1.0);
  return h.dot(q * h);
}

// The module of DecimateShared: per-shape quadrics, per-shape normal and
// area checks. Vertex handles keep their indices until garbage collection
// (which DecimateShared never runs), so fine vertex v is handle v.
template <class MeshT>
class ModSharedQuadricT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModSharedQuadricT, MeshT, SharedQuadric);

  explicit ModSharedQuadricT(MeshT& mesh) : Base(mesh, false) {}

  void set_shapes(const std::vector<Positions>* shapes, const Faces* faces) {
    shapes_ = shapes;
    faces_ = faces;
  }

  void initialize() override {
    const int n = static_cast<int>((*shapes_)[0].rows());
    quadrics_.assign(shapes_->size() * n, Quadric::Zero());
    for (size_t s = 0; s < shapes_->size(); ++s) {
      const Positions& x = (*shapes_)[s];
      for (int f = 0; f < faces_->rows(); ++f) {
        const int a = (*faces_)(f, 0), b = (*faces_)(f, 1), c = (*faces_)(f, 2);
        const Eigen::Vector3d e1 = (x.row(b) - x.row(a)).transpose();
        const Eigen::Vector3d e2 = (x.row(c) - x.row(a)).transpose();
        const Eigen::Vector3d cross = e1.cross(e2);
        const double twice_area = cross.norm();
        if (!(twice_area > 0)) continue;
        const Eigen::Vector3d normal = cross / twice_area;
        Eigen::Vector4d plane;
        plane << normal, -normal.dot(x.row(a).transpose());
        const Quadric q = 0.5 * twice_area * plane * plane.transpose();
        for (int v : {a, b, c}) quadrics_[s * n + v] += q;
      }
    }
    num_vertices_ = n;
  }

  float collapse_priority(const CollapseInfo& ci) override {
    const int v0 = ci.v0.idx(), v1 = ci.v1.idx();
    double error = 0;
    for (size_t s = 0; s < shapes_->size(); ++s) {
      const Positions& x = (*shapes_)[s];
      if (!FacesStayValid(ci, x)) return Base::ILLEGAL_COLLAPSE;
      error += QuadricError(quadrics_[s * num_vertices_ + v0] +
                                quadrics_[s * num_vertices_ + v1],
                            x.row(v1));
    }
    return static_cast<float>(std::max(0.0, error));
  }

  void postprocess_collapse(const CollapseInfo& ci) override {
    for (size_t s = 0; s < shapes_->size(); ++s) {
      quadrics_[s * num_vertices_ + ci.v1.idx()] +=
          quadrics_[s * num_vertices_ + ci.v0.idx()];
    }
  }

 private:
  // The faces around v0 other than the two that vanish, with v0 moved to
  // v1's position in shape x: normal turned by at most 60 degrees, area at
  // least 1e-3 of the old one.
  bool FacesStayValid(const CollapseInfo& ci, const Positions& x) {
    MeshT& mesh = Base::mesh();
    for (auto fh : mesh.vf_range(ci.v0)) {
      if (fh == ci.fl || fh == ci.fr) continue;
      int vs[3], k = 0;
      for (auto vh : mesh.fv_range(fh)) vs[k++] = vh.idx();
      Eigen::Vector3d p[3], q[3];
      for (int i = 0; i < 3; ++i) {
        p[i] = x.row(vs[i]).transpose();
        q[i] = vs[i] == ci.v0.idx() ? x.row(ci.v1.idx()).transpose() : p[i];
      }
      const Eigen::Vector3d before = (p[1] - p[0]).cross(p[2] - p[0]);
      const Eigen::Vector3d after = (q[1] - q[0]).cross(q[2] - q[0]);
      const double nb = before.norm(), na = after.norm();
      if (!(na > 1e-3 * nb) || !(nb > 0)) return false;
      if (before.dot(after) < 0.5 * nb * na) return false;
    }
    return true;
  }

  const std::vector<Positions>* shapes_ = nullptr;
  const Faces* faces_ = nullptr;
  std::vector<Quadric> quadrics_;  // [s * n + v]
  int num_vertices_ = 0;
};

}  // namespace

SharedDecimation DecimateShared(const Faces& faces,
                                const std::vector<Positions>& shapes,
                                int target_vertices,
                                const std::vector<int>& locked) {
  if (shapes.empty()) throw InputError("decimation: no shapes");
  const int n = static_cast<int>(shapes[0].rows());
  for (const Positions& s : shapes) {
    if (s.rows() != n) {
      throw InputError("decimation: the shapes have different vertex counts");
    }
  }
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> handles(n);
  for (int v = 0; v < n; ++v) {
    handles[v] = mesh.add_vertex(
        TriMesh::Point(shapes[0](v, 0), shapes[0](v, 1), shapes[0](v, 2)));
  }
  for (int f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      if (faces(f, c) < 0 || faces(f, c) >= n) {
        throw InputError("decimation: face " + std::to_string(f) +
                         " has a vertex index out of range");
      }
    }
    const TriMesh::FaceHandle fh = mesh.add_face(
        handles[faces(f, 0)], handles[faces(f, 1)], handles[faces(f, 2)]);
    if (!fh.is_valid()) {
      throw InputError("decimation: face " + std::to_string(f) +
                       " makes the mesh non-manifold");
    }
  }
  mesh.request_vertex_status();
  mesh.request_edge_status();
  mesh.request_face_status();
  for (int v : locked) {
    if (v >= 0 && v < n) mesh.status(handles[v]).set_locked(true);
  }

  using Decimater = OpenMesh::Decimater::DecimaterT<TriMesh>;
  using Module = ModSharedQuadricT<TriMesh>;
  Decimater decimater(mesh);
  Module::Handle module;
  decimater.add(module);
  decimater.module(module).set_shapes(&shapes, &faces);
  if (!decimater.initialize()) {
    throw InputError("decimation: OpenMesh's decimater did not initialise");
  }
  decimater.decimate_to(static_cast<size_t>(std::max(3, target_vertices)));

  SharedDecimation result;
  std::vector<int> coarse_of(n, -1);
  for (int v = 0; v < n; ++v) {
    if (mesh.status(handles[v]).deleted()) continue;
    // An isolated vertex cannot survive a collapse of its edges; skip it.
    if (mesh.is_isolated(handles[v])) continue;
    coarse_of[v] = static_cast<int>(result.survivors.size());
    result.survivors.push_back(v);
  }
  std::vector<int> face_vertices;
  for (auto fh : mesh.faces()) {
    if (mesh.status(fh).deleted()) continue;
    for (auto vh : mesh.fv_range(fh)) face_vertices.push_back(coarse_of[vh.idx()]);
  }
  result.faces.resize(static_cast<int>(face_vertices.size() / 3), 3);
  for (int f = 0; f < result.faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) result.faces(f, c) = face_vertices[3 * f + c];
  }
  for (const Positions& s : shapes) {
    Positions coarse(result.num_vertices(), 3);
    for (int i = 0; i < result.num_vertices(); ++i) {
      coarse.row(i) = s.row(result.survivors[i]);
    }
    result.shapes.push_back(std::move(coarse));
  }
  return result;
}

}  // namespace shellspace
