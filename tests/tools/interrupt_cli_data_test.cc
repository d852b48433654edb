// Stopping a long run: SIGTERM or SIGINT once it iterates, or --time_limit,
// ends it with the best state so far written whole (complete frames,
// summary.json and --json with "partial": true and the reason), exit code
// 143 / 130 / 124, and no temporary left; a run the time limit does not
// stop reports the same numbers as one without it.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "tests/tools/cli_test_support.h"

namespace shellspace {
namespace {

const std::string kPlate = DataPath("plate/plate121.ply");
const std::string kRolled = DataPath("plate/plate121_rolledA.ply");

// A geodesic of about 10 LM iterations and a Newton finish (K = 8: a few
// seconds on 2 cores), or longer (K = 32: about 10 times that).
std::string LongGeodesic(int steps, const std::string& output) {
  return "geodesic --json --multires off --tolerance 1e-14 "
         "--max_iterations 100000 --steps " +
         std::to_string(steps) + " --start " + kPlate + " --end " + kRolled +
         " --output " + output;
}

// Starts `shellspace ARGS > out_path` with stderr on a pipe; once a stderr
// line contains `wait_for`, sends `signal_number` (0: none); returns the
// exit code (-1 if it did not exit normally) and the stderr text. Gives up
// (killing the child) after `timeout_seconds`.
// `shell_prefix` runs in the shell before the exec (e.g. "trap '' HUP;").
int RunAndSignal(const std::string& args, const std::string& out_path,
                 const std::string& wait_for, int signal_number,
                 double timeout_seconds, std::string* err,
                 double* signal_after = nullptr,
                 const std::string& shell_prefix = "") {
  int fds[2];
  if (pipe(fds) != 0) return -2;
  const std::string command = shell_prefix + " exec " + SHELLSPACE_CLI + " " +
                              args + " > " + out_path;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], 2);
    close(fds[0]);
    close(fds[1]);
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  bool sent = signal_number == 0;
  std::string buffer;
  char chunk[4096];
  while (true) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    if (elapsed > timeout_seconds) {
      kill(pid, SIGKILL);
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, 100) <= 0) continue;
    const ssize_t n = read(fds[0], chunk, sizeof(chunk));
    if (n <= 0) break;  // EOF: the child exited
    buffer.append(chunk, static_cast<size_t>(n));
    if (!sent && buffer.find(wait_for) != std::string::npos) {
      kill(pid, signal_number);
      sent = true;
      if (signal_after) *signal_after = elapsed;
    }
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  *err = buffer;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The stopped geodesic's directory: every frame complete, the ends the
// inputs, the reported E_K the frames' E_K, --json == summary.json.
void ExpectCompletePartialGeodesic(const std::string& dir,
                                   const std::string& json,
                                   const std::string& reason, int kSteps) {
  EXPECT_NE(json.find("\"partial\": true"), std::string::npos) << json;
  EXPECT_NE(json.find("\"stop_reason\": \"" + reason + "\""), std::string::npos)
      << json;
  EXPECT_NE(json.find("\"converged\": false"), std::string::npos) << json;
  EXPECT_EQ(Slurp(dir + "/summary.json"), json + "\n");
  ASSERT_EQ(DirectoryListing(dir), FramesAndSummary(kSteps + 1));
  const Mesh a = ReadMesh(kPlate), b = ReadMesh(kRolled);
  ShellPath path;
  for (int k = 0; k <= kSteps; ++k) {
    char name[32];
    std::snprintf(name, sizeof(name), "/shape_%03d.ply", k);
    const Mesh frame = ReadMesh(dir + name);
    ASSERT_EQ(frame.num_vertices(), a.num_vertices());
    path.push_back(frame.positions);
  }
  EXPECT_EQ(path.front(), a.positions);
  EXPECT_EQ(path.back(), b.positions);
  const double energy = Number(json, "path_energy");
  const ShellSpace space = testing::MakeSpace(a, testing::CliDefaultMaterial(a));
  EXPECT_NEAR(PathEnergy(space, path), energy, 1e-9 * energy);
  // At most the linear path's (the initial guess).
  EXPECT_LE(energy,
            PathEnergy(space, LinearPath(a.positions, b.positions, kSteps)));
}

