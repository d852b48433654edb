// Every input defect of a mesh file written here gets its one-line error
// (library and CLI), and the CLI writes no output file when it fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "shellspace/geometry/validation.h"
#include "shellspace/io/mesh_io.h"
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
