// Input errors on the shared squares: incompatible connectivities, and the
// library's messages for a bad material and bad arguments of the geodesic,
// shooting, transport and regression solvers, which say what is wrong in
// the library's terms and never name a CLI flag.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <utility>

#include "shellspace/geometry/validation.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/parallel_transport.h"
#include "shellspace/problems/splines/spline.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

TEST(InputErrorsTest, Compatibility) {
  const Mesh a = testing::LoadData("simple/double_square.ply");
  const Mesh rotated = testing::LoadData("simple/double_square_bent.ply");
  EXPECT_NO_THROW(CheckCompatible(a, "a", rotated, "b"));
  Mesh flipped = rotated;
  std::swap(flipped.faces(0, 1), flipped.faces(0, 2));
  EXPECT_THROW(CheckCompatible(a, "a", flipped, "b"), InputError);
  const Mesh other = testing::LoadData("simple/square4.ply");
  try {
    CheckCompatible(a, "a", other, "b");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("incompatible connectivity"),
              std::string::npos);
  }
}

// The library's messages say what is wrong in its own terms and never name
// a CLI flag (tools/ owns those).
TEST(InputErrorsTest, LibraryMessagesNameTheInputNotAFlag) {
  const Mesh square = testing::LoadData("simple/square4.ply");
  const ShellSpace space = testing::MakeSpace(square);
  const auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  struct Case {
    std::string message, expected;
  };
  GeodesicInput geodesic;
  geodesic.start = geodesic.end = square.positions;
  geodesic.steps = 0;
  const Case cases[] = {
      {message([] {
         ShellMaterial{-1, 1, 0}.Validate();
       }),
       "membrane weight mu must be a positive number, got -1"},
      {message([] {
         ShellMaterial{1, 0, 0}.Validate();
       }),
       "lambda"},
      {message([] {
         ShellMaterial{1, 1, -2}.Validate();
       }),
       "bending weight eta"},
      {message([&] { SolveGeodesic(space, geodesic, SolverSettings{}); }),
       "geodesic: the number of steps K must be at least 1, got 0"},
      {message([&] {
         Shoot(space, square.positions, square.positions, 0,
               StepDirection::kForward, {}, SolverSettings{});
       }),
       "number of steps must be at least 1, got 0"},
      {message([&] {
         ParallelTransport(space, {square.positions, square.positions},
                           square.positions * 0, 0.0, {}, SolverSettings{});
       }),
       "step epsilon must be positive"},
      {message([&] {
         SolveRegression(space, {square.positions, square.positions}, {0, 2}, 2,
                         -1.0, {}, SplineSettings{});
       }),
       "weight sigma"},
      {message([&] {
         SolveRegression(space, {square.positions, square.positions}, {0}, 2,
                         1.0, {}, SplineSettings{});
       }),
       "one time index per shape"},
  };
  for (const Case& c : cases) {
    EXPECT_NE(c.message.find(c.expected), std::string::npos) << c.message;
    EXPECT_EQ(c.message.find("--"), std::string::npos) << c.message;
  }
}

}  // namespace
}  // namespace shellspace
