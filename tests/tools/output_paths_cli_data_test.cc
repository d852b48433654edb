// Output paths, by class, each a table: every spelling of an existing
// output directory ("out/", "./out", "out/../out", a symbolic link to its
// parent, ...) is replaced whole or refused, never lost; two outputs naming
// one file, an output that is an input and an output inside --output are
// one line before any work, nothing created; what killed runs left beside
// an output (staging directories, file temporaries, directories renamed
// aside) is removed by the next run into the same place if, and only if,
// the process that left it has ended. Each class prints its cases tried
// and held. And a real killed run: SIGKILL while the frames of a 3000-step
// shot are written leaves its staging directory beside the output; the
// next run into the same place removes it.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "shellspace/io/atomic_file.h"
#include "tests/tools/cli_test_support.h"

namespace shellspace {
namespace {

using testing::RunCliIn;
using testing::Square4Geodesic;

namespace fs = std::filesystem;

int Lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

// Every path under `dir` with its size and content (files) or "<dir>",
// links by their target.
std::map<std::string, std::string> Tree(const std::string& dir) {
  std::map<std::string, std::string> tree;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const fs::path& path = entry.path();
    if (fs::is_symlink(fs::symlink_status(path))) {
      tree[path.string()] = "-> " + fs::read_symlink(path).string();
    } else if (fs::is_directory(path)) {
      tree[path.string()] = "<dir>";
    } else if (!fs::is_regular_file(path)) {
      tree[path.string()] = "<special>";  // a FIFO is not read
    } else {
      tree[path.string()] = Slurp(path.string());
    }
  }
  return tree;
}

void Report(const char* what, int tried, int held) {
  std::cout << what << ": " << tried << " tried, " << held << " held\n";
}

// A directory holding the result "out" of a K = 2 run, a directory "sub"
// and "link" -> the directory itself.
std::string ResultBase() {
  const std::string base = TempDir();
  fs::create_directory(base + "/sub");
  fs::create_directory_symlink(base, base + "/link");
  EXPECT_EQ(RunCli(Square4Geodesic(2, base + "/out")), 0);
  return base;
}

TEST(OutputPathsCliTest, EverySpellingOfAnExistingResultReplacesItWhole) {
  const std::string base = ResultBase();
  const std::vector<std::string> spellings = {
      "out",          "out/",          "out//",           "./out",
      "out/.",        "out/./",        "out/../out",      "out/../out/",
      "sub/../out",   "link/out",      "link/sub/../out", "link/./out/",
      base + "/out",  base + "//out/", base + "/sub/../out",
      base + "/link/out/../out"};
  int tried = 0, held = 0;
  for (size_t i = 0; i < spellings.size(); ++i) {
    SCOPED_TRACE(spellings[i]);
    const int steps = 3 + static_cast<int>(i % 3);  // a new listing each run
    std::string err;
    ++tried;
    const int code = RunCliIn(base, Square4Geodesic(steps, spellings[i]), &err);
    const std::string summary = Slurp(base + "/out/summary.json");
    const bool ok =
        code == 0 && DirectoryListing(base + "/out") == FramesAndSummary(steps + 1) &&
        summary.find("--steps " + std::to_string(steps)) != std::string::npos &&
        DirectoryListing(base) ==
            (std::vector<std::string>{"link", "out", "sub"});
    EXPECT_TRUE(ok) << "exit " << code << ": " << err;
    // A failing run (a missing mask, found after the checks) through the
    // same spelling keeps the result.
    ++tried;
    const auto before = Tree(base);
    const int failed = RunCliIn(
        base, Square4Geodesic(2, spellings[i]) + " --mask missing.txt", &err);
    const bool kept = failed == 1 && Lines(err) == 1 && Tree(base) == before;
    EXPECT_TRUE(kept) << "exit " << failed << ": " << err;
    held += ok + kept;
  }
  Report("output spellings", tried, held);
}

// Spellings that name something that is not a run's directory: refused in
// one line, the result and everything else untouched.
TEST(OutputPathsCliTest, SpellingsOfOtherDirectoriesAreRefused) {
  const std::string base = ResultBase();
  const struct {
    std::string spelling, message;
  } cases[] = {
      {".", "which no run writes: not replacing it"},
      {"out/..", "which no run writes: not replacing it"},
      {"sub/..", "which no run writes: not replacing it"},
      {"link", "is a symbolic link"},
      {"link/", "is a symbolic link"},
      {"missing/out", "does not exist"},
      {"out/summary.json", "is not a directory"},
  };
  int tried = 0, held = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.spelling);
    const auto before = Tree(base);
    std::string err;
    ++tried;
    const int code = RunCliIn(base, Square4Geodesic(3, c.spelling), &err);
    const bool ok = code == 1 && Lines(err) == 1 &&
                    err.find(c.message) != std::string::npos &&
                    Tree(base) == before;
    EXPECT_TRUE(ok) << "exit " << code << ": " << err;
    held += ok;
  }
  Report("refused output spellings", tried, held);
}

