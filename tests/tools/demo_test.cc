// The README's demo: the procedural finger geodesic plus extrapolation writes
// 13 frames, a JSON summary, a PNG film strip and the viewer page, with near-equal geodesic
// steps; and the procedural shapes are valid shells.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/io/mesh_io.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

TEST(DemoTest, ProceduralFingerIsAValidClosedTopShell) {
  const Mesh finger = MakeFinger();
  const Topology topology = ValidateShell(finger, "finger");
  EXPECT_EQ(topology.boundary_edges.size(), 24u);  // only the open bottom ring
  Mesh bent = finger;
  bent.positions = BendAlongY(finger.positions, 4.0, std::acos(-1.0) / 2);
  ValidateShell(bent, "bent");
  // The bend is isometric on the tube's axis: the pole moves to about
  // (R, R) + cap offset with R = 8 / pi, and the base does not move.
  for (int v : FingerBaseVertices()) {
    if (finger.positions(v, 1) == 0.0) {
      EXPECT_LT((bent.positions.row(v) - finger.positions.row(v)).norm(),
                1e-12);
    }
  }
  const double R = 8 / std::acos(-1.0);
  const Eigen::RowVector3d pole = bent.positions.row(bent.num_vertices() - 1);
  EXPECT_NEAR(pole(0), R + 0.5, 1e-9);
  EXPECT_NEAR(pole(1), R, 1e-9);
}

TEST(DemoTest, WritesFramesSummaryAndFilmStrip) {
  const std::string dir = testing::TempDir() + "/demo";
  std::string out, err;
  ASSERT_EQ(testing::RunCli("demo --quiet --output " + dir, &out, &err), 0)
      << err;
  for (int k = 0; k <= 12; ++k) {
    char name[64];
    std::snprintf(name, sizeof(name), "/frames/shape_%03d.ply", k);
    EXPECT_TRUE(std::filesystem::exists(dir + name)) << name;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/frames/shape_013.ply"));
  EXPECT_GT(std::filesystem::file_size(dir + "/film_strip.png"), 1000u);
  std::ifstream json(dir + "/summary.json");
  std::stringstream text;
  text << json.rdbuf();
  EXPECT_NE(text.str().find("\"converged\": true"), std::string::npos);
  // The viewer page carries the 13 frames of 721 vertices and the summary
  // itself (its run id).
  std::ifstream page_file(dir + "/viewer.html");
  std::stringstream page;
  page << page_file.rdbuf();
  EXPECT_NE(page.str().find("data-vertices=\"721\" data-frames=\"13\""),
            std::string::npos);
  const std::string run_id = "\"run_id\": \"";
  const auto id = text.str().find(run_id);
  ASSERT_NE(id, std::string::npos);
  EXPECT_NE(page.str().find(text.str().substr(id, run_id.size() + 16)),
            std::string::npos);
  // The geodesic's 8 step energies agree to a few percent (equal steps).
  const std::string key = "\"step_energies\": [";
  const auto begin = text.str().find(key);
  ASSERT_NE(begin, std::string::npos);
  std::stringstream values(text.str().substr(begin + key.size()));
  std::vector<double> steps;
  for (int k = 0; k < 8; ++k) {
    double v;
    char comma;
    values >> v >> comma;
    steps.push_back(v);
  }
  const auto [lo, hi] = std::minmax_element(steps.begin(), steps.end());
  EXPECT_GT(*lo, 0);
  EXPECT_LT(*hi / *lo - 1, 0.05);
  // The report is the solver's: the final gradient is the Newton finish's
  // (below the relative tolerance 1e-8), and iterations are the sum over
  // the stages (LM, Newton, the 4 EXP steps).
  const auto number = [&](const std::string& key, size_t from = 0) {
    const auto at = text.str().find("\"" + key + "\": ", from);
    return at == std::string::npos
               ? -1.0
               : std::strtod(text.str().c_str() + at + key.size() + 4, nullptr);
  };
  EXPECT_LE(number("final_gradient_norm"),
            1e-8 * std::max(1.0, number("initial_gradient_norm")))
      << text.str();
  const auto stages = text.str().find("\"stages\": [");
  ASSERT_NE(stages, std::string::npos);
  const auto stages_end = text.str().find(']', stages);
  double sum = 0;
  int count = 0;
  for (auto at = text.str().find("\"iterations\": ", stages);
       at != std::string::npos && at < stages_end;
       at = text.str().find("\"iterations\": ", at + 1)) {
    sum += std::strtod(text.str().c_str() + at + 14, nullptr);
    ++count;
  }
  EXPECT_GE(count, 2 + 4);  // at least one LM and one Newton stage, 4 EXP
  EXPECT_EQ(number("iterations"), sum) << text.str();
  // The extrapolated end differs from the last geodesic frame.
  const Mesh end = ReadMesh(dir + "/frames/shape_008.ply");
  const Mesh beyond = ReadMesh(dir + "/frames/shape_012.ply");
  EXPECT_GT((end.positions - beyond.positions).cwiseAbs().maxCoeff(), 0.1);
}

}  // namespace
}  // namespace shellspace
