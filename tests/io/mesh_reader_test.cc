// The mesh and mask readers: every defect of the table in
// tests/io/bad_mesh_files.h, in every format it applies to, is one InputError
// line naming the file and the element; valid files of every format read
// back exactly.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "shellspace/geometry/validation.h"
#include "shellspace/io/mesh_io.h"
#include "tests/io/bad_mesh_files.h"
#include "tests/testing/test_support.h"

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

// The OFF header variants [ST][C][N][4]OFF: the unit square with each
// variant's extra vertex columns (normals, colours with and without alpha,
// texture coordinates) and face colours reads as the plain square; 4OFF's
// homogeneous coordinates are divided by w.
TEST(MeshReaderTest, OffHeaderVariantsReadTheSquare) {
  const std::string dir = testing::TempDir();
  const char* xyz[4] = {"0 0 0", "1 0 0", "1 1 0", "0 1 0"};
  struct Case {
    const char* keyword;
    const char* vertex_suffix;  // appended to every vertex line
    const char* face_suffix;    // appended to every face line
  };
  const Case cases[] = {
      {"OFF", "", ""},
      {"OFF", "", " 255 0 0"},
      {"OFF", "", " 0.5 0.5 0.5 1"},
      {"COFF", " 192 192 192 255", ""},
      {"COFF", " 0.2 0.4 0.6", " 1 0 0"},
      {"NOFF", " 0 0 1", ""},
      {"CNOFF", " 0 0 -1 1 1 1 1", ""},
      {"CNOFF", " 0 0 -1 1 1 1", " 0 0 0 0"},
      {"STOFF", " 0.25 0.75", ""},
      {"STCOFF", " 10 20 30 0.25 0.75", ""},
      {"STNOFF", " 0 0 1 0.25 0.75", ""},
      {"STCNOFF", " 0 0 1 10 20 30 40 0.25 0.75", ""},
      {"4OFF", " 1", ""},
      {"C4OFF", " 1 255 255 255", ""},
  };
  int read = 0;
  for (const Case& c : cases) {
    std::string text = std::string(c.keyword) + "\n# a comment\n4 2 0\n";
    for (const char* v : xyz) text += std::string(v) + c.vertex_suffix + "\n";
    text += std::string("3 0 1 2") + c.face_suffix + "\n3 0 2 3" +
            c.face_suffix + "\n";
    const std::string path =
        Write(dir + "/" + c.keyword + std::to_string(read) + ".off", text);
    SCOPED_TRACE(text);
    const Mesh mesh = ReadMesh(path);
    ASSERT_EQ(mesh.num_vertices(), 4);
    ASSERT_EQ(mesh.num_faces(), 2);
    EXPECT_EQ(mesh.positions.row(2), Eigen::RowVector3d(1, 1, 0));
    EXPECT_EQ(mesh.faces.row(1), Eigen::RowVector3i(0, 2, 3));
    ++read;
  }
  EXPECT_EQ(read, 14);
  // 4OFF: x y z w is (x/w, y/w, z/w).
  const Mesh halved = ReadMesh(
      Write(dir + "/w2.off", "4OFF 3 1 0\n0 0 0 2\n1 0 0 2\n0 4 1 2\n3 0 1 2\n"));
  EXPECT_EQ(halved.positions.row(1), Eigen::RowVector3d(0.5, 0, 0));
  EXPECT_EQ(halved.positions.row(2), Eigen::RowVector3d(0, 2, 0.5));
}

TEST(MeshReaderTest, OffVariantDefectsAreOneLine) {
  const std::string dir = testing::TempDir();
  // The square in an OFF variant with `suffix` after every vertex's x y z.
  const auto off = [](const std::string& keyword, const std::string& suffix) {
    std::string text = keyword + "\n4 2 0\n";
    for (const char* v : {"0 0 0", "1 0 0", "1 1 0", "0 1 0"}) {
      text += v + suffix + "\n";
    }
    return text + "3 0 1 2\n3 0 2 3\n";
  };
  struct Case {
    std::string text, expected;
  };
  const Case cases[] = {
      {off("COFF", ""),
       "vertex 0 has 3 values, expected 6 or 7 (COFF) (line 3)"},
      {off("NOFF", " 0 0 1 1"),
       "vertex 0 has 7 values, expected 6 (NOFF) (line 3)"},
      {off("OFF", " 192 192 192"),
       "vertex 0 has 6 values, expected 3 (line 3)"},
      {off("CNOFF", " 0 0 1 r g b"),
       "vertex 0 has a malformed number 'r' (line 3)"},
      {off("4OFF", " 0"),
       "vertex 0 has the homogeneous coordinate w = '0' (a point at "
       "infinity) (line 3)"},
      {"nOFF\n3\n4 2 0\n",
       "cannot read nOFF: OFF with a declared vertex dimension is not read (a "
       "shell's vertices are 3-D: write OFF) (line 1)"},
      {"CnOFF 3 4 2 0\n",
       "cannot read CnOFF: OFF with a declared vertex dimension is not read (a "
       "shell's vertices are 3-D: write OFF) (line 1)"},
      {"OFF BINARY\n",
       "cannot read OFF BINARY: binary OFF is not read (write ASCII OFF or "
       "binary PLY) (line 1)"},
      {"CONF\n4 2 0\n",
       "cannot read: not an OFF file (no OFF header, first line 'CONF')"},
      {"NCOFF\n4 2 0\n",
       "cannot read: not an OFF file (no OFF header, first line 'NCOFF')"},
      {"OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 0.5\n3 0 2 3\n",
       "face 0 has 4 values after the count (expected 3 indices [and a "
       "colour]) (line 7)"},
      {"COFF\n4 2 0\n0 0 0 1 1 1\n1 0 0 1 1 1\n1 1 0 1 1 1\n0 1 0 1 1 1\n"
       "3 0 1 2 red 0 0\n3 0 2 3\n",
       "face 0 has a malformed colour 'red' (line 7)"},
  };
  int n = 0;
  for (const Case& c : cases) {
    const std::string path =
        Write(dir + "/defect" + std::to_string(n++) + ".off", c.text);
    EXPECT_EQ(ReadError(path, /*read_only=*/true), path + ": " + c.expected)
        << c.text;
  }
  EXPECT_EQ(n, 12);
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
      {dir + "/missing.txt", "cannot open mask file " + dir +
                                 "/missing.txt (No such file or directory)"},
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
