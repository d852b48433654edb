// The mesh and mask readers: every defect of the table in
// tests/io/bad_mesh_files.h, in every format it applies to, is one InputError
// line naming the file and the element; valid files of every format read
// back exactly.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "shellspace/geometry/validation.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/tests/io/bad_mesh_files.h"
#include "shellspace/tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::MeshFormat;

const MeshFormat kFormats[] = {MeshFormat::kPlyAscii, MeshFormat::kPlyBinary,
                               MeshFormat::kObj, MeshFormat::kOff};

std::string Write(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// The message of the InputError of reading (and, unless `read_only`,
// validating) `path`; "" if there is none. Any other exception fails.
std::string ReadError(const std::string& path, bool read_only = false) {
  try {
    const Mesh mesh = ReadMesh(path);
    if (!read_only) ValidateShell(mesh, path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshReaderTest, EveryDefectInEveryFormatIsOneLineNamingFileAndElement) {
  const std::string dir = testing::TempDir();
  int checked = 0;
  for (const testing::BadMeshFile& file : testing::WriteBadMeshFiles(dir)) {
    const std::string& path = file.path;
    SCOPED_TRACE(path);
    if (file.defect.degenerate_only) {
      EXPECT_EQ(ReadError(path, /*read_only=*/true), "");
    }
    const std::string message = ReadError(path);
    ASSERT_FALSE(message.empty()) << "accepted";
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& word : file.defect.expected) {
      EXPECT_NE(message.find(word), std::string::npos)
          << "'" << word << "' not in: " << message;
    }
    ++checked;
  }
  // 21 defects; the formats each applies to (bad_mesh_files.h).
  EXPECT_EQ(checked, 70);
}

TEST(MeshReaderTest, ValidSquareReadsBackInEveryFormat) {
  const std::string dir = testing::TempDir();
  const testing::MeshSpec square = testing::Square();
  for (MeshFormat format : kFormats) {
    const std::string path = dir + "/square_" + testing::FormatName(format) +
                             "." + testing::FormatExtension(format);
    Write(path, testing::MeshFileContent(square, format));
    SCOPED_TRACE(path);
    const Mesh mesh = ReadMesh(path);
    ASSERT_EQ(mesh.num_vertices(), 4);
    ASSERT_EQ(mesh.num_faces(), 2);
    EXPECT_EQ(mesh.positions.row(2), Eigen::RowVector3d(1, 1, 0));
    EXPECT_EQ(mesh.faces.row(1), Eigen::RowVector3i(0, 2, 3));
    EXPECT_EQ(ValidateShell(mesh, path).edges.size(), 5u);
  }
}

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

TEST(MeshReaderTest, BinaryPlyBigEndianFloatAndExtraProperties) {
  // Big-endian float coordinates, an extra uchar vertex property, an int
  // face property before the list, an extra element: read, the rest ignored.
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\ncomment test\n"
      "element vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar quality\nelement face 2\n"
      "property int tag\nproperty list uchar uint vertex_indices\n"
      "element edge 1\nproperty int a\nproperty int b\nend_header\n";
  const auto put_be = [&bytes](uint32_t u) {
    for (int i = 3; i >= 0; --i) bytes += static_cast<char>((u >> (8 * i)) & 0xff);
  };
  const float coordinates[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5f}};
  for (const auto& v : coordinates) {
    for (float x : v) {
      uint32_t u;
      std::memcpy(&u, &x, 4);
      put_be(u);
    }
    bytes += '\x07';
  }
  for (const auto& f : {std::array<uint32_t, 3>{0, 1, 2}, {0, 2, 3}}) {
    put_be(42);
    bytes += '\x03';
    for (uint32_t v : f) put_be(v);
  }
  put_be(0);
  put_be(1);
  const std::string path = Write(testing::TempDir() + "/be.ply", bytes);
  const Mesh mesh = ReadMesh(path);
  ASSERT_EQ(mesh.num_vertices(), 4);
  EXPECT_EQ(mesh.positions.row(3), Eigen::RowVector3d(0, 1, 0.5));
  EXPECT_EQ(mesh.faces.row(1), Eigen::RowVector3i(0, 2, 3));
  // One byte short: the edge element ends early.
  const std::string short_path =
      Write(testing::TempDir() + "/be_short.ply", bytes.substr(0, bytes.size() - 1));
  EXPECT_NE(ReadError(short_path).find("ends early in element 'edge'"),
            std::string::npos)
      << ReadError(short_path);
}

TEST(MeshReaderTest, BinaryPlyIntegerCoordinatesOfEverySize) {
  // Little-endian coordinates as (u)char, (u)short and (u)int: the signed
  // types two's complement, the unsigned ones as they are.
  struct Case {
    const char* types[3];
    long long vertices[3][3];
  };
  const Case cases[] = {
      {{"char", "short", "int"},
       {{-1, -300, -70000},
        {127, 32767, 2147483647},
        {-128, -32768, -2147483647 - 1}}},
      {{"uchar", "ushort", "uint"},
       {{255, 65535, 4294967295}, {0, 0, 0}, {128, 32768, 2147483648}}},
  };
  for (const Case& c : cases) {
    std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n";
    const char* axes[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      bytes += std::string("property ") + c.types[k] + " " + axes[k] + "\n";
    }
    bytes +=
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const int sizes[3] = {1, 2, 4};
    for (const auto& v : c.vertices) {
      for (int k = 0; k < 3; ++k) {
        for (int i = 0; i < sizes[k]; ++i) {
          bytes += static_cast<char>((static_cast<unsigned long long>(v[k]) >>
                                      (8 * i)) & 0xff);
        }
      }
    }
    bytes += '\x03';
    for (int index = 0; index < 3; ++index) {
      bytes += std::string(1, static_cast<char>(index)) + std::string(3, '\0');
    }
    const Mesh mesh = ReadMesh(
        Write(testing::TempDir() + "/" + c.types[0] + ".ply", bytes));
    ASSERT_EQ(mesh.num_vertices(), 3) << c.types[0];
    for (int v = 0; v < 3; ++v) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(mesh.positions(v, k),
                  static_cast<double>(c.vertices[v][k]))
            << c.types[k] << " at vertex " << v;
      }
    }
  }
}

