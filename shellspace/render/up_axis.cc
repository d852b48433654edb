#include "shellspace/render/up_axis.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include <cctype>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "shellspace/geometry/named_values.h"

namespace shellspace {

namespace {

// Canonical names first, then the "+" aliases.
constexpr NamedValue<UpAxis> kUpAxisNames[] = {
    {UpAxis::kAuto, "auto"},   {UpAxis::kPlusX, "x"},   {UpAxis::kPlusY, "y"},
    {UpAxis::kPlusZ, "z"},     {UpAxis::kMinusX, "-x"}, {UpAxis::kMinusY, "-y"},
    {UpAxis::kMinusZ, "-z"},   {UpAxis::kPlusX, "+x"},  {UpAxis::kPlusY, "+y"},
    {UpAxis::kPlusZ, "+z"}};

}  // namespace

UpAxis ParseUpAxis(const std::string& text) {
  std::string name;
  for (char c : text) {
    if (c == ' ' || c == '\t') continue;
    name += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (const std::optional<UpAxis> axis = ValueNamed(kUpAxisNames, name)) {
    return *axis;
  }
  throw InputError("bad up axis '" + text + "' (expected " +
                   NameChoices(kUpAxisNames) + ")");
}

std::string UpAxisName(UpAxis axis) { return NameOf(kUpAxisNames, axis); }

namespace {

// +1, or -1 if the boundary of the surface (edges of one face) lies on the
// positive side of the vertices along `axis` (see AutoUpAxis).
int SignAwayFromBoundary(const Positions& vertices, const Faces& faces,
                         int axis) {
  std::map<std::pair<int, int>, int> edge_faces;
  for (int f = 0; f < faces.rows(); ++f) {
    for (int i = 0; i < 3; ++i) {
      const int a = faces(f, i), b = faces(f, (i + 1) % 3);
      ++edge_faces[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::set<int> boundary;
  for (const auto& [edge, count] : edge_faces) {
    if (count == 1) boundary.insert({edge.first, edge.second});
  }
  const int n = static_cast<int>(vertices.rows());
  if (boundary.empty()) return 1;
  double boundary_mean = 0;
  for (int v : boundary) {
    if (v < 0 || v >= n) return 1;  // invalid faces: the renderer reports it
    boundary_mean += vertices(v, axis);
  }
  boundary_mean /= boundary.size();
  const double mean = vertices.col(axis).mean();
  const double extent =
      vertices.col(axis).maxCoeff() - vertices.col(axis).minCoeff();
  return boundary_mean > mean + 1e-3 * extent ? -1 : 1;
}

}  // namespace

UpAxis AutoUpAxis(const Positions& vertices, const Faces* faces) {
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
  const bool down = faces && SignAwayFromBoundary(vertices, *faces, best) < 0;
  if (best == 0) return down ? UpAxis::kMinusX : UpAxis::kPlusX;
  if (best == 1) return down ? UpAxis::kMinusY : UpAxis::kPlusY;
  return down ? UpAxis::kMinusZ : UpAxis::kPlusZ;
}

UpAxis ResolveUpAxis(UpAxis requested, const Positions& first_frame,
                     const Faces* faces) {
  return requested == UpAxis::kAuto ? AutoUpAxis(first_frame, faces)
                                    : requested;
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
