// OutputPaths, the output-path policy of every front end: an output that is
// an input under any spelling (.., a symbolic link, a hard link, a link to
// its directory), two outputs naming one file, a name too long for the file
// system once staged, an empty list item and a glTF output not named .glb
// are one InputError each, before any work, nothing created.
#include "shellspace/io/output_paths.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "shellspace/geometry/mesh.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

namespace fs = std::filesystem;

void Touch(const std::string& path) { std::ofstream(path) << "ply\n"; }

// The message of the InputError Check() throws, or "" if it passes.
std::string Problem(const OutputPaths& paths) {
  try {
    paths.Check();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

class OutputPathsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = testing::TempDir();
    fs::create_directory(base_ + "/sub");
    Touch(base_ + "/a.ply");
    Touch(base_ + "/b.ply");
    fs::create_hard_link(base_ + "/a.ply", base_ + "/hard.ply");
    fs::create_symlink(base_ + "/a.ply", base_ + "/soft.ply");
    fs::create_directory_symlink(base_, base_ + "/here");
  }
  std::string base_;
};

TEST_F(OutputPathsTest, AnOutputThatIsAnInputUnderAnySpellingIsRefused) {
  const std::string a = base_ + "/a.ply";
  for (const std::string& spelling :
       {a, base_ + "/./a.ply", base_ + "/sub/../a.ply", base_ + "/hard.ply",
        base_ + "/soft.ply", base_ + "/here/a.ply", base_ + "//a.ply",
        base_ + "/here/sub/../hard.ply"}) {
    OutputPaths paths;
    paths.InputList("inputs", base_ + "/b.ply," + a)
        .OutputFile("output", spelling);
    const std::string problem = Problem(paths);
    EXPECT_NE(problem.find("is also the input inputs"), std::string::npos)
        << spelling << ": " << problem;
  }
  // And the other way round: the input spelled through links.
  OutputPaths paths;
  paths.InputFile("start", base_ + "/hard.ply").OutputFile("gltf", a);
  EXPECT_NE(Problem(paths).find("is also the input start"), std::string::npos);
  // A different file passes, and nothing was created.
  OutputPaths fine;
  fine.InputFile("start", a).OutputFile("output", base_ + "/c.ply");
  EXPECT_EQ(Problem(fine), "");
  EXPECT_FALSE(fs::exists(base_ + "/c.ply"));
}

TEST_F(OutputPathsTest, TwoOutputsNamingOneFileAreRefused) {
  for (const std::string& second :
       {base_ + "/x.glb", base_ + "/sub/../x.glb", base_ + "/here/x.glb"}) {
    OutputPaths paths;
    paths.OutputFile("png", base_ + "/x.glb").OutputGlb("gltf", second);
    EXPECT_NE(Problem(paths).find("gltf and png are the same file"),
              std::string::npos)
        << second;
  }
  // An existing file and its hard link are one file.
  OutputPaths linked;
  linked.OutputFile("png", base_ + "/a.ply")
      .OutputFile("output", base_ + "/hard.ply");
  EXPECT_NE(Problem(linked).find("are the same file"), std::string::npos);
  // A file inside an output directory (replaced whole).
  OutputPaths inside;
  inside.OutputDirectory("output", base_ + "/out")
      .OutputFile("png", base_ + "/here/out/strip.png");
  EXPECT_NE(Problem(inside).find("is inside output"), std::string::npos);
}

TEST_F(OutputPathsTest, AnOutputDirectoryHoldingAnInputIsRefused) {
  fs::create_directory(base_ + "/out");
  Touch(base_ + "/out/shape_000.ply");
  OutputPaths paths;
  paths.InputFile("start", base_ + "/here/out/shape_000.ply")
      .OutputDirectory("output", base_ + "/out/");
  EXPECT_NE(Problem(paths).find("holds the input start"), std::string::npos)
      << Problem(paths);
}

