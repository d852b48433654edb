#include "shellspace/cost_functions/shell/relative_bending_weight.h"

#include <cmath>
#include <sstream>
#include <string>

namespace shellspace {

double SurfaceArea(const Mesh& mesh) {
  double area = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d a = mesh.vertex(mesh.faces(f, 0));
    const Eigen::Vector3d b = mesh.vertex(mesh.faces(f, 1));
    const Eigen::Vector3d c = mesh.vertex(mesh.faces(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

double EtaFromRelative(double relative_eta, const Mesh& reference) {
  if (!std::isfinite(relative_eta) || relative_eta < 0) {
    std::ostringstream message;
    message << "relative eta must be finite and >= 0 (got " << relative_eta
            << ")";
    throw InputError(message.str());
  }
  const double area = SurfaceArea(reference);
  if (!(area > 0) || !std::isfinite(area)) {
    std::ostringstream message;
    message << "relative eta needs a reference of positive finite area (got "
            << area << ")";
    throw InputError(message.str());
  }
  return relative_eta * area;
}

}  // namespace shellspace
