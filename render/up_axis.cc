#include "shellspace/render/up_axis.h"

#include <cctype>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace shellspace {

UpAxis ParseUpAxis(const std::string& text) {
  std::string name;
  for (char c : text) {
    if (c == ' ' || c == '\t') continue;
    name += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (name == "auto") return UpAxis::kAuto;
  if (name == "x" || name == "+x") return UpAxis::kPlusX;
  if (name == "y" || name == "+y") return UpAxis::kPlusY;
  if (name == "z" || name == "+z") return UpAxis::kPlusZ;
  if (name == "-x") return UpAxis::kMinusX;
  if (name == "-y") return UpAxis::kMinusY;
  if (name == "-z") return UpAxis::kMinusZ;
  throw InputError("bad up axis '" + text +
                   "' (expected auto, x, y, z, -x, -y or -z)");
}

std::string UpAxisName(UpAxis axis) {
  switch (axis) {
    case UpAxis::kAuto: return "auto";
    case UpAxis::kPlusX: return "x";
    case UpAxis::kMinusX: return "-x";
    case UpAxis::kPlusY: return "y";
    case UpAxis::kMinusY: return "-y";
    case UpAxis::kPlusZ: return "z";
    case UpAxis::kMinusZ: return "-z";
  }
  return "auto";
}

UpAxis AutoUpAxis(const Positions& vertices) {
  if (!vertices.allFinite()) {
    throw InputError("frame 0 has a non-finite vertex coordinate");
  }
  const int n = static_cast<int>(vertices.rows());
  if (n < 2) return UpAxis::kPlusY;
  const Eigen::RowVector3d mean = vertices.colwise().mean();
  const Eigen::MatrixX3d centered = vertices.rowwise() - mean;
  const Eigen::Matrix3d covariance = centered.transpose() * centered / n;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d values = solver.eigenvalues();  // ascending
  if (!(values(2) > 0) || values(2) - values(1) <= 1e-3 * values(2)) {
    return UpAxis::kPlusY;
  }
  const Eigen::Vector3d e = solver.eigenvectors().col(2).cwiseAbs();
  // Preference on ties: y, then z, then x.
  const int order[3] = {1, 2, 0};
  int best = order[0];
  for (int k = 1; k < 3; ++k) {
    if (e(order[k]) > e(best) + 1e-9) best = order[k];
  }
  return best == 0 ? UpAxis::kPlusX
                   : best == 1 ? UpAxis::kPlusY : UpAxis::kPlusZ;
}

UpAxis ResolveUpAxis(UpAxis requested, const Positions& first_frame) {
  return requested == UpAxis::kAuto ? AutoUpAxis(first_frame) : requested;
}

Eigen::Vector3d UpDirection(UpAxis axis) {
  switch (axis) {
    case UpAxis::kPlusX: return Eigen::Vector3d::UnitX();
    case UpAxis::kMinusX: return -Eigen::Vector3d::UnitX();
    case UpAxis::kPlusY: return Eigen::Vector3d::UnitY();
    case UpAxis::kMinusY: return -Eigen::Vector3d::UnitY();
    case UpAxis::kPlusZ: return Eigen::Vector3d::UnitZ();
    case UpAxis::kMinusZ: return -Eigen::Vector3d::UnitZ();
    case UpAxis::kAuto: break;
  }
  throw std::invalid_argument("UpDirection: the auto up axis is not resolved");
}

Eigen::Matrix3d UpRotation(UpAxis axis) {
  Eigen::Matrix3d r;
  switch (axis) {
    case UpAxis::kPlusY: r.setIdentity(); return r;
    case UpAxis::kPlusX: r << 0, -1, 0, 1, 0, 0, 0, 0, 1; return r;
    case UpAxis::kMinusX: r << 0, 1, 0, -1, 0, 0, 0, 0, 1; return r;
    case UpAxis::kPlusZ: r << 1, 0, 0, 0, 0, 1, 0, -1, 0; return r;
    case UpAxis::kMinusZ: r << 1, 0, 0, 0, 0, -1, 0, 1, 0; return r;
    case UpAxis::kMinusY: r << -1, 0, 0, 0, -1, 0, 0, 0, 1; return r;
    case UpAxis::kAuto: break;
  }
  throw std::invalid_argument("UpRotation: the auto up axis is not resolved");
}

}  // namespace shellspace
