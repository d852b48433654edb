// The one atomic-write helper (io/atomic_file.h): the target appears whole
// or not at all, no temporary is left behind, and temporary names are never
// taken for meshes.
#include "shellspace/io/atomic_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/io/png_writer.h"
#include "tests/testing/cli_output.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::Slurp;
std::vector<std::string> Listing(const std::string& dir) {
  return testing::DirectoryListing(dir);
}

TEST(AtomicFileTest, WritesAndReplacesWithoutTemporaries) {
  const std::string dir = testing::TempDir();
  const std::string path = dir + "/a.json";
  WriteFileAtomically(path, std::string("first\n"));
  EXPECT_EQ(Slurp(path), "first\n");
  WriteFileAtomically(path, [](std::ostream& out) { out << "second " << 2; });
  EXPECT_EQ(Slurp(path), "second 2");
  EXPECT_EQ(Listing(dir), std::vector<std::string>{"a.json"});
}

TEST(AtomicFileTest, FailedWriterKeepsTheOldFileAndLeavesNoTemporary) {
  const std::string dir = testing::TempDir();
  const std::string path = dir + "/a.txt";
  WriteFileAtomically(path, std::string("old"));
  EXPECT_THROW(WriteFileAtomically(path,
                                   [](std::ostream& out) {
                                     out << "half";
                                     throw std::runtime_error("writer");
                                   }),
               std::runtime_error);
  EXPECT_EQ(Slurp(path), "old");
  EXPECT_EQ(Listing(dir), std::vector<std::string>{"a.txt"});
  // A directory that does not exist: an InputError naming the target.
  try {
    WriteFileAtomically(dir + "/missing/b.txt", std::string("x"));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing/b.txt"), std::string::npos);
  }
}

TEST(AtomicFileTest, SetAppearsOnCommitOnly) {
  const std::string dir = testing::TempDir();
  {
    AtomicFileSet set;
    set.Add(dir + "/x.csv", std::string("1,2\n"));
    set.Add(dir + "/y.csv", std::string("3,4\n"));
    // Before the commit only temporaries exist, none of them a target.
    for (const std::string& name : Listing(dir)) {
      EXPECT_NE(name, "x.csv");
      EXPECT_NE(name, "y.csv");
    }
    // Destroyed without Commit(): nothing is left.
  }
  EXPECT_TRUE(Listing(dir).empty());
  AtomicFileSet set;
  set.Add(dir + "/x.csv", std::string("1,2\n"));
  set.Add(dir + "/y.csv", std::string("3,4\n"));
  set.Commit();
  EXPECT_EQ(Listing(dir), (std::vector<std::string>{"x.csv", "y.csv"}));
  EXPECT_EQ(Slurp(dir + "/y.csv"), "3,4\n");
}

TEST(AtomicFileTest, TemporaryNamesAreUniqueAndNotMeshFiles) {
  const std::string a = TemporarySibling("/d/shape_000.ply");
  const std::string b = TemporarySibling("/d/shape_000.ply");
  EXPECT_NE(a, b);
  for (const std::string& name : {a, b}) {
    EXPECT_EQ(name.rfind("/d/shape_000.ply", 0), 0u) << name;  // a sibling
    for (const char* ext : {".ply", ".obj", ".off", ".png", ".PLY"}) {
      EXPECT_FALSE(name.size() >= 4 &&
                   name.compare(name.size() - 4, 4, ext) == 0)
          << name;
    }
  }
  // A frame listing of a directory holding a temporary sees only the mesh.
  const std::string dir = testing::TempDir();
  WriteMesh(MakeEquilateralSheet(2, 2, 1.0), dir + "/shape_000.ply");
  std::ofstream(TemporarySibling(dir + "/shape_001.ply")) << "partial";
  EXPECT_EQ(ListFrameFiles(dir),
            std::vector<std::string>{dir + "/shape_000.ply"});
}

TEST(AtomicFileTest, MeshAndPngWritersGoThroughIt) {
  const std::string dir = testing::TempDir();
  // A 3 x 3 vertex sheet of 8 triangles.
  const Mesh square = MakeEquilateralSheet(2, 2, 1.0);
  for (const char* name : {"m.ply", "m.obj", "m.off"}) {
    WriteMesh(square, dir + "/" + name);
    const Mesh back = ReadMesh(dir + "/" + name);
    EXPECT_EQ(back.faces, square.faces) << name;
    EXPECT_LT((back.positions - square.positions).cwiseAbs().maxCoeff(), 1e-12)
        << name;
  }
  EXPECT_THROW(WriteMesh(square, dir + "/m.stl"), InputError);
  RgbImage image(3, 2, 7);
  WritePng(image, dir + "/i.png");
  const std::string png = Slurp(dir + "/i.png");
  EXPECT_EQ(png, EncodePng(image));
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(Listing(dir),
            (std::vector<std::string>{"i.png", "m.obj", "m.off", "m.ply"}));
}

}  // namespace
}  // namespace shellspace
