// StagedDirectory: a directory appears whole on Commit, is replaced whole,
// never replaces a directory of other files, and leaves nothing behind
// when destroyed without Commit.
#include "shellspace/io/output_directory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/atomic_file.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::DirectoryListing;

void Touch(const std::string& path, const std::string& text = "x\n") {
  std::ofstream(path) << text;
}

TEST(OutputDirectoryTest, AppearsOnCommitOnly) {
  const std::string base = testing::TempDir();
  const std::string dir = base + "/out";
  {
    StagedDirectory staged(dir);
    Touch(staged.File("shape_000.ply"));
    EXPECT_FALSE(std::filesystem::exists(dir));
    // The staging directory is a hidden sibling, never named like a frame.
    const std::string name =
        std::filesystem::path(staged.staging()).filename().string();
    EXPECT_EQ(name.rfind(".out.tmp-", 0), 0u) << name;
    EXPECT_TRUE(IsTemporaryName(name));
    staged.Commit();
  }
  EXPECT_EQ(DirectoryListing(base), std::vector<std::string>{"out"});
  EXPECT_EQ(DirectoryListing(dir), std::vector<std::string>{"shape_000.ply"});
  {
    StagedDirectory abandoned(dir);
    Touch(abandoned.File("shape_001.ply"));
  }  // no Commit: the staging directory is removed, the output kept
  EXPECT_EQ(DirectoryListing(base), std::vector<std::string>{"out"});
  EXPECT_EQ(DirectoryListing(dir), std::vector<std::string>{"shape_000.ply"});
}

TEST(OutputDirectoryTest, ReplacesWholeAndTheLastCommitWins) {
  const std::string base = testing::TempDir();
  const std::string dir = base + "/out";
  StagedDirectory first(dir), second(dir);
  Touch(first.File("shape_000.ply"));
  Touch(first.File("shape_001.ply"));
  Touch(second.File("summary.json"));
  first.Commit();
  second.Commit();
  EXPECT_EQ(DirectoryListing(dir), std::vector<std::string>{"summary.json"});
  EXPECT_EQ(DirectoryListing(base), std::vector<std::string>{"out"});
}

TEST(OutputDirectoryTest, NeverReplacesOtherFiles) {
  const std::string base = testing::TempDir();
  const std::string dir = base + "/out";
  std::filesystem::create_directory(dir);
  Touch(dir + "/shape_000.ply");
  StagedDirectory staged(dir);
  Touch(staged.File("shape_000.ply"));
  // The user adds a file of their own while the run computes.
  Touch(dir + "/notes.txt");
  EXPECT_THROW(staged.Commit(), InputError);
  EXPECT_EQ(DirectoryListing(dir),
            (std::vector<std::string>{"notes.txt", "shape_000.ply"}));
  EXPECT_THROW(StagedDirectory again(dir), InputError);
  EXPECT_NE(ReplaceableDirectoryProblem(dir).find("holds notes.txt"),
            std::string::npos);
  Touch(base + "/file");
  EXPECT_NE(ReplaceableDirectoryProblem(base + "/file").find("not a directory"),
            std::string::npos);
  EXPECT_EQ(ReplaceableDirectoryProblem(base + "/missing"), "");
}

// Which names a directory may hold and still be replaced: the files a run
// writes (frames, modes, the example sets) and the temporaries of a run;
// a name that only resembles one is the user's.
TEST(OutputDirectoryTest, KnowsTheNamesARunWrites) {
  const std::string base = testing::TempDir();
  int n = 0;
  auto problem_with = [&](const std::string& name) {
    const std::string dir = base + "/d" + std::to_string(n++);
    std::filesystem::create_directory(dir);
    Touch(dir + "/" + name);
    return ReplaceableDirectoryProblem(dir);
  };
  for (const char* name :
       {"shape_000.ply", "shape_12.ply", "summary.json", "mode_2_plus.ply",
        "procrustes_mode_10_minus.ply", "finger.ply", "finger1.ply",
        "plate12_var.ply", "pose_var.ply", "collection_mask.txt", "viewer.html",
        ".out.tmp-12-345-0", "shape_000.ply.tmp-7-0"}) {
    EXPECT_EQ(problem_with(name), "") << name;
  }
  for (const char* name : {"shape_.ply", "shape_1.plyx", "shape_1a.ply",
                           "mode_a_plus.ply", "mode_1_both.ply", "finger_x.ply",
                           "fingers.ply", "summary.json2", "notes.txt"}) {
    EXPECT_NE(problem_with(name).find(std::string("holds ") + name),
              std::string::npos)
        << name;
  }
}