TEST(InterruptCliTest, SigtermAfterTheFirstIterationWritesThePartialPath) {
  const std::string base = TempDir();
  const std::string dir = base + "/g";
  std::string err;
  double after = 0;
  const auto start = std::chrono::steady_clock::now();
  const int code = RunAndSignal(LongGeodesic(8, dir), base + "/out",
                                "geodesic iter   1", SIGTERM, 60, &err, &after);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  EXPECT_EQ(code, 143) << err;
  EXPECT_NE(err.find("stopped (SIGTERM): wrote the best state so far"),
            std::string::npos)
      << err;
  const std::string json = Slurp(base + "/out");
  ExpectCompletePartialGeodesic(dir, json.substr(0, json.find('\n')), "SIGTERM",
                                8);
  EXPECT_EQ(DirectoryListing(base), (std::vector<std::string>{"g", "out"}));
  std::cout << "SIGTERM sent " << after << " s after the start, run ended "
            << seconds << " s after the start\n";
}

// SIGHUP (the terminal closed) is handled as SIGTERM: the partial path
// written whole, exit 129 = 128 + SIGHUP; under `nohup` (SIGHUP ignored by
// the starting shell) it stays ignored and the run ends normally.
TEST(InterruptCliTest, SighupWritesThePartialPathUnlessIgnored) {
  const struct {
    std::string prefix;
    int code;
  } cases[] = {{"", 129}, {"trap '' HUP;", 0}};
  int tried = 0, held = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.prefix);
    const std::string base = TempDir();
    const std::string dir = base + "/g";
    std::string err;
    ++tried;
    const int code = RunAndSignal(LongGeodesic(8, dir), base + "/out",
                                  "geodesic iter   1", SIGHUP, 120, &err,
                                  nullptr, c.prefix);
    EXPECT_EQ(code, c.code) << err;
    const std::string out = Slurp(base + "/out");
    const std::string json = out.substr(0, out.find('\n'));
    if (c.code == 129) {
      EXPECT_NE(err.find("stopped (SIGHUP): wrote the best state so far"),
                std::string::npos)
          << err;
      ExpectCompletePartialGeodesic(dir, json, "SIGHUP", 8);
    } else {
      EXPECT_NE(json.find("\"partial\": false"), std::string::npos) << json;
      EXPECT_TRUE(Bool(json, "converged")) << json;
      EXPECT_EQ(DirectoryListing(dir), FramesAndSummary(9));
    }
    EXPECT_EQ(DirectoryListing(base), (std::vector<std::string>{"g", "out"}));
    const bool stopped = json.find("\"partial\": true") != std::string::npos;
    held += code == c.code && stopped == (c.code == 129) &&
            Slurp(dir + "/summary.json") == json + "\n";
  }
  std::cout << "SIGHUP: " << tried << " tried, " << held << " held\n";
}

TEST(InterruptCliTest, SigintStopsAShotAfterCompleteSteps) {
  const std::string base = TempDir();
  const std::string dir = base + "/shot";
  // The first step of a plate -> rolled plate geodesic, extrapolated by
  // 2000 EXP steps (minutes); SIGINT once step 5 is done.
  ASSERT_EQ(testing::RunCli("geodesic --quiet --multires off --steps 4 "
                            "--start " +
                            kPlate + " --end " + kRolled + " --output " + base +
                            "/g"),
            0);
  std::string err;
  const int code =
      RunAndSignal("shoot --json --steps 2000 --first " + base +
                       "/g/shape_000.ply --second " + base +
                       "/g/shape_001.ply --output " + dir,
                   base + "/out", "shoot step 5 of 2000", SIGINT, 60, &err);
  EXPECT_EQ(code, 130) << err;
  const std::string json = Slurp(base + "/out");
  EXPECT_NE(json.find("\"partial\": true"), std::string::npos) << json;
  EXPECT_NE(json.find("\"stop_reason\": \"SIGINT\""), std::string::npos)
      << json;
  // The steps done were solved, but the shot did not reach step K.
  EXPECT_NE(json.find("\"converged\": false"), std::string::npos) << json;
  const int frames = static_cast<int>(Number(json, "frames"));
  EXPECT_GE(frames, 6);  // s_0, s_1 and at least steps 2..5
  EXPECT_LT(frames, 2001);
  EXPECT_EQ(Slurp(dir + "/summary.json"), json);
  EXPECT_EQ(DirectoryListing(dir), FramesAndSummary(frames));
  for (int k = 0; k < frames; ++k) {
    char name[32];
    std::snprintf(name, sizeof(name), "/shape_%03d.ply", k);
    EXPECT_EQ(ReadMesh(dir + name).num_vertices(), 121);
  }
  EXPECT_EQ(DirectoryListing(base),
            (std::vector<std::string>{"g", "out", "shot"}));
}

