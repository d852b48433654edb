// Reference values of W (docs/math.md, "Deformation energy"), through both the
// direct energy formula and the residual form 1/2 sum r^2.
#include <ceres/problem.h>
#include <gtest/gtest.h>

#include "shellspace/cost_functions/deformation_energy_residuals.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

struct Case {
  const char* reference;
  const char* deformed;
  double membrane, bending, total;
};

const Case kCases[] = {
    {"simple/square4.ply", "simple/square4_bent.ply", 1.792921565674,
     22.50433857408, 2.017964951415},
    {"simple/square4_bent.ply", "simple/square4.ply", 1.357468646826,
     30.19273850419, 1.659396031868},
    {"simple/double_square.ply", "simple/double_square_bent.ply",
     4.362755621348, 81.59899885208, 5.178745609869},
    {"sphere/unitSphere1.ply", "sphere/unitSphere1_defX.ply", 2.320247051872,
     1.944322291127, 2.339690274784},
    {"sphere/unitSphere1_defX.ply", "sphere/unitSphere1.ply", 2.058753015777,
     1.831960178704, 2.077072617564},
    {"sphere/unitSphere1.ply", "sphere/unitSphere1_defY.ply", 2.319376687848,
     2.020320487326, 2.339579892721},
};

// 1/2 sum r^2 of all residuals of W[reference, deformed] in a problem.
double ResidualEnergy(const ShellSpace& space, const Positions& reference,
                      Positions deformed) {
  ceres::Problem problem;
  AddDeformationEnergy(space, ShellArgument::Fixed(reference),
                       ShellArgument::Variable(&deformed), 1.0, &problem);
  double cost = 0;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr,
                   nullptr);
  return cost;
}

TEST(ReferenceValuesTest, MatchSpecTo1e10) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(std::string(c.reference) + " -> " + c.deformed);
    const Mesh ref = testing::LoadData(c.reference);
    const Mesh def = testing::LoadData(c.deformed);
    const ShellSpace space = testing::MakeSpace(ref);
    const DeformationEnergy e =
        EvaluateDeformationEnergy(space, ref.positions, def.positions);
    EXPECT_NEAR(e.membrane / c.membrane, 1.0, 1e-10);
    EXPECT_NEAR(e.bending / c.bending, 1.0, 1e-10);
    EXPECT_NEAR(e.total / c.total, 1.0, 1e-10);
    EXPECT_NEAR(ResidualEnergy(space, ref.positions, def.positions) / c.total,
                1.0, 1e-10);
  }
}

TEST(ReferenceValuesTest, OtherLameWeights) {
  const Mesh ref = testing::LoadData("simple/square4.ply");
  const Mesh def = testing::LoadData("simple/square4_bent.ply");
  ShellMaterial material;
  material.mu = 2.0;
  material.lambda = 0.5;
  material.eta = 0;
  const ShellSpace space = testing::MakeSpace(ref, material);
  const DeformationEnergy e =
      EvaluateDeformationEnergy(space, ref.positions, def.positions);
  EXPECT_NEAR(e.membrane / 2.689382348512, 1.0, 1e-10);
  EXPECT_NEAR(
      ResidualEnergy(space, ref.positions, def.positions) / 2.689382348512, 1.0,
      1e-10);
}

}  // namespace
}  // namespace shellspace
