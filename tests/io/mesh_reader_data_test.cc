// The mesh reader and writer on the shared meshes: the rolled plate written
// in every format reads back bit for bit, and CGAL's dino.off (a real COFF
// file with per-vertex colours) reads with its colours ignored.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include "shellspace/io/mesh_io.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

TEST(MeshReaderTest, WrittenMeshesReadBackBitExactly) {
  const Mesh mesh = testing::LoadData("plate/plate121_rolledA.ply");
  const std::string dir = testing::TempDir();
  for (const char* ext : {"ply", "obj", "off"}) {
    const std::string path = dir + "/plate." + ext;
    WriteMesh(mesh, path);
    const Mesh back = ReadMesh(path);
    EXPECT_EQ(back.positions, mesh.positions) << ext;
    EXPECT_EQ(back.faces, mesh.faces) << ext;
  }
}

// A real COFF file: CGAL's dino.off (per-vertex colours r g b a), read with
// its colours ignored; its first and last vertex and face as printed.
TEST(MeshReaderDataTest, CgalDinoCoffReads) {
  const Mesh dino = testing::LoadData("cgal/dino.off");
  ASSERT_EQ(dino.num_vertices(), 3916);
  ASSERT_EQ(dino.num_faces(), 7828);
  EXPECT_EQ(dino.positions.row(0),
            Eigen::RowVector3d(0.991441, -0.544272, -0.555859));
  EXPECT_EQ(dino.faces.row(7827), Eigen::RowVector3i(1859, 2191, 1904));
}

}  // namespace
}  // namespace shellspace
