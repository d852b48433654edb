// The geodesic workflow names, before it solves, the folds and slivers of
// the end shape that the start does not have (a pose that folds the surface
// shut), each with the input it belongs to.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/workflows/geodesic.h"

namespace shellspace {
namespace {

// A 6 x 4 equilateral sheet and the same sheet rolled onto radius 0.6, one
// LM iteration (the warnings come before the solve).
workflows::GeodesicOptions RolledSheet() {
  workflows::GeodesicOptions options;
  options.start = MakeEquilateralSheet(6, 4, 0.25);
  options.topology = Topology::Build(options.start);
  options.end = RollOntoCylinder(options.start.positions, 0.6);
  options.steps = 2;
  options.material.material.eta =
      EtaFromRelative(kDefaultRelativeEta, options.start);
  options.settings = UserSolverSettings(1e-8, 1, 1, /*quiet=*/true, "test");
  return options;
}

struct Warning {
  std::string input, text;
};

TEST(GeodesicInputWarningsTest, AFoldOfTheEndShapeIsNamedWithTheEndInput) {
  workflows::GeodesicOptions options = RolledSheet();
  // An interior edge's flap: faces f and g with apexes c and d. Moving d
  // next to c in the end shape lays g over f: a fold shut.
  ASSERT_FALSE(options.topology.interior_edges.empty());
  const EdgeFlap& flap = options.topology.interior_edges.front();
  const int f = std::min(flap.face_0, flap.face_1);
  const int g = std::max(flap.face_0, flap.face_1);
  const int c = flap.k, d = flap.l;
  ASSERT_GE(d, 0);
  Positions folded = options.end;
  folded.row(d) = 0.9 * folded.row(c) + 0.1 * folded.row(d);
  options.end = folded;
  std::vector<Warning> warnings;
  options.warn = [&](const std::string& input, const std::string& text) {
    warnings.push_back({input, text});
  };
  const workflows::GeodesicResult result = workflows::RunGeodesic(options);
  EXPECT_TRUE(result.slivers.folds.empty());
  const std::pair<int, int> fold{f, g};
  EXPECT_NE(std::find(result.end_slivers.folds.begin(),
                      result.end_slivers.folds.end(), fold),
            result.end_slivers.folds.end());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].input, "end");
  EXPECT_NE(warnings[0].text.find("folded edge"), std::string::npos)
      << warnings[0].text;
  EXPECT_NE(workflows::ToJson(result).str().find(
                "\"end_slivers\": {\"faces\": ["),
            std::string::npos);

  // The twin: the plain roll has no new fold and no warning.
  warnings.clear();
  options.end = RolledSheet().end;
  const workflows::GeodesicResult plain = workflows::RunGeodesic(options);
  EXPECT_TRUE(plain.end_slivers.empty());
  EXPECT_TRUE(warnings.empty());
}

}  // namespace
}  // namespace shellspace
