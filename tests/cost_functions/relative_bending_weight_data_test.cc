// The scale-aware bending weight (relative_bending_weight.h): the surface
// area against closed forms, and W(sS, sS') = s^2 W(S, S') with
// eta = relative_eta x area, which one absolute eta breaks.
#include "shellspace/cost_functions/shell/relative_bending_weight.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::LoadData;
using testing::MakeSpace;

TEST(RelativeBendingWeightTest, SurfaceAreaOfClosedForms) {
  // The unit square (two triangles) and the double square (1 + 0.98).
  EXPECT_NEAR(SurfaceArea(LoadData("simple/square4.ply")), 1.0, 1e-15);
  EXPECT_NEAR(SurfaceArea(LoadData("plate/plate121.ply")), 1.0, 1e-13);
  // The icosahedral unit sphere is inscribed: area below 4 pi.
  const double sphere = SurfaceArea(LoadData("sphere/unitSphere1.ply"));
  EXPECT_LT(sphere, 4 * M_PI);
  EXPECT_GT(sphere, 0.95 * 4 * M_PI);
  // Scaling by s scales the area by s^2; rigid motions keep it.
  Mesh cactus = LoadData("cactus/cactus0.ply");
  const double area = SurfaceArea(cactus);
  Mesh moved = cactus;
  moved.positions = testing::RandomRigidMotion(cactus.positions, 7);
  EXPECT_NEAR(SurfaceArea(moved), area, 1e-12 * area);
  cactus.positions *= 3.0;
  EXPECT_NEAR(SurfaceArea(cactus), 9.0 * area, 1e-12 * area);
}

// W[s A, s B] / (s^2 W[A, B]) for eta from `eta_of(reference)`.
template <class EtaOf>
double ScaledEnergyRatio(double s, EtaOf eta_of) {
  const Mesh a = LoadData("cactus/cactus0.ply");
  const Mesh b = LoadData("cactus/cactus1.ply");
  Mesh big_a = a;
  big_a.positions *= s;
  ShellMaterial small, big;
  small.eta = eta_of(a);
  big.eta = eta_of(big_a);
  const double w =
      EvaluateDeformationEnergy(MakeSpace(a, small), a.positions, b.positions)
          .total;
  const double w_big = EvaluateDeformationEnergy(MakeSpace(big_a, big),
                                                 s * a.positions,
                                                 s * b.positions)
                           .total;
  return w_big / (s * s * w);
}

TEST(RelativeBendingWeightTest, RelativeEtaMakesWScaleLikeArea) {
  for (double s : {1e-3, 0.5, 7.0, 1e3}) {
    EXPECT_NEAR(ScaledEnergyRatio(
                    s, [](const Mesh& m) { return EtaFromRelative(0.01, m); }),
                1.0, 1e-12)
        << s;
  }
}

TEST(RelativeBendingWeightTest, AbsoluteEtaDoesNot) {
  // Negative twin through the same helper: on the cactus bending is most of
  // W, so with a fixed eta W[1000 A, 1000 B] is about W_mem / W = 0.62 of
  // 1000^2 W[A, B].
  EXPECT_LT(ScaledEnergyRatio(1e3, [](const Mesh&) { return 0.01; }), 0.7);
}

TEST(RelativeBendingWeightTest, BadArgumentsAreOneLineErrors) {
  const Mesh square = LoadData("simple/square4.ply");
  EXPECT_THROW(EtaFromRelative(-1, square), InputError);
  EXPECT_THROW(EtaFromRelative(std::nan(""), square), InputError);
  Mesh flat = square;
  flat.positions.setZero();
  EXPECT_THROW(EtaFromRelative(0.01, flat), InputError);
  EXPECT_DOUBLE_EQ(EtaFromRelative(0.25, square), 0.25);
}

}  // namespace
}  // namespace shellspace
