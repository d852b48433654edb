// The scale-aware default material of the CLI: with the
// default --relative_eta, a mesh and the same mesh scaled by 1000 have the
// same geodesic up to the scale (E_K scaled by 1000^2); with one absolute
// --eta they do not (the negative twin: the check below can fail). Every
// summary carries the resolved material and the membrane / bending split.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/mesh_io.h"
#include "tests/tools/cli_test_support.h"

namespace shellspace {
namespace {

constexpr double kScale = 1000;

// The two ends of the test geodesic and their copies scaled by kScale.
struct ScaledPair {
  std::string start, end, big_start, big_end;
};

ScaledPair MakeScaledPair() {
  ScaledPair pair{DataPath("simple/double_square.ply"),
                  DataPath("simple/double_square_bent.ply"),
                  TempDir() + "/big_start.ply", TempDir() + "/big_end.ply"};
  for (const auto& [from, to] : {std::pair{pair.start, pair.big_start},
                                 std::pair{pair.end, pair.big_end}}) {
    Mesh mesh = ReadMesh(from);
    mesh.positions *= kScale;
    WriteMesh(mesh, to);
  }
  return pair;
}

// max over frames and vertices of |big / kScale - small|, relative to the
// diameter of the small start, and the two --json reports.
struct PathPair {
  double relative_distance = 0;
  std::string small_json, big_json;
};

PathPair GeodesicsAtTwoScales(const std::string& material_flags) {
  const ScaledPair ends = MakeScaledPair();
  const std::string small_dir = TempDir() + "/small", big_dir = TempDir() + "/big";
  const std::string common = "geodesic --quiet --json --steps 4 " + material_flags;
  PathPair out;
  out.small_json = RunOk(common + " --start " + ends.start + " --end " +
                         ends.end + " --output " + small_dir);
  out.big_json = RunOk(common + " --start " + ends.big_start + " --end " +
                       ends.big_end + " --output " + big_dir);
  const FrameSequence small = ReadFrameSequence(small_dir);
  const FrameSequence big = ReadFrameSequence(big_dir);
  EXPECT_EQ(small.frames.size(), 5u);
  EXPECT_EQ(big.frames.size(), 5u);
  const Positions& s0 = small.frames[0];
  const double diameter =
      (s0.colwise().maxCoeff() - s0.colwise().minCoeff()).norm();
  for (size_t k = 0; k < std::min(small.frames.size(), big.frames.size());
       ++k) {
    out.relative_distance =
        std::max(out.relative_distance,
                 (big.frames[k] / kScale - small.frames[k])
                         .rowwise()
                         .norm()
                         .maxCoeff() /
                     diameter);
  }
  return out;
}

TEST(RelativeEtaCliTest, ScaledMeshHasTheScaledGeodesic) {
  const PathPair paths = GeodesicsAtTwoScales("");
  EXPECT_LT(paths.relative_distance, 1e-6);
  const double small_energy = Number(paths.small_json, "path_energy");
  const double big_energy = Number(paths.big_json, "path_energy");
  EXPECT_NEAR(big_energy, kScale * kScale * small_energy,
              1e-6 * big_energy);
  // eta = 1e-4 x area: the area of the double square is 1.98.
  EXPECT_EQ(kDefaultRelativeEta, 1e-4);
  EXPECT_NEAR(Number(paths.small_json, "eta"), 1.98e-4, 1e-17);
  EXPECT_NEAR(Number(paths.big_json, "eta"), 1.98e-4 * kScale * kScale,
              1e-11);
  EXPECT_NE(paths.small_json.find("\"eta_from\": \"relative\""),
            std::string::npos);
  // The bending share of E_K is the same at both scales.
  EXPECT_NEAR(Number(paths.big_json, "bending_share"),
              Number(paths.small_json, "bending_share"), 1e-6);
}

TEST(RelativeEtaCliTest, OneAbsoluteEtaIsADifferentMaterialAtEachScale) {
  // The negative twin of the test above, through the same helper. (At 1000
  // times the size bending is 1e-6 of W and the membrane-only problem does
  // not converge in 200 iterations: the absolute material is also a worse
  // problem there.)
  const PathPair paths =
      GeodesicsAtTwoScales("--eta 0.01 --allow_unconverged");
  EXPECT_GT(paths.relative_distance, 1e-3);
  EXPECT_NE(paths.small_json.find("\"eta_from\": \"absolute\""),
            std::string::npos);
  EXPECT_GT(Number(paths.small_json, "bending_share"),
            100 * Number(paths.big_json, "bending_share"));
}

TEST(RelativeEtaCliTest, EnergySplitAddsUpToThePathEnergy) {
  const PathPair paths = GeodesicsAtTwoScales("--relative_eta 0.1");
  const double membrane = Number(paths.small_json, "membrane");
  const double bending = Number(paths.small_json, "bending");
  const double total = Number(paths.small_json, "path_energy");
  EXPECT_GT(membrane, 0);
  EXPECT_GT(bending, 0);
  EXPECT_NEAR(membrane + bending, total, 1e-10 * total);
  EXPECT_NEAR(Number(paths.small_json, "bending_share"), bending / total,
              1e-12);
  EXPECT_NEAR(Number(paths.small_json, "relative_eta"), 0.1, 1e-15);
}

// energy, deform and mean (geodesic above) report the material they
// resolved from their own flags, relative or absolute.
TEST(RelativeEtaCliTest, EverySolvingVerbReportsTheMaterialItResolved) {
  const std::string dir = TempDir();
  const std::string mask = dir + "/corners.txt";
  std::ofstream(mask) << "1\n2\n3\n4\n";
  const std::string square = testing::Square4(), bent = testing::Square4Bent();
  const std::vector<std::string> runs = {
      "energy --json --reference " + square + " --deformed " + bent,
      "deform --quiet --json --reference " + square + " --targets " + bent +
          " --mask " + mask + " --output " + dir + "/deformed.ply",
      "mean --quiet --json --inputs " + square + "," + bent + " --output " +
          dir + "/mean.ply"};
  for (const std::string& run : runs) {
    const std::string relative = RunOk(run + " --relative_eta 0.02");
    EXPECT_NEAR(Number(relative, "relative_eta"), 0.02, 1e-15) << run;
    EXPECT_NE(relative.find("\"eta_from\": \"relative\""), std::string::npos)
        << relative;
    const std::string absolute = RunOk(run + " --eta 0.5");
    EXPECT_EQ(Number(absolute, "eta"), 0.5) << run;
    EXPECT_NE(absolute.find("\"eta_from\": \"absolute\""), std::string::npos)
        << absolute;
  }
}

TEST(RelativeEtaCliTest, EtaAndRelativeEtaTogetherAreAnError) {
  std::string out, err;
  EXPECT_EQ(testing::RunCli("energy --reference " + testing::Square4() +
                                " --deformed " + testing::Square4Bent() +
                                " --eta 0.01 --relative_eta 0.01",
                            &out, &err),
            1);
  EXPECT_NE(err.find("--eta and --relative_eta: give one of them"),
            std::string::npos)
      << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}

}  // namespace
}  // namespace shellspace
