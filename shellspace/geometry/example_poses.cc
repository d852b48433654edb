#include "shellspace/geometry/example_poses.h"

#include <cmath>

#include "shellspace/geometry/procedural_shapes.h"

namespace shellspace {
namespace {

constexpr double kPi = 3.14159265358979323846;

// `shape` with each vertex moved by amplitude exp(-|x - centre|^2 / width^2)
// along `direction`(x) (a unit vector or zero).
template <typename Direction>
Positions WithBump(const Positions& shape, const Eigen::RowVector3d& centre,
                   double amplitude, double width, Direction direction) {
  Positions out = shape;
  for (Eigen::Index i = 0; i < shape.rows(); ++i) {
    const Eigen::RowVector3d x = shape.row(i);
    const double weight =
        amplitude * std::exp(-(x - centre).squaredNorm() / (width * width));
    out.row(i) += weight * direction(x);
  }
  return out;
}

// Away from the y axis (the axis of the finger and the tube).
Eigen::RowVector3d Radial(const Eigen::RowVector3d& x) {
  const Eigen::RowVector3d r(x(0), 0, x(2));
  const double norm = r.norm();
  return norm > 0 ? Eigen::RowVector3d(r / norm) : Eigen::RowVector3d::Zero();
}

// `shape` rotated by `angle` about the y axis.
Positions RotatedAboutY(const Positions& shape, double angle) {
  Positions out = shape;
  const double c = std::cos(angle), s = std::sin(angle);
  out.col(0) = c * shape.col(0) + s * shape.col(2);
  out.col(2) = -s * shape.col(0) + c * shape.col(2);
  return out;
}

// BendAlongY toward the direction at `side` radians from +x about the y
// axis (`shape` itself for angle 0).
Positions BentToward(const Positions& shape, double length, double angle,
                     double side) {
  if (angle == 0) return shape;
  return RotatedAboutY(BendAlongY(RotatedAboutY(shape, side), length, angle),
                       -side);
}

ExampleSet Finger() {
  ExampleSet set;
  const Mesh finger = MakeFinger();
  set.faces = finger.faces;
  set.shapes = {
      {"finger0", finger.positions},
      {"finger1", BendAlongY(finger.positions, 4.0, 0.5 * kPi)},
      {"finger_var", WithBump(finger.positions, {0, 2.5, -0.5}, 0.12, 0.45,
                              Radial)}};
  set.mask = FingerBaseVertices();
  return set;
}

ExampleSet Plate() {
  ExampleSet set;
  Mesh plate = MakeEquilateralSheet(16, 18, 0.25);
  const Eigen::RowVector3d middle =
      0.5 * (plate.positions.colwise().minCoeff() +
             plate.positions.colwise().maxCoeff());
  plate.positions.rowwise() -= middle;
  set.faces = plate.faces;
  Positions swapped = plate.positions;
  swapped.col(0).swap(swapped.col(1));
  Positions rolled_about_x = RollOntoCylinder(swapped, 2.0);
  rolled_about_x.col(0).swap(rolled_about_x.col(1));
  set.shapes = {
      {"plate0", plate.positions},
      {"plate1", RollOntoCylinder(plate.positions, 2.0)},
      {"plate2", rolled_about_x},
      {"plate_var",
       WithBump(plate.positions, {0.6, 0.5, 0}, 0.2, 0.5,
                [](const Eigen::RowVector3d&) {
                  return Eigen::RowVector3d(0, 0, 1);
                })}};
  for (Eigen::Index i = 0; i < plate.positions.rows(); ++i) {
    if (plate.positions.row(i).norm() < 0.3) set.mask.push_back(i);
  }
  return set;
}

ExampleSet Cylinder() {
  ExampleSet set;
  // The finger's tube without its cap: its first 24 rings of 24 vertices.
  const int around = 24, rings = 24;
  const double length = 4.0;
  const Mesh finger = MakeFinger(0.5, length, around, rings);
  const int n = around * rings;
  std::vector<Eigen::RowVector3i> faces;
  for (Eigen::Index f = 0; f < finger.faces.rows(); ++f) {
    if (finger.faces.row(f).maxCoeff() < n) faces.push_back(finger.faces.row(f));
  }
  set.faces.resize(faces.size(), 3);
  for (size_t f = 0; f < faces.size(); ++f) set.faces.row(f) = faces[f];
  const Positions tube = finger.positions.topRows(n);
  Positions twisted = tube;
  for (int i = 0; i < n; ++i) {
    twisted.row(i) =
        RotatedAboutY(tube.row(i), 0.5 * kPi * tube(i, 1) / length);
  }
  set.shapes = {{"cylinder0", tube},
                {"cylinder1", twisted},
                {"cylinder_var",
                 WithBump(tube, {0, 2.0, -0.5}, 0.1, 0.45, Radial)}};
  set.mask = FingerBaseVertices(around, 1);
  return set;
}

ExampleSet Collection() {
  ExampleSet set;
  const int around = 16;
  const Mesh finger = MakeFinger(0.5, 4.0, around, 16, 4);
  set.faces = finger.faces;
  for (int k = 0; k <= 6; ++k) {
    const double side = (k % 2 ? 0.3 : -0.3);
    set.shapes.emplace_back(
        "pose" + std::to_string(k),
        BentToward(finger.positions, 4.0, kPi / 12 * k, side));
  }
  set.mask = FingerBaseVertices(around, 2);
  return set;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> ExampleSetNames() {
  return {{"finger", "a finger straight and bent by 90 degrees"},
          {"plate", "a plate flat and rolled two ways"},
          {"cylinder", "a tube straight and twisted by 90 degrees"},
          {"collection", "seven poses of a finger bending to either side"}};
}

ExampleSet MakeExampleSet(const std::string& name) {
  ExampleSet set;
  if (name == "finger") {
    set = Finger();
  } else if (name == "plate") {
    set = Plate();
  } else if (name == "cylinder") {
    set = Cylinder();
  } else if (name == "collection") {
    set = Collection();
  } else {
    std::string names;
    for (const auto& known : ExampleSetNames()) {
      names += (names.empty() ? "" : ", ") + known.first;
    }
    throw InputError("no example set '" + name + "' (known: " + names + ")");
  }
  set.name = name;
  for (const auto& [known, description] : ExampleSetNames()) {
    if (known == name) set.description = description;
  }
  return set;
}

}  // namespace shellspace
