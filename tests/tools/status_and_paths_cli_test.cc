// The CLI tells the truth and loses nothing, on procedural sheets: a report
// that cannot be written is a failed run (stdout to /dev/full, closed); a
// glTF export of values float32 cannot hold, or under a .gltf name, writes
// nothing; a frame folder with a gap or a broken link is one line; a
// trailing comma is refused; an output name too long once staged is refused
// before any solve; the collection verbs refuse an output that is an input
// (any spelling) and bad schedulers before starting Python; a capped
// branching simulation exits 4; a spline through constant keyframes is
// converged (exit 0).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/io/mesh_io.h"
#include "tests/testing/cli_output.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

namespace fs = std::filesystem;
using testing::RunCli;
using testing::Slurp;
using testing::TempDir;

// A flat and a bent equilateral sheet (one connectivity) in `dir`.
struct Sheets {
  std::string dir, flat, bent;
};

Sheets MakeSheets() {
  Sheets s;
  s.dir = TempDir();
  const Mesh flat = MakeEquilateralSheet(4, 3, 1.0);
  Mesh bent = flat;
  for (Eigen::Index v = 0; v < bent.positions.rows(); ++v) {
    const double x = bent.positions(v, 0);
    bent.positions(v, 2) = 0.1 * x * x;
  }
  s.flat = s.dir + "/flat.ply";
  s.bent = s.dir + "/bent.ply";
  WriteMesh(flat, s.flat);
  WriteMesh(bent, s.bent);
  return s;
}

