// A run killed while it writes: SIGKILL while the frames of a 3000-step
// shot are written leaves its staging directory beside the output; the
// next run into the same place removes it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "tests/tools/cli_test_support.h"

namespace shellspace {
namespace {

using testing::RunCliIn;
using testing::Square4Geodesic;

// A real killed run: SIGKILL while the frames of a 3000-step shot are
// written leaves its staging directory; the next run into the same place
// removes it.
TEST(OutputPathsCliTest, TheStagingOfARunKilledWhileWritingIsRemoved) {
  const std::string base = TempDir();
  const std::string shoot = "shoot --quiet --steps 3000 --first " + kSquare +
                            " --second " + kBent + " --output out";
  // Kill the run once its staging directory exists.
  const std::string command =
      "cd '" + base + "' && (" + SHELLSPACE_CLI + " " + shoot +
      " 2>/dev/null & pid=$!; for i in $(seq 1 600); do "
      "ls -a | grep -q '^\\.out\\.tmp-' && break; sleep 0.05; done; "
      "kill -9 $pid; wait $pid; true)";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::vector<std::string> left = DirectoryListing(base);
  const bool staged =
      left.size() == 1 && left[0].rfind(".out.tmp-", 0) == 0;
  if (!staged) {
    GTEST_SKIP() << "the run ended before it was killed while writing";
  }
  std::string err;
  ASSERT_EQ(RunCliIn(base, Square4Geodesic(2, "out"), &err), 0) << err;
  EXPECT_EQ(DirectoryListing(base), std::vector<std::string>{"out"});
  EXPECT_EQ(DirectoryListing(base + "/out"), FramesAndSummary(3));
}

}  // namespace
}  // namespace shellspace