TEST(MeshReaderTest, ObjVariants) {
  const std::string dir = testing::TempDir();
  // v/vt/vn face tokens, negative indices, comments, ignored statements.
  const std::string path = Write(
      dir + "/variants.obj",
      "# c\nmtllib a.mtl\no square\nv 0 0 0\nv 1 0 0 1\nv 1 1 0\n"
      "v 0 1 0 0.5 0.5 0.5\nvt 0 0\nvn 0 0 1\ns off\n"
      "f 1/1/1 2/1/1 3/1/1\nf -4//1 -2//1 -1//1\n");
  const Mesh mesh = ReadMesh(path);
  ASSERT_EQ(mesh.num_faces(), 2);
  EXPECT_EQ(mesh.faces.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_NE(ReadError(Write(dir + "/zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"))
                .find("face 0 has vertex index 0"),
            std::string::npos);
  EXPECT_NE(ReadError(Write(dir + "/line.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n"))
                .find("unsupported OBJ statement 'l' (a mesh has only v and f "
                      "lines) (line 3)"),
            std::string::npos);
}

TEST(MeshReaderTest, BinaryContentIsEchoedEscapedAndShort) {
  const std::string dir = testing::TempDir();
  std::string junk = "ply\nformat ascii 1.0\n";
  junk += std::string("\x01\x02\xff\x00", 4) + std::string(200, 'A') + "\n";
  const std::string message = ReadError(Write(dir + "/junk.ply", junk));
  EXPECT_NE(message.find("unknown PLY header line '\\x01\\x02\\xff\\x00AAAA"),
            std::string::npos)
      << message;
  EXPECT_LT(message.size(), 150u) << message;
  for (char c : message) {
    EXPECT_TRUE(c >= 0x20 && c < 0x7f) << static_cast<int>(c);
  }
  const std::string not_off = ReadError(Write(dir + "/x.off", std::string("\x7f\x45LF\x02", 5)));
  EXPECT_NE(not_off.find("not an OFF file (no OFF header, first line '\\x7fELF\\x02')"),
            std::string::npos)
      << not_off;
}

TEST(MeshReaderTest, DirectoryIsNotAMesh) {
  const std::string dir = testing::TempDir();
  std::filesystem::create_directory(dir + "/d.ply");
  EXPECT_EQ(ReadError(dir + "/d.ply"),
            dir + "/d.ply: is a directory, not a mesh file");
}

// Mask reader: each defect names the file (and the line of a bad entry).
TEST(MeshReaderTest, MaskDefects) {
  const std::string dir = testing::TempDir();
  std::filesystem::create_directory(dir + "/mask_dir");
  struct Case {
    std::string path, expected;
  };
  const Case cases[] = {
      {dir + "/mask_dir", dir + "/mask_dir: is a directory, not a mask file"},
      {dir + "/missing.txt", "cannot open mask file " + dir + "/missing.txt"},
      {Write(dir + "/binary.txt", std::string("0\n\x00\x01\xfe", 5)),
       dir + "/binary.txt: not a text file (it contains NUL bytes)"},
      {Write(dir + "/high.txt", "0\n1 \xff\xfe\n"),
       dir + "/high.txt:2: not a vertex index: '\\xff\\xfe'"},
      {Write(dir + "/float.txt", "0\n# fine\n1 2.5\n"),
       dir + "/float.txt:3: not a vertex index: '2.5'"},
      {Write(dir + "/range.txt", "0\n3\n4\n"),
       dir + "/range.txt:3: vertex index '4' out of range for a mesh with 4 "
             "vertices"},
      {Write(dir + "/negative.txt", "-1\n"),
       dir + "/negative.txt:1: vertex index '-1' out of range for a mesh "
             "with 4 vertices"},
      {Write(dir + "/huge.txt", "999999999999999999999999999999\n"),
       dir + "/huge.txt:1: not a vertex index: '999999999999999999999999"
             "...'"},
  };
  for (const Case& c : cases) {
    try {
      ReadMask(c.path, 4);
      ADD_FAILURE() << c.path << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), c.expected);
    }
  }
  EXPECT_EQ(ReadMask(Write(dir + "/ok.txt", "3 1\n# c\n1\r\n0 # x\n"), 4),
            (std::vector<int>{0, 1, 3}));
}

}  // namespace
}  // namespace shellspace