// The spline through cactus 2, 10, 17 (K = 8), SIGTERM as its LΘA frames
// start (seconds of LM each): the run stops before F_K is ever evaluated and
// writes its start, the LΘA path, whole: "evaluated": false, null energies,
// the keyframes exact, exit 143 with the reason in one line.
TEST(InterruptCliTest, ASplineStoppedBeforeItsFirstEvaluationWritesItsStart) {
  const std::string base = TempDir();
  const std::string dir = base + "/spline";
  const std::string cactus = DataPath("cactus/cactus");
  std::string err;
  const int code = RunAndSignal(
      "spline --json --steps 8 --at 0,4,8 --keyframes " + cactus + "2.ply," +
          cactus + "10.ply," + cactus + "17.ply --output " + dir,
      base + "/out", "spline: LTheta spline\n", SIGTERM, 120, &err);
  EXPECT_EQ(code, 143) << err;
  EXPECT_NE(err.find("not converged: spline: stopped before the first "
                     "evaluation of F_K finished"),
            std::string::npos)
      << err;
  const std::string json = Slurp(base + "/out");
  EXPECT_NE(json.find("\"evaluated\": false"), std::string::npos) << json;
  EXPECT_NE(json.find("\"spline_energy\": null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"stop_reason\": \"SIGTERM\""), std::string::npos)
      << json;
  EXPECT_EQ(Slurp(dir + "/summary.json"), json);
  ASSERT_EQ(DirectoryListing(dir), FramesAndSummary(9));
  EXPECT_EQ(ReadMesh(dir + "/shape_004.ply").positions,
            ReadMesh(cactus + "10.ply").positions);
  EXPECT_EQ(ReadMesh(dir + "/shape_008.ply").positions,
            ReadMesh(cactus + "17.ply").positions);
}

TEST(InterruptCliTest, AStoppedTransportIsNotCalledSolved) {
  // Transport of the rolled plate along a 200-step shot; SIGINT once rung 3
  // is done: the rungs done are solved, the transport is not. The material
  // is the thick plate of relative eta 0.01: at the default 1e-4 the
  // 200-step shot has no EXP solution far out (an unsolved step, exit 4).
  const std::string base = TempDir();
  ASSERT_EQ(testing::RunCli("geodesic --quiet --multires off --steps 4 "
                            "--relative_eta 0.01 --start " +
                            kPlate + " --end " + kRolled + " --output " + base +
                            "/g"),
            0);
  ASSERT_EQ(testing::RunCli("shoot --quiet --steps 200 --relative_eta 0.01 "
                            "--first " + base +
                            "/g/shape_000.ply --second " + base +
                            "/g/shape_001.ply --output " + base + "/shot"),
            0);
  std::string err;
  const int code = RunAndSignal(
      "transport --json --relative_eta 0.01 --path " + base +
          "/shot --variation " +
          DataPath("plate/plate121_rolledB.ply") + " --output " + base +
          "/moved",
      base + "/out", "rung 3 of 200", SIGINT, 120, &err);
  EXPECT_EQ(code, 130) << err;
  const std::string json = Slurp(base + "/out");
  EXPECT_NE(json.find("\"partial\": true"), std::string::npos) << json;
  EXPECT_NE(json.find("\"converged\": false"), std::string::npos) << json;
  const int frames = static_cast<int>(Number(json, "frames"));
  EXPECT_GE(frames, 4);  // p_0 and at least rungs 1..3
  EXPECT_LT(frames, 201);
}