// Two outputs naming one file, an output that is an input, an output file
// inside --output: one line naming the flags, exit 1, before any input is
// read (a verb whose solve takes seconds answers at once), nothing created.
TEST(OutputPathsCliTest, CollidingOutputsAreRefusedBeforeAnyWork) {
  const std::string base = TempDir();
  fs::create_directory(base + "/sub");
  fs::copy_file(kSquare, base + "/a.ply");
  fs::copy_file(kBent, base + "/b.ply");
  fs::create_symlink(base + "/a.ply", base + "/alias.ply");
  ASSERT_EQ(RunCli(Square4Geodesic(2, base + "/path")), 0);
  ASSERT_EQ(mkfifo((base + "/fifo.png").c_str(), 0644), 0);
  const std::string ends = " --start a.ply --end b.ply --output out";
  const std::string shoot = "shoot --first a.ply --second b.ply --output out";
  const std::string transport =
      "transport --path path --variation b.ply --output out";
  const std::string spline =
      "spline --keyframes a.ply,b.ply --at 0,4 --steps 4 --output out";
  const std::string regress =
      "regress --inputs a.ply,b.ply --at 0,4 --steps 4 --output out";
  const std::string pca = "pca --inputs a.ply,b.ply --output out";
  const struct {
    std::string args, message;
  } cases[] = {
      // One file twice.
      {"geodesic --png x.glb --gltf x.glb" + ends,
       "--gltf and --png are the same file"},
      {"geodesic --png x.glb --gltf ./x.glb" + ends,
       "--gltf and --png are the same file"},
      {"geodesic --png sub/../x.glb --gltf x.glb" + ends,
       "--gltf and --png are the same file"},
      {"geodesic --png x.glb --gltf " + base + "/sub/../x.glb" + ends,
       "--gltf and --png are the same file"},
      {shoot + " --png x.glb --gltf x.glb", "--gltf and --png are the same file"},
      {transport + " --png x.glb --gltf x.glb",
       "--gltf and --png are the same file"},
      {spline + " --png x.glb --gltf x.glb", "--gltf and --png are the same file"},
      {regress + " --png x.glb --gltf x.glb",
       "--gltf and --png are the same file"},
      // An output inside --output (replaced as a whole).
      {"geodesic --gltf out/x.glb" + ends, "--gltf out/x.glb is inside --output"},
      {"geodesic --png out/../out/s.png" + ends, "is inside --output"},
      {"geodesic --gltf ./out/x.glb" + ends, "is inside --output"},
      {shoot + " --gltf out/x.glb", "is inside --output"},
      {transport + " --gltf out/x.glb", "is inside --output"},
      {spline + " --gltf out/x.glb", "is inside --output"},
      {regress + " --png out/s.png", "is inside --output"},
      {"demo --output out --gltf out/x.glb", "is inside --output"},
      {"demo --output out --gltf out/frames/x.glb", "is inside --output"},
      {pca + " --png out/s.png", "is inside --output"},
      // An output that is an input.
      {"geodesic --gltf a.ply" + ends, "is also the input --start"},
      {"geodesic --png ./sub/../b.ply" + ends, "is also the input --end"},
      {"geodesic --gltf alias.ply" + ends, "is also the input --start"},
      {shoot + " --png a.ply", "is also the input --first"},
      {spline + " --gltf " + base + "/b.ply", "is also the input --keyframes"},
      {pca + " --png ./a.ply", "is also the input --inputs"},
      // pca's --mean is an input too (a mean to start from).
      {"pca --inputs a.ply,alias.ply --mean b.ply --output out --png "
       "sub/../b.ply",
       "is also the input --mean"},
      {"pca --inputs a.ply,alias.ply --mean b.ply --output ./sub --html "
       "b.ply",
       "is also the input --mean"},
      {"log --start a.ply --end b.ply --output ./a.ply",
       "is also the input --start"},
      {"log --start a.ply --end b.ply --output sub/../b.ply",
       "is also the input --end"},
      {"export --input a.ply,b.ply --output ./b.ply", "is also the input --input"},
      {"export --input a.ply,b.ply --output alias.ply",
       "is also the input --input"},
      {"export --input path --output path/shape_001.ply",
       "is also the input --input"},
      {"render --input path --output ./path/../path/shape_000.ply",
       "is also the input --input"},
      {"mean --inputs a.ply,b.ply --output sub/../a.ply",
       "is also the input --inputs"},
      {"deform --reference a.ply --mask m.txt --targets b.ply --output alias.ply",
       "is also the input --reference"},
      // A container that does not match its name.
      {"geodesic --html page.png" + ends, "is an HTML page; name it .html"},
      {"geodesic --png strip.glb" + ends, "is a PNG image; name it .png"},
      {"render --input path --output strip.jpg", "name it .png"},
      {"view --input path --output page.png", "name it .html, .htm"},
      {"log --start a.ply --end b.ply --output l.stl",
       "is a mesh; name it .ply, .obj, .off"},
      {"mean --inputs a.ply,b.ply --output m.stl", "name it .ply, .obj, .off"},
      // An existing output that is no regular file.
      {"geodesic --png fifo.png" + ends, "is not a regular file"},
      // An output directory that holds an input.
      {"transport --path path --variation b.ply --output ./path/",
       "--output ./path/ holds the input --path"},
  };
  int tried = 0, held = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const auto before = Tree(base);
    std::string err;
    ++tried;
    const int code = RunCliIn(base, c.args, &err);
    const bool ok = code == 1 && Lines(err) == 1 &&
                    err.find(c.message) != std::string::npos &&
                    Tree(base) == before;
    EXPECT_TRUE(ok) << "exit " << code << ": " << err;
    held += ok;
  }
  Report("colliding outputs", tried, held);
}

