// The --bending flag of the CLI: every verb with material flags
// accepts it and reports `bending_model` in --json; `energy --bending both`
// reports both models' W_bend, each equal to the library's value, and the
// edge-angle variant (energy only; every other verb refuses it); a geodesic
// with the shape-operator model reports the energy the library evaluates on
// its frames with that model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "shellspace/cost_functions/edge_angle_bending.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "tests/tools/cli_test_support.h"

namespace shellspace {
namespace {

ShellMaterial Material(BendingModel model, double eta) {
  ShellMaterial material;
  material.eta = eta;
  material.bending_model = model;
  return material;
}

TEST(BendingModelCliTest, EnergyReportsTheChosenModelAndBoth) {
  const Mesh a = ReadMesh(kSquare), b = ReadMesh(kBent);
  const double ds =
      EvaluateDeformationEnergy(
          testing::MakeSpace(a, Material(BendingModel::kDiscreteShells, 0.5)),
          a.positions, b.positions)
          .bending;
  const DeformationEnergy so = EvaluateDeformationEnergy(
      testing::MakeSpace(a, Material(BendingModel::kShapeOperator, 0.5)),
      a.positions, b.positions);
  ASSERT_GT(ds, 1e-6);
  ASSERT_GT(so.bending, 1e-6);
  const std::string common =
      "energy --json --eta 0.5 --reference " + kSquare + " --deformed " + kBent;
  const std::string plain = RunOk(common);
  EXPECT_NE(plain.find("\"bending_model\": \"discrete-shells\""),
            std::string::npos)
      << plain;
  EXPECT_NEAR(Number(plain, "bending"), ds, 1e-12 * ds);
  const std::string shape = RunOk(common + " --bending shape-operator");
  EXPECT_NE(shape.find("\"bending_model\": \"shape-operator\""),
            std::string::npos)
      << shape;
  EXPECT_NEAR(Number(shape, "bending"), so.bending, 1e-12 * so.bending);
  EXPECT_NEAR(Number(shape, "total"), so.total, 1e-12 * so.total);
  const std::string both = RunOk(common + " --bending both");
  EXPECT_NE(both.find("\"bending_model\": \"both\""), std::string::npos)
      << both;
  EXPECT_NEAR(Number(both, "discrete-shells"), ds, 1e-12 * ds) << both;
  EXPECT_NEAR(Number(both, "shape-operator"), so.bending, 1e-12 * so.bending)
      << both;
  EXPECT_NEAR(Number(both, "bending"), ds, 1e-12 * ds);
}

TEST(BendingModelCliTest, GeodesicWithTheShapeOperatorModel) {
  const std::string dir = testing::TempDir() + "/so";
  const std::string json = RunOk(
      "geodesic --quiet --json --steps 4 --bending shape-operator "
      "--start " +
      kSquare + " --end " + kBent + " --output " + dir);
  EXPECT_NE(json.find("\"bending_model\": \"shape-operator\""),
            std::string::npos)
      << json;
  const double energy = Number(json, "path_energy");
  const Mesh a = ReadMesh(kSquare);
  ShellPath path;
  for (int k = 0; k <= 4; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "/shape_%03d.ply", k);
    path.push_back(ReadMesh(dir + name).positions);
  }
  const double so = PathEnergy(
      testing::MakeSpace(
          a, testing::CliDefaultMaterial(a, BendingModel::kShapeOperator)),
      path);
  const double ds =
      PathEnergy(testing::MakeSpace(a, testing::CliDefaultMaterial(a)), path);
  EXPECT_NEAR(energy, so, 1e-9 * so);
  EXPECT_GT(std::abs(so - ds), 1e-6 * so);  // the model made a difference
  const std::string ds_json =
      RunOk("geodesic --quiet --json --steps 4 --start " + kSquare + " --end " +
            kBent + " --output " + dir + "_ds");
  EXPECT_NE(ds_json.find("\"bending_model\": \"discrete-shells\""),
            std::string::npos);
}

TEST(BendingModelCliTest, EveryVerbWithMaterialFlagsTakesBending) {
  for (const char* verb :
       {"energy", "deform", "geodesic", "shoot", "log", "transport", "spline",
        "regress", "mean", "pca", "demo"}) {
    std::string help, err;
    EXPECT_EQ(RunCli(std::string(verb) + " --help", &help, &err), 0) << verb;
    EXPECT_NE(help.find("--bending (string)"), std::string::npos) << verb;
  }
  std::string err;
  EXPECT_EQ(
      RunCli("geodesic --quiet --steps 2 --bending both --start " + kSquare +
                 " --end " + kBent + " --output " + testing::TempDir() + "/x",
             nullptr, &err),
      1);
  EXPECT_NE(err.find("--bending"), std::string::npos) << err;
}

TEST(BendingModelCliTest, EnergyReportsTheEdgeAngleVariantOnlyThere) {
  // The cactus pair: a real mesh with boundary (faces with 1-3 interior
  // edges), where the fitted angles change W_bend by tens of percent.
  const std::string a_path = DataPath("cactus/cactus0.ply");
  const std::string b_path = DataPath("cactus/cactus1.ply");
  const Mesh a = ReadMesh(a_path), b = ReadMesh(b_path);
  const EdgeAngleBending variant = EvaluateEdgeAngleBending(
      a, Topology::Build(a), a.positions, b.positions);
  ASSERT_TRUE(variant.converged);
  const DeformationEnergy so = EvaluateDeformationEnergy(
      testing::MakeSpace(a, Material(BendingModel::kShapeOperator, 0.01)),
      a.positions, b.positions);
  EXPECT_LT(variant.energy, 0.95 * so.bending);  // the angles matter here
  const std::string common = "energy --json --eta 0.01 --reference " + a_path +
                             " --deformed " + b_path;
  const std::string json = RunOk(common + " --bending shape-operator-edge-angles");
  EXPECT_NE(json.find("\"bending_model\": \"shape-operator-edge-angles\""),
            std::string::npos)
      << json;
  EXPECT_NEAR(Number(json, "bending"), variant.energy, 1e-12 * variant.energy);
  EXPECT_NEAR(Number(json, "total"), so.membrane + 0.01 * variant.energy,
              1e-12 * so.total);
  EXPECT_EQ(Number(json, "iterations"),
            variant.reference.iterations + variant.deformed.iterations);
  EXPECT_TRUE(testing::Bool(json, "converged")) << json;
  const std::string both = RunOk(common + " --bending both");
  EXPECT_NEAR(Number(both, "shape-operator-edge-angles"), variant.energy,
              1e-12 * variant.energy)
      << both;
  EXPECT_NEAR(Number(both, "shape-operator"), so.bending, 1e-12 * so.bending);
  // Every other verb refuses it with one line naming the flag.
  std::string err;
  EXPECT_EQ(RunCli("geodesic --quiet --steps 2 --bending "
                   "shape-operator-edge-angles --start " +
                       kSquare + " --end " + kBent + " --output " +
                       testing::TempDir() + "/edge_angles",
                   nullptr, &err),
            1);
  EXPECT_NE(err.find("--bending shape-operator-edge-angles"), std::string::npos)
      << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}

}  // namespace
}  // namespace shellspace