// Leftovers of ended runs beside an output are removed, by their tag
// "<pid>-<start>-<n>" or "<pid>-<n>"; this process's, and names whose tag
// is not one, stay.
TEST(OutputDirectoryTest, RemovesOnlyTheLeftoversOfEndedRuns) {
  const std::string base = testing::TempDir() + "/leftovers";
  std::filesystem::create_directory(base);
  // No process has a pid this large (the kernel's limit is 2^22).
  const std::string ended = "999999999";
  const std::vector<std::string> removed = {
      ".out.tmp-" + ended + "-12345-0", ".out.tmp-" + ended + "-3",
      "out.tmp-" + ended + "-12345-1", ".out.old-" + ended + "-12345-2"};
  const std::vector<std::string> kept = {".out.tmp-" + ProcessTag() + "-0",
                                         ".out.tmp-" + ended + "-x-0",
                                         ".out.tmp-1234567890123456789-0",
                                         ".out.tmp-" + ended + "-1-2-3",
                                         ".out.tmp-" + ended,
                                         ".other.tmp-" + ended + "-0"};
  for (const std::string& name : removed) Touch(base + "/" + name);
  for (const std::string& name : kept) Touch(base + "/" + name);
  EXPECT_EQ(RemoveLeftoversOfEndedRuns(base + "/out", true),
            static_cast<int>(removed.size()));
  std::vector<std::string> expected = kept;
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(DirectoryListing(base), expected);
}

// Every spelling names the path that is renamed: the parent resolved
// physically (a symbolic link's "..", the link's target's parent), the last
// name kept unless it is "." or "..".
TEST(OutputDirectoryTest, NormalOutputPathResolvesTheParent) {
  const std::string base =
      std::filesystem::canonical(testing::TempDir()).string();
  std::filesystem::create_directories(base + "/sub/deep");
  std::filesystem::create_directory_symlink(base + "/sub/deep", base + "/link");
  std::filesystem::create_directory(base + "/out");
  const struct {
    std::string spelling, path;
  } cases[] = {
      {base + "/out", base + "/out"},
      {base + "/out/", base + "/out"},
      {base + "//out//", base + "/out"},
      {base + "/./out", base + "/out"},
      {base + "/out/.", base + "/out"},
      {base + "/out/../out", base + "/out"},
      {base + "/sub/../out/", base + "/out"},
      {base + "/link/../../out", base + "/out"},  // link/.. is sub
      {base + "/link/x.glb", base + "/sub/deep/x.glb"},
      {base + "/link", base + "/link"},  // the link itself, not followed
      {base + "/link/..", base + "/sub"},
      {base + "/out/..", base},
      {base + "/missing/../x", base + "/x"},  // lexical: no parent to resolve
  };
  for (const auto& c : cases) {
    EXPECT_EQ(NormalOutputPath(c.spelling), c.path) << c.spelling;
  }
  const std::string here = std::filesystem::current_path().string();
  EXPECT_EQ(NormalOutputPath("x.ply"),
            std::filesystem::canonical(here).string() + "/x.ply");
}

TEST(OutputDirectoryTest, TemporaryNames) {
  EXPECT_TRUE(IsTemporaryName(".g.tmp-12-0"));
  EXPECT_TRUE(IsTemporaryName(".g.old-12-3"));
  EXPECT_TRUE(IsTemporaryName("shape_000.ply.tmp-12-0"));
  EXPECT_FALSE(IsTemporaryName("shape_000.ply"));
  EXPECT_FALSE(IsTemporaryName("summary.json"));
  EXPECT_EQ(WithoutTrailingSlash("a/b//"), "a/b");
  EXPECT_EQ(WithoutTrailingSlash("/"), "/");
}

}  // namespace
}  // namespace shellspace