// The pid of a process that has ended.
long EndedPid() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  int status = 0;
  waitpid(pid, &status, 0);
  return static_cast<long>(pid);
}

// The start time of this process as its temporaries carry it.
std::string OwnStart() {
  const std::string tag = ProcessTag();
  return tag.substr(tag.find('-') + 1);
}

// Leftovers beside an output: each a name and whether the next run into
// the output removes it (its owner has ended) or keeps it (its owner runs:
// this test process, as a concurrent run would). Directories renamed
// aside (.old-) go only once a new output is in place: a run that fails
// keeps them (they hold the previous result).
TEST(OutputPathsCliTest, LeftoversOfEndedRunsAreRemovedByTheNextRun) {
  const std::string ended = std::to_string(EndedPid());
  const std::string self = std::to_string(static_cast<long>(getpid()));
  const std::string start = OwnStart();
  ASSERT_NE(start, "0") << "no /proc/self/stat";
  const struct {
    std::string name;
    bool directory, removed_before_the_solve, removed_after_the_commit;
  } cases[] = {
      // Staging directories of killed runs (current and earlier names).
      {".out.tmp-" + ended + "-" + start + "-0", true, true, true},
      {".out.tmp-" + ended + "-0", true, true, true},
      // This pid with another start time: a reused pid, the owner ended.
      {".out.tmp-" + self + "-1-0", true, true, true},
      // A directory renamed aside by a run killed before its second rename:
      // the previous result, kept until a new one is in place.
      {".out.old-" + ended + "-" + start + "-3", true, false, true},
      {".out.old-" + ended + "-4", true, false, true},
      // File temporaries of --png / --gltf.
      {"s.png.tmp-" + ended + "-" + start + "-5", false, true, true},
      {"x.glb.tmp-" + ended + "-6", false, true, true},
      // Live owners (this process): never removed.
      {".out.tmp-" + self + "-" + start + "-7", true, false, false},
      {".out.tmp-" + self + "-8", true, false, false},
      {".out.old-" + self + "-" + start + "-9", true, false, false},
      {"s.png.tmp-" + self + "-" + start + "-10", false, false, false},
      // Not a temporary of these outputs: never touched.
      {".other.tmp-" + ended + "-" + start + "-0", true, false, false},
      {".out.tmp-x-0", true, false, false},
      {"notes.txt", false, false, false},
  };
  const std::string base = TempDir();
  const auto make = [&] {
    for (const auto& c : cases) {
      const std::string path = base + "/" + c.name;
      if (c.directory) {
        fs::create_directories(path + "/frames");
        std::ofstream(path + "/frames/shape_000.ply") << "a killed run's\n";
      } else {
        std::ofstream(path) << "a killed run's\n";
      }
    }
  };
  const auto present = [&](const std::string& name) {
    return fs::exists(fs::symlink_status(base + "/" + name));
  };
  const std::string run =
      Square4Geodesic(2, "out") + " --png s.png --gltf x.glb";
  int tried = 0, held = 0;
  // A run that fails after its checks (a missing mask): the staging and
  // file leftovers of ended runs are gone, the .old ones kept.
  make();
  std::string err;
  ASSERT_EQ(RunCliIn(base, run + " --mask missing.txt", &err), 1) << err;
  for (const auto& c : cases) {
    ++tried;
    const bool ok = present(c.name) != c.removed_before_the_solve;
    EXPECT_TRUE(ok) << c.name << " after a failed run";
    held += ok;
  }
  // A run that commits: every leftover of an ended run is gone.
  make();
  ASSERT_EQ(RunCliIn(base, run, &err), 0) << err;
  EXPECT_EQ(DirectoryListing(base + "/out"), FramesAndSummary(3));
  for (const auto& c : cases) {
    ++tried;
    const bool ok = present(c.name) != c.removed_after_the_commit;
    EXPECT_TRUE(ok) << c.name << " after a committed run";
    held += ok;
  }
  Report("leftovers", tried, held);
}

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
