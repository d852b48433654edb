// Properties of W on the shared meshes: zero at rest, rigid invariance of
// each argument, the closed form for a uniformly stretched flat sheet.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

TEST(EnergyPropertiesTest, ZeroAtRest) {
  for (const char* name : {"finger/finger0.ply", "sphere/unitSphere1.ply",
                           "plate/plate121_rolledA.ply"}) {
    const Mesh mesh = testing::LoadData(name);
    const ShellSpace space = testing::MakeSpace(mesh);
    const DeformationEnergy e =
        EvaluateDeformationEnergy(space, mesh.positions, mesh.positions);
    EXPECT_NEAR(e.total, 0.0, 1e-12) << name;
  }
}

TEST(EnergyPropertiesTest, IndependentRigidMotionsOfBothArguments) {
  const auto [ref, def, space] =
      testing::LoadPair("finger/finger0.ply", "finger/finger1.ply");
  const double w =
      EvaluateDeformationEnergy(space, ref.positions, def.positions).total;
  ASSERT_GT(w, 1e-3);
  const Positions ref_moved = testing::RandomRigidMotion(ref.positions, 1);
  const Positions def_moved = testing::RandomRigidMotion(def.positions, 2);
  const double w_moved =
      EvaluateDeformationEnergy(space, ref_moved, def_moved).total;
  EXPECT_NEAR(w_moved / w, 1.0, 1e-10);
}

// A flat sheet scaled by s in its plane: G = s^2 I, so
// W = A (mu s^2 + lambda/4 s^4 - (mu/2 + lambda/4) log s^4 - mu - lambda/4)
// and no bending.
TEST(EnergyPropertiesTest, UniformStretchOfFlatSheet) {
  const Mesh plate = testing::LoadData("plate/plate121.ply");
  ShellMaterial material;
  material.mu = 1.5;
  material.lambda = 0.8;
  const ShellSpace space = testing::MakeSpace(plate, material);
  double area = 0;
  for (int f = 0; f < plate.num_faces(); ++f) {
    const Eigen::Vector3d a = plate.vertex(plate.faces(f, 0));
    area += 0.5 * (plate.vertex(plate.faces(f, 1)) - a)
                      .cross(plate.vertex(plate.faces(f, 2)) - a)
                      .norm();
  }
  // The plate lies in a plane: check, then scale about the centroid.
  for (double s : {0.5, 0.9, 1.0, 1.3, 2.0}) {
    Positions scaled = plate.positions;
    const Eigen::RowVector3d center = scaled.colwise().mean();
    scaled = ((scaled.rowwise() - center) * s).rowwise() + center;
    const double mu = material.mu, lambda = material.lambda;
    const double expected =
        area *
        (mu * s * s + lambda / 4 * std::pow(s, 4) -
         (mu / 2 + lambda / 4) * std::log(std::pow(s, 4)) - mu - lambda / 4);
    const DeformationEnergy e =
        EvaluateDeformationEnergy(space, plate.positions, scaled);
    EXPECT_NEAR(e.membrane, expected, 1e-10 * std::max(1.0, expected)) << s;
    EXPECT_NEAR(e.bending, 0.0, 1e-12) << s;
  }
}

}  // namespace
}  // namespace shellspace
