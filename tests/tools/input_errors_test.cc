// Every input defect gets its one-line error (library and CLI), and the CLI
// writes no output file when it fails.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "shellspace/geometry/validation.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/parallel_transport.h"
#include "shellspace/problems/splines/spline.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

std::string Write(const std::string& dir, const std::string& name,
                  const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

const char* kHeader =
    "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\n"
    "property float y\nproperty float z\nelement face %d\n"
    "property list uchar int vertex_indices\nend_header\n";

std::string Ply(int nv, int nf, const std::string& body) {
  char header[512];
  std::snprintf(header, sizeof(header), kHeader, nv, nf);
  return header + body;
}

// Loads and validates; returns the error message ("" if none).
std::string ErrorOf(const std::string& path) {
  try {
    ValidateShell(ReadMesh(path), path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(InputErrorsTest, LibraryErrors) {
  const std::string dir = testing::TempDir();
  struct Case {
    const char* file;
    std::string text;  // "": the file is not written
    const char* expected;
  };
  const Case cases[] = {
      {"missing.ply", "", "cannot open"},
      {"garbage.off", "not a mesh\n", "cannot read"},
      {"quad.ply", Ply(4, 1, "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"),
       "only triangle"},
      // Three triangles on the edge (0, 1).
      {"nonmanifold.ply",
       Ply(5, 3,
           "0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n"
           "3 0 1 4\n"),
       "non-manifold"},
      {"degenerate.ply",
       Ply(4, 2, "0 0 0\n1 0 0\n2 0 0\n0 1 0\n3 0 1 2\n3 0 3 1\n"),
       "degenerate"},
      {"nan.ply", Ply(3, 1, "0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"),
       "non-finite"},
      {"range.ply", Ply(3, 1, "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
       "references vertex 7"},
      {"short.ply", Ply(3, 1, "0 0 0\n1 0 0\n"), "ends early"},
  };
  for (const Case& c : cases) {
    const std::string path = c.text.empty() ? dir + "/" + c.file
                                            : Write(dir, c.file, c.text);
    const std::string error = ErrorOf(path);
    EXPECT_NE(error.find(c.expected), std::string::npos)
        << c.file << ": \"" << error << "\"";
  }
}

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

TEST(InputErrorsTest, CliReportsOneLineAndWritesNothing) {
  const std::string dir = testing::TempDir();
  const std::string out = dir + "/out.ply";
  const std::string square = testing::DataPath("simple/square4.ply");
  const std::string cases[] = {
      "energy --reference " + dir + "/missing.ply --deformed " + square,
      "energy --reference " + square + " --deformed " +
          testing::DataPath("simple/double_square.ply"),
      "energy --reference " + square + " --deformed " + square + " --mu -1",
      "energy --deformed " + square,
      "deform --reference " + square + " --mask " + dir + "/nomask.txt" +
          " --targets " + square + " --output " + out,
      "deform --reference " + square + " --mask " +
          Write(dir, "bad_mask.txt", "0\n99\n") + " --targets " + square +
          " --output " + out,
      "energy --reference " + square + " --deformed " + square +
          " --no_such_flag=1",
      "no_such_verb",
  };
  for (const std::string& args : cases) {
    std::string err;
    const int code = testing::RunCli(args, nullptr, &err);
    EXPECT_NE(code, 0) << args;
    EXPECT_FALSE(err.empty()) << args;
    EXPECT_LE(std::count(err.begin(), err.end(), '\n'), 1) << args << "\n"
                                                           << err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
}

}  // namespace
}  // namespace shellspace
