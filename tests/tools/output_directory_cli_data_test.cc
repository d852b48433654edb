// Output directories hold exactly one run: a second run into a directory
// replaces it whole (no frame of the first run left), a directory of the
// user's own files is never replaced, two runs into one directory at once
// never mix, and no temporary is left beside or inside it.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "tests/tools/cli_test_support.h"

namespace shellspace {
namespace {

std::string Geodesic(int steps, const std::string& output) {
  return "geodesic --quiet --steps " + std::to_string(steps) + " --start " +
         kSquare + " --end " + kBent + " --output " + output;
}

TEST(OutputDirectoryCliTest, ASecondRunReplacesTheDirectoryWhole) {
  const std::string base = TempDir();
  const std::string dir = base + "/g";
  ASSERT_EQ(RunCli(Geodesic(4, dir)), 0);
  ASSERT_EQ(DirectoryListing(dir), FramesAndSummary(5));
  std::string err;
  ASSERT_EQ(RunCli(Geodesic(2, dir), nullptr, &err), 0) << err;
  // K = 2 over K = 4: shape_003, shape_004 of the first run are gone.
  EXPECT_EQ(DirectoryListing(dir), FramesAndSummary(3));
  const std::string summary = Slurp(dir + "/summary.json");
  EXPECT_NE(summary.find("--steps 2"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"frames\": 3"), std::string::npos) << summary;
  // Nothing beside it: no staging or old directory left.
  EXPECT_EQ(DirectoryListing(base), std::vector<std::string>{"g"});
  // A trailing slash names the same directory.
  ASSERT_EQ(RunCli(Geodesic(3, dir + "/"), nullptr, &err), 0) << err;
  EXPECT_EQ(DirectoryListing(dir), FramesAndSummary(4));
  EXPECT_EQ(DirectoryListing(base), std::vector<std::string>{"g"});
}

TEST(OutputDirectoryCliTest, ADirectoryOfOtherFilesIsNotReplaced) {
  const std::string base = TempDir();
  const std::string dir = base + "/mine";
  std::filesystem::create_directory(dir);
  std::ofstream(dir + "/notes.txt") << "mine\n";
  std::ofstream(dir + "/shape_000.ply") << "not a run's\n";
  std::string err;
  EXPECT_EQ(RunCli(Geodesic(2, dir), nullptr, &err), 1);
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find("holds notes.txt, which no run writes"), std::string::npos)
      << err;
  EXPECT_EQ(DirectoryListing(dir),
            (std::vector<std::string>{"notes.txt", "shape_000.ply"}));
  EXPECT_EQ(Slurp(dir + "/notes.txt"), "mine\n");
  EXPECT_EQ(DirectoryListing(base), std::vector<std::string>{"mine"});
  // An empty directory is filled.
  std::filesystem::create_directory(base + "/empty");
  ASSERT_EQ(RunCli(Geodesic(2, base + "/empty"), nullptr, &err), 0) << err;
  EXPECT_EQ(DirectoryListing(base + "/empty"), FramesAndSummary(3));
}

// Two runs (K = 2 and K = 4) into one directory at the same moment, 6
// times: the directory always holds one run whole (its frames match its
// summary.json), each run either succeeded or said that the other one won.
TEST(OutputDirectoryCliTest, ConcurrentRunsNeverMix) {
  const std::string base = TempDir();
  const std::string dir = base + "/g";
  const std::string cli = SHELLSPACE_CLI;
  int conflicts = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const std::string command = "(" + cli + " " + Geodesic(2, dir) + " 2> " +
                                base + "/e2; echo $? > " + base + "/c2) & (" +
                                cli + " " + Geodesic(4, dir) + " 2> " + base +
                                "/e4; echo $? > " + base + "/c4) & wait";
    ASSERT_EQ(std::system(("bash -c '" + command + "'").c_str()), 0);
    const std::vector<std::string> listing = DirectoryListing(dir);
    const std::string summary = Slurp(dir + "/summary.json");
    const bool two = summary.find("--steps 2") != std::string::npos;
    EXPECT_EQ(listing, FramesAndSummary(two ? 3 : 5)) << summary;
    for (const char* k : {"2", "4"}) {
      const int code = std::atoi(Slurp(base + "/c" + k).c_str());
      const std::string err = Slurp(base + "/e" + k);
      if (code != 0) {
        ++conflicts;
        EXPECT_EQ(code, 1) << err;
        EXPECT_NE(err.find("another run wrote"), std::string::npos) << err;
      }
    }
    // Only the directory and the captured outputs are left.
    EXPECT_EQ(DirectoryListing(base),
              (std::vector<std::string>{"c2", "c4", "e2", "e4", "g"}));
  }
  std::cout << "concurrent trials: 6, runs that lost the race with an "
               "error: "
            << conflicts << "\n";
}

TEST(OutputDirectoryCliTest, FrameReadersSkipTemporariesAndHiddenFiles) {
  const std::string base = TempDir();
  const std::string dir = base + "/g";
  ASSERT_EQ(RunCli(Geodesic(2, dir)), 0);
  // Leftovers of killed runs: an atomic-write temporary, a hidden file, a
  // staging directory.
  std::filesystem::copy_file(dir + "/shape_000.ply",
                             dir + "/shape_003.ply.tmp-1-0");
  std::filesystem::copy_file(dir + "/shape_000.ply", dir + "/.shape_004.ply");
  std::filesystem::create_directory(dir + "/.g.tmp-1-0");
  std::string out, err;
  ASSERT_EQ(RunCli("render --json --input " + dir + " --output " + base +
                       "/strip.png --width 20 --height 20",
                   &out, &err),
            0)
      << err;
  EXPECT_NE(out.find("\"frames\": 3"), std::string::npos) << out;
}

// An entry named like the next frame that is a directory or a FIFO is
// refused in one line, not skipped (the strip had 3 frames of 4 names,
// exit 0). The twin is the test above: hidden files and temporaries are
// skipped.
TEST(OutputDirectoryCliTest, AFrameThatIsNoRegularFileIsRefused) {
  const std::string base = TempDir();
  const std::string dir = base + "/g";
  ASSERT_EQ(RunCli(Geodesic(2, dir)), 0);
  for (const std::string kind : {"directory", "fifo"}) {
    const std::string odd = dir + "/shape_003.ply";
    if (kind == "directory") {
      std::filesystem::create_directory(odd);
    } else {
      ASSERT_EQ(mkfifo(odd.c_str(), 0644), 0);
    }
    for (const std::string& verb : {"render --output " + base + "/s.png",
                                   "export --output " + base + "/x.glb"}) {
      std::string out, err;
      EXPECT_EQ(RunCli(verb + " --input " + dir, &out, &err), 1)
          << kind << " " << verb;
      EXPECT_NE(err.find("shape_003.ply is named like a mesh but is not a "
                         "regular file"),
                std::string::npos)
          << err;
      EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
      EXPECT_FALSE(std::filesystem::exists(base + "/s.png"));
      EXPECT_FALSE(std::filesystem::exists(base + "/x.glb"));
    }
    std::filesystem::remove(odd);
  }
}

}  // namespace
}  // namespace shellspace
