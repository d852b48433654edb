// A SIGTERM during a long read (a 105 MB OBJ written here) ends it with the
// stop line and exit 143. The run is a child with a timeout
// (testing::RunCliWithTimeout), so a regression fails instead of hanging.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::CliRun;
using testing::RunCliWithTimeout;

// SIGTERM while a 105 MB OBJ (3 million vertices, about 2.5 s to read on 2
// cores) is read: the read ends at its next poll with the stop line and
// exit 143 (a read that ignored the signal would end "mesh has no faces",
// exit 1).
TEST(ReaderCliTest, SigtermEndsALongRead) {
  const std::string dir = testing::TempDir();
  const std::string path = dir + "/long.obj";
  {
    std::ofstream out(path);
    const std::string line = "v 0.123456789 1.23456789 2.3456789\n";
    std::string block;
    for (int i = 0; i < 10000; ++i) block += line;
    for (int i = 0; i < 300; ++i) out << block;
  }
  const CliRun run =
      RunCliWithTimeout("energy --reference " + path + " --deformed " + path,
                        60, /*signal_after=*/0.3);
  std::filesystem::remove(path);
  EXPECT_EQ(run.code, 143) << run.err;
  EXPECT_EQ(run.err, "shellspace energy: stopped (SIGTERM) while reading " +
                         path + "\n");
  // Had the read not stopped, it would have ended "mesh has no faces".
  std::cout << "SIGTERM at 0.3 s, run ended after " << run.seconds << " s\n";
}

}  // namespace
}  // namespace shellspace
