// The CLI on every defective mesh of tests/io/bad_mesh_files.h (written
// here), through `energy` and through the verbs that solve: one line on
// stderr naming the file, a non-zero exit, no file created, no file changed
// (testing::ExpectRejected: the tree's names, sizes, modification times and
// content hashes before and after).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/io/bad_mesh_files.h"
#include "tests/testing/cli_output.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::ExpectRejected;

TEST(BadInputCliTest, EveryBadMeshIsRejectedWithOneLine) {
  const std::string dir = testing::TempDir();
  int runs = 0;
  for (const testing::BadMeshFile& file : testing::WriteBadMeshFiles(dir)) {
    ExpectRejected("energy --reference " + file.path + " --deformed " +
                       file.path,
                   file.path, dir);
    ++runs;
  }
  // The isolated vertex (which used to abort the solvers with a CHECK) in
  // every format through the verbs that solve.
  std::ofstream(dir + "/mask.txt") << "0\n1\n";
  for (const testing::BadMeshFile& file :
       testing::WriteBadMeshFiles(dir, "isolated_vertex")) {
    const std::string& path = file.path;
    ExpectRejected("geodesic --quiet --steps 2 --start " + path + " --end " +
                       path + " --output " + dir + "/out",
                   path, dir);
    ExpectRejected("mean --quiet --inputs " + path + "," + path +
                       " --output " + dir + "/mean.ply",
                   path, dir);
    ExpectRejected("shoot --quiet --steps 2 --first " + path + " --second " +
                       path + " --output " + dir + "/out",
                   path, dir);
    ExpectRejected("deform --quiet --reference " + path + " --mask " + dir +
                       "/mask.txt --targets " + path + " --output " + dir +
                       "/deformed.ply",
                   path, dir);
    runs += 4;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  // 70 energy runs on the table's files, 16 solver runs (geodesic, mean,
  // shoot, deform on the isolated vertex in 4 formats).
  EXPECT_EQ(runs, 86);
}

}  // namespace
}  // namespace shellspace