// Runs `shellspace ARGS` through the shell with `redirect` (e.g. ">
// /dev/full"); exit code, stderr in `err`.
int RunShell(const std::string& args, const std::string& redirect,
             std::string* err) {
  const std::string log = TempDir() + "/err";
  const std::string command = std::string(SHELLSPACE_CLI) + " " + args + " " +
                              redirect + " 2> " + log;
  const int status = std::system(command.c_str());
  *err = Slurp(log);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int Lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

TEST(StatusAndPathsCliTest, AReportThatCannotBeWrittenIsAFailedRun) {
  const Sheets s = MakeSheets();
  const std::string energy =
      "energy --reference " + s.flat + " --deformed " + s.bent + " --json";
  const std::string compare =
      "compare --a " + s.flat + " --b " + s.flat + " --json";
  for (const std::string& args : {energy, compare}) {
    std::string err;
    EXPECT_EQ(RunShell(args, "> /dev/null", &err), 0) << args << err;
    for (const char* redirect : {"> /dev/full", ">&-"}) {
      const int code = RunShell(args, redirect, &err);
      EXPECT_NE(code, 0) << args << " " << redirect;
      EXPECT_EQ(Lines(err), 1) << args << " " << redirect << "\n" << err;
      EXPECT_NE(err.find("cannot write standard output"), std::string::npos)
          << err;
    }
  }
  // A geodesic's --json into /dev/full: its directory is written, the
  // exit says the report was lost.
  std::string err;
  EXPECT_EQ(RunShell("geodesic --quiet --json --steps 2 --start " + s.flat +
                         " --end " + s.bent + " --output " + s.dir + "/out",
                     "> /dev/full", &err),
            1)
      << err;
  EXPECT_EQ(Lines(err), 1) << err;
}

TEST(StatusAndPathsCliTest, GltfExportRefusesWhatFloat32CannotHold) {
  const Sheets s = MakeSheets();
  Mesh far = ReadMesh(s.bent);
  far.positions(0, 0) = 1e39;  // finite as double, inf as float32
  const std::string far_path = s.dir + "/far.ply";
  WriteMesh(far, far_path);
  std::string out, err;
  EXPECT_EQ(RunCli("export --input " + s.flat + "," + far_path + " --output " +
                       s.dir + "/x.glb",
                   &out, &err),
            1);
  EXPECT_NE(err.find("beyond float32"), std::string::npos) << err;
  EXPECT_EQ(Lines(err), 1) << err;
  EXPECT_FALSE(fs::exists(s.dir + "/x.glb"));
  // A delta between frames that overflows float32.
  Mesh near = ReadMesh(s.bent);
  near.positions(0, 0) = -3e38;
  Mesh other = near;
  other.positions(0, 0) = 3e38;
  WriteMesh(near, s.dir + "/n1.ply");
  WriteMesh(other, s.dir + "/n2.ply");
  EXPECT_EQ(RunCli("export --input " + s.dir + "/n1.ply," + s.dir +
                       "/n2.ply --output " + s.dir + "/y.glb",
                   &out, &err),
            1);
  EXPECT_NE(err.find("morph delta"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(s.dir + "/y.glb"));
  // A .gltf name (JSON glTF) for the binary file: refused before reading.
  for (const char* name : {"/z.gltf", "/z.GLTF", "/z.ply"}) {
    EXPECT_EQ(RunCli("export --input " + s.flat + "," + s.bent +
                         " --output " + s.dir + name,
                     &out, &err),
              1)
        << name;
    EXPECT_NE(err.find("binary glTF"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(s.dir + name));
  }
  EXPECT_EQ(RunCli("geodesic --quiet --steps 2 --start " + s.flat + " --end " +
                       s.bent + " --output " + s.dir + "/o --gltf " + s.dir +
                       "/p.gltf",
                   &out, &err),
            1);
  EXPECT_NE(err.find("binary glTF"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(s.dir + "/o"));
}

TEST(StatusAndPathsCliTest, FrameFoldersWithGapsOrBrokenLinksAreOneLine) {
  const Sheets s = MakeSheets();
  const std::string path = s.dir + "/path";
  ASSERT_EQ(RunCli("geodesic --quiet --steps 3 --start " + s.flat +
                   " --end " + s.bent + " --output " + path),
            0);
  std::string out, err;
  ASSERT_EQ(RunCli("export --input " + path + " --output " + s.dir + "/a.glb",
                   &out, &err),
            0)
      << err;
  fs::remove(path + "/shape_001.ply");
  EXPECT_EQ(RunCli("export --input " + path + " --output " + s.dir + "/b.glb",
                   &out, &err),
            1);
  EXPECT_NE(err.find("shape_001 is missing"), std::string::npos) << err;
  EXPECT_EQ(Lines(err), 1);
  EXPECT_FALSE(fs::exists(s.dir + "/b.glb"));
  fs::create_symlink(s.dir + "/gone.ply", path + "/shape_001.ply");
  EXPECT_EQ(RunCli("render --input " + path + " --output " + s.dir + "/c.png",
                   &out, &err),
            1);
  EXPECT_NE(err.find("broken symbolic link"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(s.dir + "/c.png"));
}

TEST(StatusAndPathsCliTest, EmptyListItemsAndLongNamesAreRefusedFirst) {
  const Sheets s = MakeSheets();
  std::string out, err;
  for (const std::string& list :
       {s.flat + "," + s.bent + ",", s.flat + ",," + s.bent}) {
    EXPECT_EQ(RunCli("mean --inputs " + list + " --output " + s.dir +
                         "/m.ply",
                     &out, &err),
              1)
        << list;
    EXPECT_NE(err.find("empty item"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(s.dir + "/m.ply"));
  }
  const std::string long_name(240, 'n');
  EXPECT_EQ(RunCli("geodesic --quiet --steps 2 --start " + s.flat + " --end " +
                       s.bent + " --output " + s.dir + "/" + long_name,
                   &out, &err),
            1);
  EXPECT_NE(err.find("give a name of at most"), std::string::npos) << err;
  EXPECT_EQ(testing::DirectoryListing(s.dir),
            (std::vector<std::string>{"bent.ply", "flat.ply"}));
}

TEST(StatusAndPathsCliTest, CollectionVerbsRefuseBeforeRunning) {
  const Sheets s = MakeSheets();
  fs::create_directory(s.dir + "/sub");
  fs::create_hard_link(s.flat, s.dir + "/hard.ply");
  const std::string before = Slurp(s.flat);
  const std::string inputs = " --inputs " + s.flat + "," + s.bent;
  const struct {
    std::string args, message;
  } cases[] = {
      {"mean" + inputs + " --output " + s.flat, "is also the input --inputs"},
      {"mean" + inputs + " --output " + s.dir + "/sub/../flat.ply",
       "is also the input --inputs"},
      {"mean" + inputs + " --output " + s.dir + "/hard.ply",
       "is also the input --inputs"},
      {"distances" + inputs + " --output " + s.dir + "/d.npz --cache " +
           s.dir + "/d.npz",
       "are the same file"},
      {"distances" + inputs + " --output " + s.dir + "/d.npz --cache " +
           s.bent,
       "--cache must end in .npz"},
      {"distances" + inputs + "," + " --output " + s.dir + "/d.npz",
       "empty item"},
      {"distances" + inputs + " --output " + s.dir + "/d.npz --scheduler "
       "local:100000",
       "local workers"},
      {"distances" + inputs + " --output " + s.dir + "/d.npz --scheduler "
       "local:-1",
       "worker count"},
      {"distances" + inputs + " --output " + s.dir + "/d.npz --scheduler "
       "localhost:99999",
       "PORT 1..65535"},
      {"distances" + inputs + " --output " + s.dir + "/d.npz --scheduler "
       "tcp://",
       "scheduler address"},
      {"pca" + inputs + " --output " + s.dir + "/p.NPZ", "must end in .npz"},
      {"distances" + inputs + " --output " + s.dir + "/" +
           std::string(240, 'd') + ".npz",
       "give a name of at most"},
  };
  for (const auto& c : cases) {
    std::string out, err;
    EXPECT_EQ(RunCli("collection " + c.args, &out, &err), 1) << c.args;
    EXPECT_EQ(Lines(err), 1) << c.args << "\n" << err;
    EXPECT_NE(err.find(c.message), std::string::npos) << c.args << "\n"
                                                      << err;
  }
  EXPECT_EQ(Slurp(s.flat), before);
  EXPECT_EQ(testing::DirectoryListing(s.dir),
            (std::vector<std::string>{"bent.ply", "flat.ply", "hard.ply",
                                      "sub"}));
}

// A scheduler keyword in another case is a mistyped keyword, not a host
// named LOCAL (which Python then failed to resolve); an empty or padded
// list item is named by its position. One line, exit 1, before Python
// starts, nothing written.
TEST(StatusAndPathsCliTest, MistypedSchedulersAndListItemsAreOneLine) {
  const Sheets s = MakeSheets();
  const std::string output = " --output " + s.dir + "/d.npz";
  const std::string inputs = " --inputs " + s.flat + "," + s.bent;
  const struct {
    std::string args, message;
  } cases[] = {
      {"distances" + inputs + output + " --scheduler LOCAL:2",
       "did you mean 'local:2'?"},
      {"distances" + inputs + output + " --scheduler Local",
       "did you mean 'local'?"},
      {"mean" + inputs + " --output " + s.dir + "/m.ply --scheduler NONE",
       "did you mean 'none'?"},
      {"pca" + inputs + " --output " + s.dir + "/p.npz --scheduler lOcAl:1",
       "did you mean 'local:1'?"},
      {"distances" + inputs + output + " --scheduler none:1",
       "none takes no count"},
      {"distances --inputs '" + s.flat + ", ," + s.bent + "'" + output,
       "has an empty item: item 2 of 3 (only white space between commas)"},
      {"distances --inputs '" + s.flat + ",," + s.bent + "'" + output,
       "has an empty item: item 2 of 3 (two commas in a row)"},
      {"distances --inputs '," + s.flat + "," + s.bent + "'" + output,
       "has an empty item: item 1 of 3 (a leading comma)"},
      {"distances --inputs '" + s.flat + ", " + s.bent + "'" + output,
       "begins or ends with white space and names no file"},
  };
  for (const auto& c : cases) {
    std::string out, err;
    EXPECT_EQ(RunCli("collection " + c.args, &out, &err), 1) << c.args;
    EXPECT_EQ(Lines(err), 1) << c.args << "\n" << err;
    EXPECT_NE(err.find(c.message), std::string::npos) << c.args << "\n"
                                                      << err;
    EXPECT_EQ(err.find("Traceback"), std::string::npos) << err;
  }
  // The same list items in a verb of its own.
  std::string out, err;
  EXPECT_EQ(RunCli("mean --inputs '" + s.flat + ", ," + s.bent +
                       "' --output " + s.dir + "/m.ply",
                   &out, &err),
            1);
  EXPECT_NE(err.find("has an empty item: item 2 of 3"), std::string::npos)
      << err;
  EXPECT_EQ(testing::DirectoryListing(s.dir),
            (std::vector<std::string>{"bent.ply", "flat.ply"}));
}

// The value of the first "key": true|false of `json` (the summary's own
// key comes before the nested ones of its stages and widths).
bool FirstBool(const std::string& json, const std::string& key) {
  const std::string needle = "\"" + key + "\": ";
  const size_t at = json.find(needle);
  return at != std::string::npos &&
         json.compare(at + needle.size(), 4, "true") == 0;
}

// The summary's converged is what the exit code says: a delta
// extrapolation with a width short of convergence (the fourth and fifth
// widths stop at 30 LM iterations, the simulation itself converges) is
// "converged": false and exit 4 -- it was true beside exit 4. Three widths,
// all converged: true and exit 0.
TEST(StatusAndPathsCliTest, BranchingExtrapolationConvergedIsTheExitCode) {
  for (const int widths : {5, 3}) {
    SCOPED_TRACE(widths);
    const std::string dir = TempDir() + "/br";
    std::string out, err;
    const int code = RunCli(
        "branching simulate --quiet --json --nx 8 --ny 32 --continuation 1 "
        "--lm_iterations 30 --delta_extrapolation " +
            std::to_string(widths) + " --output " + dir,
        &out, &err);
    const bool all = widths == 3;
    EXPECT_EQ(code, all ? 0 : 4) << err;
    EXPECT_EQ(FirstBool(out, "all_converged"), all) << out;
    EXPECT_EQ(FirstBool(out, "converged"), all) << out;
    EXPECT_EQ(FirstBool(Slurp(dir + "/summary.json"), "converged"), all);
    if (!all) {
      EXPECT_NE(err.find("delta extrapolation: not every width converged"),
                std::string::npos)
          << err;
    }
  }
}

TEST(StatusAndPathsCliTest, ACappedBranchingSimulationExitsFour) {
  const std::string dir = TempDir() + "/br";
  std::string out, err;
  const int code = RunCli("branching simulate --quiet --nx 16 --ny 32 "
                          "--lm_iterations 3 --output " + dir,
                          &out, &err);
  const std::string summary = Slurp(dir + "/summary.json");
  ASSERT_NE(summary.find("\"converged\""), std::string::npos) << err;
  if (summary.find("\"converged\": false") != std::string::npos ||
      summary.find("\"converged\":false") != std::string::npos) {
    EXPECT_EQ(code, 4) << err;
    EXPECT_NE(err.find("not converged"), std::string::npos) << err;
  } else {
    EXPECT_EQ(code, 0) << err;
  }
  EXPECT_NE(summary.find("NO_CONVERGENCE"), std::string::npos) << summary;
}

TEST(StatusAndPathsCliTest, ARegressionThroughConstantInputsConverges) {
  const Sheets s = MakeSheets();
  for (const char* verb : {"regress --inputs "}) {
    std::string out, err;
    EXPECT_EQ(RunCli(std::string(verb) + s.bent + "," + s.bent +
                         " --at 0,4 --steps 4 --quiet --output " + s.dir +
                         "/" + verb[0],
                     &out, &err),
              0)
        << verb << err;
  }
}

// Through one keyframe twice (the procedural finger): the LTheta start
// differs from the keyframe by round-off, where no criterion relative to
// |D_2 W| can be met; the midpoints of equal ends are their average, and
// the spline (zero energy) converges at once.
TEST(StatusAndPathsCliTest, ASplineThroughOneFingerTwiceConverges) {
  const std::string dir = TempDir();
  ASSERT_EQ(RunCli("example finger --output " + dir + "/f"), 0);
  const std::string f = dir + "/f/finger0.ply";
  for (const std::string& args :
       {"spline --keyframes " + f + "," + f + " --at 0,4 --steps 4",
        "regress --inputs " + f + "," + f + "," + f +
            " --at 0,2,4 --steps 4"}) {
    std::string out, err;
    const std::string output = dir + "/" + args.substr(0, 6);
    EXPECT_EQ(RunCli(args + " --quiet --output " + output, &out, &err), 0)
        << args << ": " << err;
    const std::string summary = Slurp(output + "/summary.json");
    EXPECT_NE(summary.find("\"converged\": true"), std::string::npos)
        << summary.substr(0, 300);
  }
}

}  // namespace
}  // namespace shellspace
