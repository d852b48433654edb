#include "shellspace/geometry/edge_angle_second_form.h"

#include <cmath>
#include <string>

namespace shellspace {

double EdgeAngleFace::Coefficient(int i, double phi_i) const {
  if (!interior(i)) return 0;
  return 2 * altitude[i] * std::sin(half_dihedral[i] + sign[i] * phi_i);
}

double EdgeAngleFace::CoefficientDerivative(int i, double phi_i) const {
  if (!interior(i)) return 0;
  return 2 * altitude[i] * sign[i] *
         std::cos(half_dihedral[i] + sign[i] * phi_i);
}

SecondForm2 EdgeAngleSecondForm(const EdgeAngleFace& face, const double* phi) {
  const double c0 = face.Coefficient(0, phi[0]);
  const double c1 = face.Coefficient(1, phi[1]);
  const double c2 = face.Coefficient(2, phi[2]);
  return {c0 + c1, c0, c0 + c2};
}

void FaceEdgeAngles(const EdgeAngleFace& face, const std::vector<double>& angles,
                    double* phi) {
  for (int i = 0; i < 3; ++i) phi[i] = face.interior(i) ? angles[face.edge[i]] : 0.0;
}

std::vector<EdgeAngleFace> EdgeAngleFaces(const Mesh& mesh,
                                          const Topology& topology,
                                          const Positions& shape) {
  const int num_faces = mesh.num_faces();
  std::vector<EdgeAngleFace> out(num_faces);
  auto position = [&](int v) -> Eigen::Vector3d { return shape.row(v).transpose(); };
  // Altitudes of every slot.
  for (int f = 0; f < num_faces; ++f) {
    const Eigen::Vector3d x0 = position(mesh.faces(f, 0)),
                          x1 = position(mesh.faces(f, 1)),
                          x2 = position(mesh.faces(f, 2));
    const double twice_area = (x1 - x0).cross(x2 - x0).norm();
    if (!(twice_area > 0)) {
      throw InputError("face " + std::to_string(f) +
                       " is degenerate (zero area): no shape operator");
    }
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d a = position(mesh.faces(f, (i + 1) % 3)),
                            b = position(mesh.faces(f, (i + 2) % 3));
      out[f].altitude[i] = twice_area / (b - a).norm();
    }
  }
  // Interior slots: the face runs through the edge a -> b (a = X_{i+1},
  // b = X_{i+2}); the flap's first face runs i -> j.
  for (int e = 0; e < static_cast<int>(topology.interior_edges.size()); ++e) {
    const EdgeFlap& flap = topology.interior_edges[e];
    for (int side = 0; side < 2; ++side) {
      const int f = side == 0 ? flap.face_0 : flap.face_1;
      const int from = side == 0 ? flap.i : flap.j;
      const int to = side == 0 ? flap.j : flap.i;
      const int across = side == 0 ? flap.l : flap.k;
      for (int i = 0; i < 3; ++i) {
        if (mesh.faces(f, (i + 1) % 3) != from || mesh.faces(f, (i + 2) % 3) != to) {
          continue;
        }
        const Eigen::Vector3d xi = position(mesh.faces(f, i));
        const Eigen::Vector3d xa = position(from), xb = position(to),
                              xp = position(across);
        const Eigen::Vector3d normal =
            (xa - xi).cross(xb - xi).normalized();  // (X_i, a, b) is T's order
        const Eigen::Vector3d normal_across = (xa - xb).cross(xp - xb).normalized();
        const Eigen::Vector3d edge = (xb - xa).normalized();
        Eigen::Vector3d t = 0.5 * (xa + xb) - xi;
        t = (t - t.dot(edge) * edge).normalized();
        out[f].half_dihedral[i] =
            0.5 * std::atan2(normal_across.dot(t), normal.dot(normal_across));
        out[f].edge[i] = e;
        out[f].sign[i] = side == 0 ? 1.0 : -1.0;
      }
    }
  }
  return out;
}

}  // namespace shellspace
