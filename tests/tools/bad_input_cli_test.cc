// The CLI on every defective mesh of tests/io/bad_mesh_files.h (and on bad
// masks): one line on stderr naming the file, a non-zero exit, no file
// created, no file changed.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "shellspace/tests/io/bad_mesh_files.h"
#include "shellspace/tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::MeshFormat;

// Every file under `dir` (recursively) with its content.
std::map<std::string, std::string> Snapshot(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(dir)) {
    std::string content;
    if (entry.is_regular_file()) {
      std::ifstream in(entry.path(), std::ios::binary);
      std::ostringstream bytes;
      bytes << in.rdbuf();
      content = bytes.str();
    } else {
      content = "<dir>";
    }
    files[entry.path().string()] = content;
  }
  return files;
}

// Runs `args`; expects a non-zero exit, one stderr line containing `name`,
// and `dir` unchanged.
void ExpectRejected(const std::string& args, const std::string& name,
                    const std::string& dir) {
  SCOPED_TRACE(args);
  const auto before = Snapshot(dir);
  std::string err;
  const int code = testing::RunCli(args, nullptr, &err);
  EXPECT_NE(code, 0);
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find(name), std::string::npos) << err;
  EXPECT_EQ(Snapshot(dir), before) << "files created or changed";
}

TEST(BadInputCliTest, EveryBadMeshIsRejectedWithOneLine) {
  const std::string dir = testing::TempDir();
  int runs = 0;
  for (const testing::BadMeshCase& c : testing::BadMeshCases()) {
    for (MeshFormat format : c.formats) {
      const std::string path = testing::WriteBadMesh(dir, c, format);
      ExpectRejected("energy --reference " + path + " --deformed " + path,
                     path, dir);
      ++runs;
    }
  }
  // The isolated vertex (which used to abort the solvers with a CHECK) in
  // every format through the verbs that solve.
  std::ofstream(dir + "/mask.txt") << "0\n1\n";
  for (const testing::BadMeshCase& c : testing::BadMeshCases()) {
    if (c.name != "isolated_vertex") continue;
    for (MeshFormat format : c.formats) {
      const std::string path = testing::WriteBadMesh(dir, c, format);
      ExpectRejected("geodesic --quiet --steps 2 --start " + path + " --end " +
                         path + " --output " + dir + "/out",
                     path, dir);
      ExpectRejected("mean --quiet --inputs " + path + "," + path +
                         " --output " + dir + "/mean.ply",
                     path, dir);
      ExpectRejected("shoot --quiet --steps 2 --first " + path + " --second " +
                         path + " --output " + dir + "/out",
                     path, dir);
      ExpectRejected("deform --quiet --reference " + path + " --mask " +
                         dir + "/mask.txt --targets " + path + " --output " +
                         dir + "/deformed.ply",
                     path, dir);
      runs += 4;
    }
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  // 62 energy runs on the table's files, 16 solver runs (geodesic, mean,
  // shoot, deform on the isolated vertex in 4 formats).
  EXPECT_EQ(runs, 78);
}

TEST(BadInputCliTest, EveryBadMaskIsRejectedWithOneLine) {
  const std::string dir = testing::TempDir();
  const std::string square = testing::DataPath("simple/square4.ply");
  std::filesystem::create_directory(dir + "/mask_dir");
  const auto write = [&dir](const std::string& name, const std::string& bytes) {
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  };
  const std::string masks[] = {
      dir + "/mask_dir",
      write("binary.txt", std::string("0\n\x00\x01\xfe\x7f", 6)),
      write("high.txt", "0\n\xff\xfe\n"),
      write("float.txt", "0\n2.5\n"),
      write("range.txt", "0\n5\n"),
  };
  for (const std::string& mask : masks) {
    ExpectRejected("deform --reference " + square + " --mask " + mask +
                       " --targets " + square + " --output " + dir +
                       "/out.ply",
                   mask, dir);
  }
  // The error echoes no raw byte.
  std::string err;
  testing::RunCli("deform --reference " + square + " --mask " + masks[2] +
                      " --targets " + square + " --output " + dir + "/out.ply",
                  nullptr, &err);
  EXPECT_NE(err.find("high.txt:2: not a vertex index: '\\xff\\xfe'"),
            std::string::npos)
      << err;
  for (char c : err) EXPECT_TRUE(c == '\n' || (c >= 0x20 && c < 0x7f));
}

}  // namespace
}  // namespace shellspace