TEST_F(OutputPathsTest, NamesTooLongOnceStagedAreRefusedBeforeAnyWork) {
  const long name_max = ::pathconf(base_.c_str(), _PC_NAME_MAX);
  ASSERT_GT(name_max, 40);
  // Fits NAME_MAX itself, but not with the temporary's suffix.
  const std::string name(static_cast<size_t>(name_max) - 8, 'n');
  OutputPaths file;
  file.OutputFile("output", base_ + "/" + name + ".npz");
  EXPECT_NE(Problem(file).find("the file system takes"), std::string::npos)
      << Problem(file);
  OutputPaths dir;
  dir.OutputDirectory("output", base_ + "/" + name);
  EXPECT_NE(Problem(dir).find("give a name of at most"), std::string::npos);
  EXPECT_FALSE(OutputNameLengthProblem("output", base_ + "/" + name).empty());
  EXPECT_EQ(OutputNameLengthProblem("output", base_ + "/short.npz"), "");
}

TEST_F(OutputPathsTest, EmptyListItemsAreRefused) {
  for (const std::string& list :
       {base_ + "/a.ply,", base_ + "/a.ply,," + base_ + "/b.ply",
        "," + base_ + "/a.ply", base_ + "/a.ply, ,b.ply"}) {
    OutputPaths paths;
    EXPECT_THROW(paths.InputList("inputs", list), InputError) << list;
  }
  try {
    OutputPaths().InputList("inputs", "a.ply,b.ply,");
    ADD_FAILURE() << "a trailing comma passed";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("trailing comma"),
              std::string::npos);
  }
}

// The message names the empty item's position and why it is empty; an
// item padded with white space that names no file ("a.ply, b.ply") is
// refused too, while a file whose name does end with a space is taken.
TEST_F(OutputPathsTest, ListItemsAreNamedByPosition) {
  const std::string a = base_ + "/a.ply", b = base_ + "/b.ply";
  const struct {
    std::string list, message;
  } cases[] = {
      {a + ", ," + b,
       "has an empty item: item 2 of 3 (only white space between commas)"},
      {a + ",\t," + b, "has an empty item: item 2 of 3 (only white space"},
      {a + ",," + b, "has an empty item: item 2 of 3 (two commas in a row)"},
      {"," + a, "has an empty item: item 1 of 2 (a leading comma)"},
      {a + "," + b + ",",
       "has an empty item: item 3 of 3 (a trailing comma)"},
      {a + ", " + b, "item 2 of 2, ' " + b +
                         "', begins or ends with white space and names no "
                         "file"},
      {a + " ," + b, "item 1 of 2, '" + a + " ', begins or ends"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.list);
    try {
      OutputPaths().InputList("inputs", c.list);
      ADD_FAILURE() << "passed";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(c.message), std::string::npos)
          << error.what();
    }
  }
  // The twins: the same items without the stray commas and spaces, and an
  // item whose file does end with a space.
  Touch(a + " ");
  EXPECT_NO_THROW(OutputPaths().InputList("inputs", a + "," + b));
  EXPECT_NO_THROW(OutputPaths().InputList("inputs", a + " ," + b));
}

TEST_F(OutputPathsTest, AGltfOutputMustBeNamedGlb) {
  for (const char* name : {"/x.gltf", "/x.GLTF", "/x.ply", "/x"}) {
    OutputPaths paths;
    paths.OutputGlb("gltf", base_ + name);
    EXPECT_NE(Problem(paths).find("binary glTF"), std::string::npos) << name;
  }
  OutputPaths fine;
  fine.OutputGlb("gltf", base_ + "/x.GLB");
  EXPECT_EQ(Problem(fine), "");
}

TEST_F(OutputPathsTest, CaseFoldingIsProbedNotAssumed) {
  // This file system (a Linux temporary directory) does not fold case:
  // OUT.npz and out.npz are two files; the probe leaves nothing behind.
  const auto before = testing::DirectoryListing(base_);
  EXPECT_FALSE(FoldsCase(base_));
  EXPECT_EQ(testing::DirectoryListing(base_), before);
  OutputPaths paths;
  paths.OutputFile("output", base_ + "/out.npz")
      .OutputFile("cache", base_ + "/OUT.npz");
  EXPECT_EQ(Problem(paths), "");
}

}  // namespace
}  // namespace shellspace