TEST(InterruptCliTest, AStopAfterThePcaMeanWritesTheMeanAlone) {
  // Three faces (7,118 vertices): the mean takes seconds, each LOG of the
  // displacements much longer; SIGINT once the mean is done.
  const std::string base = TempDir();
  const std::string faces = DataPath("faces");
  std::string err;
  const int code = RunAndSignal(
      "pca --json --modes 1 --inputs " + faces + "/neutral.ply," + faces +
          "/smile.ply," + faces + "/disgust.ply --output " + base + "/pca",
      base + "/out", "pca: elastic mean done", SIGINT, 300, &err);
  EXPECT_EQ(code, 130) << err;
  const std::string json = Slurp(base + "/out");
  EXPECT_NE(json.find("\"partial\": true"), std::string::npos) << json;
  EXPECT_NE(json.find("\"stopped_in\": \"displacements\""),
            std::string::npos)
      << json;
  EXPECT_EQ(Number(json, "modes"), 0) << json;
  EXPECT_EQ(DirectoryListing(base + "/pca"),
            (std::vector<std::string>{"mean.ply", "pca.json", "summary.json"}));
  EXPECT_EQ(ReadMesh(base + "/pca/mean.ply").num_vertices(), 7118);
}

TEST(InterruptCliTest, TimeLimitStopsTheGeodesic) {
  const std::string base = TempDir();
  const std::string dir = base + "/g";
  std::string err;
  const int code = RunAndSignal(LongGeodesic(32, dir) + " --time_limit 1",
                                base + "/out", "", 0, 60, &err);
  EXPECT_EQ(code, 124) << err;
  // One line says the stop and what had not converged by then.
  const std::string stopped =
      "shellspace geodesic: stopped (time limit 1 s): wrote the best state so "
      "far, marked partial; not converged: ";
  const size_t line = err.find(stopped);
  ASSERT_NE(line, std::string::npos) << err;
  EXPECT_NE(err.find("above the target", line), std::string::npos) << err;
  EXPECT_EQ(err.find("not converged"), line + stopped.find("not converged"))
      << err;
  const std::string json = Slurp(base + "/out");
  ExpectCompletePartialGeodesic(dir, json.substr(0, json.find('\n')),
                                "time limit 1 s", 32);
}

TEST(InterruptCliTest, ATimeLimitThatIsNotReachedChangesNoNumber) {
  const std::string base = TempDir();
  const std::string common =
      "geodesic --quiet --json --multires off --steps 4 --start " + kPlate +
      " --end " + kRolled;
  std::string with, without, err;
  ASSERT_EQ(
      testing::RunCli(common + " --output " + base + "/a", &without, &err), 0)
      << err;
  ASSERT_EQ(
      testing::RunCli(common + " --time_limit 1000 --output " + base + "/b",
                      &with, &err),
      0)
      << err;
  EXPECT_NE(with.find("\"partial\": false"), std::string::npos) << with;
  for (const char* key :
       {"path_energy", "iterations", "final_gradient_norm", "newton_steps"}) {
    EXPECT_EQ(Number(with, key), Number(without, key)) << key;
  }
  for (int k = 0; k <= 4; ++k) {
    char name[32];
    std::snprintf(name, sizeof(name), "/shape_%03d.ply", k);
    EXPECT_EQ(Slurp(base + "/a" + name), Slurp(base + "/b" + name)) << name;
  }
}

// SIGKILL (no handler can run) during the solve of a run into a directory
// that holds an earlier run: the earlier run is untouched, nothing is left
// beside it. A second SIGTERM kills at once, with the same result.
TEST(InterruptCliTest, AKilledRunLeavesThePreviousOutputUntouched) {
  const std::string base = TempDir();
  const std::string dir = base + "/g";
  ASSERT_EQ(testing::RunCli("geodesic --quiet --steps 2 --start " + kPlate +
                            " --end " + kRolled + " --output " + dir),
            0);
  const std::vector<std::string> listing = DirectoryListing(dir);
  std::vector<std::string> contents;
  for (const std::string& name : listing)
    contents.push_back(Slurp(dir + "/" + name));
  std::string err;
  const int code = RunAndSignal(LongGeodesic(8, dir), base + "/out",
                                "geodesic iter   1", SIGKILL, 60, &err);
  EXPECT_EQ(code, -1) << err;  // killed, no exit status
  EXPECT_EQ(DirectoryListing(dir), listing);
  for (size_t i = 0; i < listing.size(); ++i) {
    EXPECT_EQ(Slurp(dir + "/" + listing[i]), contents[i]) << listing[i];
  }
  EXPECT_EQ(DirectoryListing(base), (std::vector<std::string>{"g", "out"}));
}

}  // namespace
}  // namespace shellspace
