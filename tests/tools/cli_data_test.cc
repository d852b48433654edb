// Successful runs of the verbs of the `shellspace` binary on the small
// meshes of ../shared/data/simple and the 121-vertex plate, each checking
// the numbers of its --json report against independent expectations
// (closed forms, the library, the files written), and the solver flags of
// `geodesic` (--multires, --lm, --linear_solver) by the energies they reach.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "tests/tools/cli_test_support.h"

namespace shellspace {
namespace {

// Sum of every "iterations" inside the "stages" array.
int StageIterations(const std::string& json) {
  const auto begin = json.find("\"stages\": [");
  if (begin == std::string::npos) return -1;
  const auto end = json.find(']', begin);
  const std::string stages = json.substr(begin, end - begin);
  int sum = 0;
  for (auto at = stages.find("\"iterations\": "); at != std::string::npos;
       at = stages.find("\"iterations\": ", at + 1)) {
    sum += std::atoi(stages.c_str() + at + 14);
  }
  return sum;
}

// W_m(s^2 I) (docs/math.md, "Membrane energy") with mu = lambda = 1: the
// membrane energy density of a flat triangle scaled by s.
double ScaledDensity(double s) {
  const double mu = 1, lambda = 1;
  const double tr = 2 * s * s, det = s * s * s * s;
  return mu / 2 * tr + lambda / 4 * det -
         (mu / 2 + lambda / 4) * std::log(det) - mu - lambda / 4;
}

// square4 scaled by 2 about its centre vertex (the origin).
std::string ScaledSquare(const std::string& dir) {
  Mesh mesh = ReadMesh(kSquare);
  mesh.positions *= 2.0;
  const std::string path = dir + "/square_x2.ply";
  WriteMesh(mesh, path);
  return path;
}

TEST(CliTest, EnergyOfAShellWithItselfIsZero) {
  const std::string json =
      RunOk("energy --json --reference " + kSquare + " --deformed " + kSquare);
  EXPECT_EQ(Number(json, "membrane"), 0.0) << json;
  EXPECT_EQ(Number(json, "bending"), 0.0) << json;
  EXPECT_EQ(Number(json, "total"), 0.0) << json;
}

TEST(CliTest, EnergyOfAScaledFlatSquareIsTheClosedForm) {
  const std::string dir = TempDir();
  const std::string json =
      RunOk("energy --json --reference " + kSquare + " --deformed " +
            ScaledSquare(dir) + " --eta 0.5");
  // Reference area 1 (the unit square); flat stays flat: no bending.
  EXPECT_NEAR(Number(json, "membrane"), ScaledDensity(2.0), 1e-12) << json;
  EXPECT_NEAR(Number(json, "bending"), 0.0, 1e-20) << json;
  EXPECT_NEAR(Number(json, "total"), ScaledDensity(2.0), 1e-12) << json;
  EXPECT_EQ(Number(json, "eta"), 0.5);
}

TEST(CliTest, DeformWithTheBoundaryScaledKeepsTheSymmetricCentre) {
  const std::string dir = TempDir();
  const std::string mask = dir + "/boundary.txt";
  std::ofstream(mask) << "# the four corners\n1\n2\n3\n4\n";
  const std::string out = dir + "/deformed.off";
  const std::string json =
      RunOk("deform --quiet --json --reference " + kSquare + " --mask " + mask +
            " --targets " + ScaledSquare(dir) + " --output " + out);
  // The centre stays at the origin by symmetry: every triangle is scaled by
  // 2, the closed form.
  EXPECT_NEAR(Number(json, "total"), ScaledDensity(2.0), 1e-9) << json;
  EXPECT_TRUE(Bool(json, "converged")) << json;
  const Mesh deformed = ReadMesh(out);
  EXPECT_LT(deformed.positions.row(0).norm(), 1e-9);
  const Mesh square = ReadMesh(kSquare);
  for (int v = 1; v <= 4; ++v) {
    EXPECT_NEAR(
        (deformed.positions.row(v) - 2 * square.positions.row(v)).norm(), 0,
        1e-12);
  }
  EXPECT_EQ(DirectoryListing(dir),
            (std::vector<std::string>{"boundary.txt", "deformed.off",
                                      "square_x2.ply"}));
}

TEST(CliTest, GeodesicReportsTheLibraryNumbers) {
  const std::string dir = TempDir() + "/geodesic";
  const std::string json =
      RunOk("geodesic --quiet --json --steps 8 --start " + kSquare + " --end " +
            kBent + " --output " + dir);
  const double energy = Number(json, "path_energy");
  const std::vector<double> steps = Numbers(json, "step_energies");
  ASSERT_EQ(steps.size(), 8u) << json;
  // E_K = K sum_k W[s_{k-1}, s_k] >= 0, with nearly equal steps.
  double sum = 0;
  for (double w : steps) sum += w;
  EXPECT_GT(energy, 0);
  EXPECT_NEAR(energy, 8 * sum, 1e-12 * energy);
  const auto [lo, hi] = std::minmax_element(steps.begin(), steps.end());
  EXPECT_LT(*hi / *lo - 1, 0.05) << json;
  // Below the energy of the linear path (the initial guess).
  const Mesh a = ReadMesh(kSquare), b = ReadMesh(kBent);
  const ShellSpace space = testing::MakeSpace(a, testing::CliDefaultMaterial(a));
  const double linear =
      PathEnergy(space, LinearPath(a.positions, b.positions, 8));
  EXPECT_LE(energy, linear);
  // iterations counts every stage; converged means the gradient criterion.
  EXPECT_EQ(Number(json, "iterations"), StageIterations(json)) << json;
  EXPECT_GT(Number(json, "iterations"), 0);
  EXPECT_TRUE(Bool(json, "converged")) << json;
  const double g0 = Number(json, "initial_gradient_norm");
  const double g = Number(json, "final_gradient_norm");
  EXPECT_LE(g, 1e-8 * std::max(1.0, g0)) << json;
  EXPECT_NEAR(Number(json, "relative_gradient_norm"), g / g0, 1e-15);
  EXPECT_EQ(Number(json, "frames"), 9);
  // The frames, nothing else; the ends are the inputs.
  EXPECT_EQ(DirectoryListing(dir), FramesAndSummary(9));
  // summary.json is the printed report, with the run's identity.
  EXPECT_EQ(Slurp(dir + "/summary.json"), json);
  EXPECT_NE(json.find("\"run_id\": \""), std::string::npos) << json;
  EXPECT_NE(json.find("\"command_line\": \""), std::string::npos) << json;
  EXPECT_EQ(ReadMesh(dir + "/shape_000.ply").positions, a.positions);
  EXPECT_EQ(ReadMesh(dir + "/shape_008.ply").positions, b.positions);
  // The frames' energy, evaluated by the library from the files, is the
  // reported one.
  ShellPath path;
  for (const std::string& name : Frames(9)) {
    path.push_back(ReadMesh(dir + "/" + name).positions);
  }
  EXPECT_NEAR(PathEnergy(space, path), energy, 1e-9 * energy);
}

TEST(CliTest, ShootLogAndTransportAlongAGeodesic) {
  const std::string base = TempDir();
  const std::string geodesic = base + "/geodesic";
  RunOk("geodesic --quiet --steps 4 --start " + kSquare + " --end " + kBent +
        " --output " + geodesic);
  // Shooting from the geodesic's first step continues it to its end.
  const std::string shot = base + "/shot";
  const std::string json = RunOk("shoot --quiet --json --steps 4 --first " +
                                 geodesic + "/shape_000.ply --second " +
                                 geodesic + "/shape_001.ply --output " + shot);
  EXPECT_EQ(DirectoryListing(shot), FramesAndSummary(5));
  // The shot ends at the geodesic's end up to a rigid motion (the gauges of
  // the two solves differ): W[end, shot end] = 0.
  const std::string w = RunOk("energy --json --reference " + kBent +
                              " --deformed " + shot + "/shape_004.ply");
  EXPECT_LT(std::abs(Number(w, "total")), 1e-7) << w;
  EXPECT_EQ(Number(json, "iterations"), StageIterations(json)) << json;
  EXPECT_TRUE(Bool(json, "converged")) << json;
  const std::vector<double> steps = Numbers(json, "step_energies");
  ASSERT_EQ(steps.size(), 4u);
  double sum = 0;
  for (double w : steps) sum += w;
  EXPECT_NEAR(Number(json, "path_energy"), 4 * sum, 1e-12 * sum);

  // LOG_4(A -> B) = 4 (s_1 - A) of the same geodesic.
  const std::string log = base + "/log.ply";
  const std::string log_json =
      RunOk("log --quiet --json --steps 4 --start " + kSquare + " --end " +
            kBent + " --output " + log);
  const Mesh a = ReadMesh(kSquare);
  const Mesh s1 = ReadMesh(geodesic + "/shape_001.ply");
  const Positions expected = a.positions + 4 * (s1.positions - a.positions);
  const Positions written = ReadMesh(log).positions;
  EXPECT_LT((written - expected).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_NEAR(Number(log_json, "log_max_norm"),
              (written - a.positions).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(Number(log_json, "iterations"), StageIterations(log_json));

  // Transporting the zero variation keeps it zero and the shapes on the path.
  const std::string moved = base + "/transport";
  const std::string t_json =
      RunOk("transport --quiet --json --path " + geodesic + " --variation " +
            geodesic + "/shape_000.ply --output " + moved);
  const std::vector<double> norms = Numbers(t_json, "variation_max_norms");
  ASSERT_EQ(norms.size(), 5u) << t_json;
  for (double n : norms) EXPECT_LT(n, 1e-6) << t_json;
  EXPECT_EQ(Number(t_json, "epsilon"), 1.0);
  // iterations counts every rung's midpoint solves (LM + Newton of the
  // 2-step geodesic) and EXP iterations.
  double rung_iterations = 0;
  for (const char* key : {"midpoint_iterations", "newton_steps", "lm_iterations"}) {
    const std::vector<double> counts = testing::EveryNumber(t_json, key);
    ASSERT_EQ(counts.size(), 4u) << key << t_json;
    for (double c : counts) rung_iterations += c;
  }
  EXPECT_GT(Number(t_json, "midpoint_iterations"), 0) << t_json;
  EXPECT_EQ(Number(t_json, "iterations"), rung_iterations) << t_json;
  EXPECT_EQ(DirectoryListing(moved), FramesAndSummary(5));
}

TEST(CliTest, SplineThroughKeyframesAndRegression) {
  const std::string dir = TempDir();
  // Keyframes on a discrete geodesic: the geodesic is the spline, F_K = 0.
  const std::string geodesic = dir + "/geodesic";
  RunOk("geodesic --quiet --steps 4 --start " + kSquare + " --end " + kBent +
        " --output " + geodesic);
  const std::string keys = geodesic + "/shape_000.ply," + geodesic +
                           "/shape_002.ply," + geodesic + "/shape_004.ply";
  const std::string json =
      RunOk("spline --quiet --json --keyframes " + keys +
            " --at 0,2,4 --steps 4 --output " + dir + "/spline");
  EXPECT_EQ(DirectoryListing(dir + "/spline"), FramesAndSummary(5));
  EXPECT_LT(std::abs(Number(json, "spline_energy")), 1e-8) << json;
  // The keyframes are data: the frame at 2 is the input.
  EXPECT_EQ(ReadMesh(dir + "/spline/shape_002.ply").positions,
            ReadMesh(geodesic + "/shape_002.ply").positions);
  EXPECT_EQ(Number(json, "objective"), Number(json, "spline_energy"));
  EXPECT_GE(Number(json, "iterations"), 1);
  EXPECT_TRUE(Bool(json, "converged")) << json;

  // This regression, capped at 2 L-BFGS iterations, stops short of the
  // gradient tolerance: it says so ("converged": false, exit 4, below with
  // --allow_unconverged to accept it).
  const std::string r_json = RunOk(
      "regress --quiet --json --allow_unconverged --max_iterations 2 "
      "--inputs " + kSquare + "," + kBent +
      " --at 0,2 --steps 2 --sigma 0.5 --output " + dir + "/regress");
  EXPECT_FALSE(Bool(r_json, "converged")) << r_json;
  EXPECT_EQ(Number(r_json, "iterations"), 2) << r_json;
  EXPECT_EQ(DirectoryListing(dir + "/regress"), FramesAndSummary(3));
  const double data = Number(r_json, "data_energy");
  const double spline = Number(r_json, "spline_energy");
  EXPECT_GE(data, 0);
  EXPECT_GE(spline, 0);
  EXPECT_NEAR(Number(r_json, "objective"), data + 0.5 * spline,
              1e-12 * (data + spline));
  EXPECT_EQ(Number(r_json, "sigma"), 0.5);
}

TEST(CliTest, MeanAndPca) {
  const std::string dir = TempDir();
  // The mean of two copies of one shell is that shell: energy 0.
  const std::string same = RunOk("mean --quiet --json --inputs " + kSquare +
                                 "," + kSquare + " --output " + dir + "/m.ply");
  EXPECT_LT(Number(same, "energy"), 1e-20) << same;
  EXPECT_TRUE(Bool(same, "converged")) << same;

  const std::string json =
      RunOk("mean --quiet --json --inputs " + kSquare + "," + kBent +
            " --output " + dir + "/mean.ply");
  const std::vector<double> energies = Numbers(json, "energies");
  ASSERT_EQ(energies.size(), 2u);
  EXPECT_NEAR(Number(json, "energy"), energies[0] + energies[1],
              1e-12 * Number(json, "energy"));
  EXPECT_GT(energies[0], 0);
  EXPECT_GT(energies[1], 0);
  EXPECT_EQ(Number(json, "iterations"),
            Number(json, "lm_iterations") + Number(json, "newton_iterations"));
  EXPECT_TRUE(Bool(json, "converged")) << json;
  EXPECT_LE(Number(json, "final_gradient_norm"),
            1e-8 * std::max(1.0, Number(json, "initial_gradient_norm")));

  const std::string pca = dir + "/pca";
  const std::string p_json =
      RunOk("pca --quiet --json --modes 1 --inputs " + kSquare + "," + kBent +
            "," + DataPath("simple/square4.ply") + " --output " + pca);
  EXPECT_EQ(DirectoryListing(pca),
            (std::vector<std::string>{"mean.ply", "mode_1_minus.ply",
                                      "mode_1_plus.ply", "pca.json",
                                      "summary.json"}));
  // pca.json and summary.json are the printed summary.
  EXPECT_EQ(Slurp(pca + "/pca.json"), p_json);
  EXPECT_EQ(Slurp(pca + "/summary.json"), p_json);
  // The Gram matrix of 3 displacements, two of them equal (the first and
  // the third input are one shell): rank <= 2, the third eigenvalue is 0.
  const std::vector<double> eigenvalues = Numbers(p_json, "eigenvalues");
  ASSERT_EQ(eigenvalues.size(), 3u) << p_json;
  EXPECT_GT(eigenvalues[0], 0);
  EXPECT_GE(eigenvalues[0], eigenvalues[1]);
  EXPECT_LT(std::abs(eigenvalues[2]), 1e-12 * eigenvalues[0]) << p_json;
}

TEST(CliTest, RenderWritesTheStripItReports) {
  const std::string dir = TempDir();
  const std::string out = dir + "/strip.png";
  const std::string json = RunOk("render --json --input " + kSquare + "," +
                                 kBent + " --output " + out + " --width 80");
  // --width is the whole image; frames are square unless --height, with a
  // label strip of 12 rows under them.
  EXPECT_EQ(Number(json, "frames"), 2);
  EXPECT_EQ(Number(json, "frame_width"), 40);
  EXPECT_EQ(Number(json, "frame_height"), 40);
  EXPECT_EQ(Number(json, "width"), 80);
  EXPECT_EQ(Number(json, "height"), 40 + 12);
  const std::string png = Slurp(out);
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(DirectoryListing(dir), std::vector<std::string>{"strip.png"});
}

// --gltf and --png are written with the frames, together or not at all: a
// .glb or a film strip in a missing directory fails with one line and leaves
// no frames, no directory and no temporary behind; with good paths all
// three appear.
TEST(CliTest, GltfAndPngAreWrittenWithTheFramesOrNothing) {
  const std::string dir = TempDir();
  const std::string common = "geodesic --quiet --steps 2 --start " + kSquare +
                             " --end " + kBent + " --output " + dir + "/g";
  for (const std::string& extra :
       {" --gltf " + dir + "/missing/a.glb",
        " --gltf " + dir + "/a.glb --png " + dir + "/missing/a.png"}) {
    std::string err;
    EXPECT_EQ(RunCli(common + extra, nullptr, &err), 1) << extra;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find("missing"), std::string::npos) << err;
    EXPECT_TRUE(DirectoryListing(dir).empty()) << extra;
  }
  ASSERT_EQ(
      RunCli(common + " --gltf " + dir + "/a.glb --png " + dir + "/a.png"), 0);
  EXPECT_EQ(DirectoryListing(dir),
            (std::vector<std::string>{"a.glb", "a.png", "g"}));
  EXPECT_EQ(DirectoryListing(dir + "/g"), FramesAndSummary(3));
}

// --multires on a small mesh: two levels (the coarse one decimated), the
// same E_K as without, and a clear error for a bad value.
TEST(CliTest, GeodesicMultiresolutionLevels) {
  const std::string dir = testing::TempDir();
  const std::string common =
      "geodesic --start " + testing::DataPath("plate/plate121.ply") +
      " --end " + testing::DataPath("plate/plate121_rolledA.ply") +
      " --steps 4 --quiet --json --tolerance 1e-10 --output " + dir;
  std::string out_multi, out_single, err;
  ASSERT_EQ(testing::RunCli(common + "/multi --multires 1", &out_multi, &err),
            0)
      << err;
  ASSERT_EQ(
      testing::RunCli(common + "/single --multires off", &out_single, &err), 0)
      << err;
  const double multi = Number(out_multi, "path_energy");
  const double single = Number(out_single, "path_energy");
  EXPECT_NEAR(multi, single, 1e-8 * single);
  // Two levels listed, the coarse one with fewer vertices, the fine one 121.
  const size_t levels = out_multi.find("\"multires_levels\"");
  ASSERT_NE(levels, std::string::npos) << out_multi;
  const size_t first = out_multi.find("\"vertices\":", levels);
  const size_t second = out_multi.find("\"vertices\":", first + 1);
  ASSERT_NE(second, std::string::npos) << out_multi;
  EXPECT_LT(std::stoi(out_multi.substr(first + 11)), 121);
  EXPECT_EQ(std::stoi(out_multi.substr(second + 11)), 121);
  EXPECT_NE(testing::RunCli(common + "/bad --multires two", nullptr, &err), 0);
  EXPECT_NE(err.find("--multires"), std::string::npos) << err;
}

// The text after "KEY": "  in `json` up to the closing quote; "" if absent.
std::string Text(const std::string& json, const std::string& key) {
  const std::string needle = "\"" + key + "\": \"";
  const auto at = json.find(needle);
  if (at == std::string::npos) return "";
  const auto begin = at + needle.size();
  return json.substr(begin, json.find('"', begin) - begin);
}

// A geodesic on the plate (plate121 -> rolledA, K = 4, tolerance 1e-10,
// --json, no multiresolution) into a fresh temporary directory: append
// "/NAME" and the flags under test.
std::string PlateGeodesicCommand() {
  return "geodesic --start " + testing::DataPath("plate/plate121.ply") +
         " --end " + testing::DataPath("plate/plate121_rolledA.ply") +
         " --steps 4 --quiet --json --tolerance 1e-10 --multires off "
         "--output " +
         testing::TempDir();
}

// --lm: Ceres' LM and the engine's give the same E_K (1e-8), the stages
// name who ran them, auto is Ceres on the plate, a bad value is rejected by
// name.
TEST(CliTest, GeodesicLmFlag) {
  const std::string common = PlateGeodesicCommand();
  std::string ceres, engine, automatic, err;
  ASSERT_EQ(RunCli(common + "/c --lm ceres", &ceres, &err), 0) << err;
  ASSERT_EQ(RunCli(common + "/e --lm engine", &engine, &err), 0) << err;
  ASSERT_EQ(RunCli(common + "/a", &automatic, &err), 0) << err;
  EXPECT_NE(ceres.find("\"solver\": \"ceres\""), std::string::npos) << ceres;
  EXPECT_EQ(engine.find("\"solver\": \"ceres\""), std::string::npos) << engine;
  EXPECT_NE(engine.find("\"solver\": \"direct\""), std::string::npos) << engine;
  EXPECT_NE(automatic.find("\"solver\": \"ceres\""), std::string::npos)
      << automatic;
  EXPECT_TRUE(Bool(engine, "converged")) << engine;
  const double e = Number(ceres, "path_energy");
  EXPECT_NEAR(Number(engine, "path_energy"), e, 1e-8 * e);
  EXPECT_EQ(RunCli(common + "/bad --lm gauss", nullptr, &err), 1);
  EXPECT_NE(err.find("--lm must be auto, ceres or engine"), std::string::npos)
      << err;
}

// --linear_solver: direct and block-jacobi give the same E_K, --json names
// the solver used and its counts, auto is direct on the plate, and a bad
// value is rejected by name (geodesic and log).
TEST(CliTest, GeodesicLinearSolverFlag) {
  const std::string common = PlateGeodesicCommand();
  std::string direct, jacobi, automatic, err;
  ASSERT_EQ(RunCli(common + "/d --linear_solver direct", &direct, &err), 0)
      << err;
  ASSERT_EQ(RunCli(common + "/j --linear_solver block-jacobi", &jacobi, &err),
            0)
      << err;
  ASSERT_EQ(RunCli(common + "/a", &automatic, &err), 0) << err;
  EXPECT_EQ(Text(direct, "linear_solver"), "direct") << direct;
  EXPECT_EQ(Text(jacobi, "linear_solver"), "block-jacobi") << jacobi;
  EXPECT_EQ(Text(automatic, "linear_solver"), "direct") << automatic;
  EXPECT_GE(Number(jacobi, "factorizations"), 1) << jacobi;
  EXPECT_GT(Number(jacobi, "cg_iterations"), 0) << jacobi;
  EXPECT_EQ(Number(jacobi, "cg_not_converged"), 0) << jacobi;
  EXPECT_TRUE(Bool(jacobi, "converged")) << jacobi;
  const double e_direct = Number(direct, "path_energy");
  EXPECT_NEAR(Number(jacobi, "path_energy"), e_direct, 1e-8 * e_direct);
  EXPECT_EQ(Number(automatic, "path_energy"), e_direct);
  EXPECT_EQ(RunCli(common + "/bad --linear_solver cholesky", nullptr, &err), 1);
  EXPECT_NE(err.find("--linear_solver must be auto, direct or block-jacobi"),
            std::string::npos)
      << err;
  // log reads the flag too.
  std::string log;
  ASSERT_EQ(
      RunCli("log --start " + testing::DataPath("plate/plate121.ply") +
                 " --end " + testing::DataPath("plate/plate121_rolledA.ply") +
                 " --steps 4 --json --linear_solver block-jacobi "
                 "--output " +
                 testing::TempDir() + "/log.ply",
             &log, &err),
      0)
      << err;
  EXPECT_EQ(Text(log, "linear_solver"), "block-jacobi") << log;
}

}  // namespace
}  // namespace shellspace
