// The limits of a run, by class, each a table: --time_limit values (any
// finite value >= 0 runs, one beyond the clock's range is no limit, not an
// immediate stop; NaN, infinite, negative and non-numbers are one line),
// --steps of every verb that takes it bounded before any work (the range,
// then the memory estimate: one line and exit 1, never std::bad_alloc), and
// flags given twice refused in one line naming the flag (flag files and
// the environment are not taken at all). Each class prints its
// cases tried and held.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "tests/tools/cli_test_support.h"

namespace shellspace {
namespace {

int Lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

void Report(const char* what, int tried, int held) {
  std::cout << what << ": " << tried << " tried, " << held << " held\n";
}

std::string SmallGeodesic(const std::string& output) {
  return "geodesic --json --quiet --steps 2 --start " + kSquare + " --end " +
         kBent + " --output " + output;
}

TEST(RunLimitsCliTest, TimeLimitValues) {
  const std::string base = TempDir();
  const struct {
    std::string value;
    bool valid;
  } cases[] = {
      {"0", true},          {"-0", true},       {"1000", true},
      {"4.6e9", true},      {"9.2e9", true},    {"9.3e9", true},
      {"1e10", true},       {"1e18", true},     {"1e300", true},
      {"1.7976931348623157e308", true},
      {"nan", false},       {"NaN", false},     {"-nan", false},
      {"inf", false},       {"-inf", false},    {"1e309", false},
      {"-1", false},        {"-1e-300", false}, {"-1e10", false},
      {"ten", false},       {"", false},
  };
  int tried = 0, held = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE("--time_limit '" + c.value + "'");
    std::string out, err;
    ++tried;
    const int code = RunCli(SmallGeodesic(base + "/g") + " --time_limit '" +
                                c.value + "'",
                            &out, &err);
    bool ok;
    if (c.valid) {
      // Run to the end: not stopped, converged, exit 0.
      ok = code == 0 && out.find("\"partial\": false") != std::string::npos &&
           out.find("\"stop_reason\": \"\"") != std::string::npos &&
           Bool(out, "converged");
    } else {
      ok = code == 1 && Lines(err) == 1 &&
           err.find("time_limit") != std::string::npos && out.empty();
    }
    EXPECT_TRUE(ok) << "exit " << code << "\n" << out << err;
    held += ok;
  }
  Report("time_limit values", tried, held);
}

// --steps per verb: out of range, or within range but above the memory
// estimate of machines with up to 280 GB (shoot on the faces: 142 GB; the
// others 240 GB to terabytes): one line naming --steps, exit 1, within
// seconds, nothing written.
TEST(RunLimitsCliTest, StepsAreBoundedBeforeAnyWorkInEveryVerb) {
  const std::string base = TempDir();
  const std::string faces = DataPath("faces/neutral.ply");
  const std::string out = " --output " + base + "/out";
  const auto geodesic = [&](const std::string& verb, const std::string& k) {
    return verb + " --steps " + k + " --start " + kSquare + " --end " + kBent +
           (verb == "log" ? " --output " + base + "/log.ply" : out);
  };
  const auto spline = [&](const std::string& k) {
    return "spline --steps " + k + " --at 0," + k + " --keyframes " + kSquare +
           "," + kBent + out;
  };
  const auto regress = [&](const std::string& k) {
    return "regress --steps " + k + " --at 0," + k + " --inputs " + kSquare +
           "," + kBent + out;
  };
  const auto shoot = [&](const std::string& first, const std::string& k) {
    return "shoot --steps " + k + " --first " + first + " --second " + first +
           out;
  };
  // The memory refusal names the flag and its value.
  const auto memory = [](const std::string& k) {
    return "--steps " + k + " on";
  };
  const struct {
    std::string args, message;
  } cases[] = {
      // Above the memory estimate (the estimates of geometry/memory_limits.h).
      {geodesic("geodesic", "100000"), memory("100000")},
      {geodesic("geodesic", "20000"), memory("20000")},
      {geodesic("log", "100000"), memory("100000")},
      {spline("100000"), memory("100000")},
      {regress("100000"), memory("100000")},
      {spline("99999"), memory("99999")},
      {regress("99999"), memory("99999")},
      {shoot(faces, "100000"), memory("100000")},
      {"demo --steps 100000" + out, memory("100000")},
      {"demo --steps 30000" + out, memory("30000")},
      // Out of range.
      {geodesic("geodesic", "100001"),
       "--steps must be an integer in [1, 100000], got 100001"},
      {geodesic("geodesic", "0"), "--steps must be"},
      {geodesic("log", "-3"), "--steps must be"},
      {spline("1"), "--steps must be an integer in [2, 100000], got 1"},
      {spline("2147483647"), "--steps must be"},
      {regress("100001"), "--steps must be"},
      {shoot(kSquare, "100001"), "--steps must be"},
      {shoot(kSquare, "2.5"), "for int32 flag 'steps'"},
      {shoot(kSquare, "2147483648"), "for int32 flag 'steps'"},
      {"demo --steps 1" + out, "--steps must be"},
      {"demo --steps 100001" + out, "--steps must be"},
      {"demo --extrapolate 100001" + out,
       "--extrapolate must be an integer in [0, 100000]"},
      {"demo --extrapolate -1" + out, "--extrapolate must be"},
  };
  int tried = 0, held = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    std::string err;
    ++tried;
    const auto start = std::chrono::steady_clock::now();
    const int code = RunCli(c.args, nullptr, &err);
    const double seconds = std::chrono::duration<double>(
                               std::chrono::steady_clock::now() - start)
                               .count();
    const bool in_range = c.message.find(" on") != std::string::npos;
    const bool ok = code == 1 && Lines(err) == 1 &&
                    err.find(c.message) != std::string::npos &&
                    (!in_range || err.find("needs about") != std::string::npos) &&
                    seconds < 20 && DirectoryListing(base).empty();
    EXPECT_TRUE(ok) << "exit " << code << " after " << seconds << " s: "
                    << err;
    held += ok;
  }
  Report("steps bounds", tried, held);
}

// The pixels of a film strip (render --width/--height, --png of the verbs
// that write frames) against the memory bound before anything is
// allocated: one line naming the size and "needs about", exit 1, nothing
// written, at once -- never std::bad_alloc (exit 3) after the solve. 600
// frames at 49152 x 8192 (100 rows of six 8192-pixel frames) need about
// 250 GB; 100001 frames of the default 320-pixel columns about 66 GB (a
// machine of less than twice that refuses them).
TEST(RunLimitsCliTest, FilmStripSizesAreBoundedBeforeAnyWork) {
  const std::string base = TempDir();
  std::string many;
  for (int k = 0; k < 600; ++k) many += (k ? "," : "") + kSquare;
  const std::string render = "render --input " + many + " --output " + base +
                             "/strip.png";
  const std::string out = " --output " + base + "/out --png " + base +
                          "/strip.png";
  const struct {
    std::string args, message;
  } cases[] = {
      {render + " --width 49152 --height 8192",
       "--width 49152 --height 8192: a film strip of 600 frame(s)"},
      {render + " --width 65536 --height 8192",
       "frame width at most 8192 pixels, got 10922"},
      {render + " --width 49152", "needs about"},
      {render + " --width 12288 --height 8192", "needs about"},
      {"shoot --steps 100000 --first " + kSquare + " --second " + kBent + out,
       "--png: a film strip of 100001 frame(s)"},
      {"shoot --steps 60000 --first " + kSquare + " --second " + kBent + out +
           " --labels=false --color displacement",
       "--png: a film strip of 60001 frame(s)"},
      // The path's own bound or the strip's, whichever this machine's
      // memory meets first.
      {"demo --steps 2 --extrapolate 100000 --output " + base + "/demo",
       "needs about"},
      // Not a memory question: a frame wider than 8192 pixels, one line too.
      {"render --input " + kSquare + " --output " + base +
           "/strip.png --width 49152 --height 8192",
       "frame width at most 8192 pixels, got 49152"},
  };
  int tried = 0, held = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    std::string err;
    ++tried;
    const auto start = std::chrono::steady_clock::now();
    const int code = RunCli(c.args, nullptr, &err);
    const double seconds = std::chrono::duration<double>(
                               std::chrono::steady_clock::now() - start)
                               .count();
    const bool ok = code == 1 && Lines(err) == 1 &&
                    err.find(c.message) != std::string::npos &&
                    err.find("bad_alloc") == std::string::npos &&
                    seconds < 20 && DirectoryListing(base).empty();
    EXPECT_TRUE(ok) << "exit " << code << " after " << seconds << " s: "
                    << err;
    held += ok;
  }
  Report("film strip bounds", tried, held);
  // The help states the bound.
  std::string help, help_err;
  RunCli("render --help", &help, &help_err);
  help += help_err;
  EXPECT_NE(help.find("at most 8192 per column; the strip's estimated "
                      "memory, 6 B x width x height + 128 B x frame width x "
                      "frame height, within half the physical memory"),
            std::string::npos)
      << help;
}

TEST(RunLimitsCliTest, AFlagGivenTwiceIsRefused) {
  const std::string base = TempDir();
  const std::string run = "geodesic --start " + kSquare + " --end " + kBent;
  const std::string run_out = run + " --output " + base + "/g";
  std::ofstream(base + "/steps4.flags") << "# two steps\n--steps=4\n";
  const std::string flags = base + "/steps4.flags";
  const struct {
    std::string args, message;
    int code;
  } cases[] = {
      {run_out + " --steps 4 --steps 8", "--steps is given twice (4, then 8)", 2},
      {run_out + " --steps=4 --steps 8", "--steps is given twice (4, then 8)", 2},
      {run_out + " -steps 4 --steps=8", "--steps is given twice (4, then 8)", 2},
      {run_out + " --steps 4 -steps=4", "--steps is given twice (4, then 4)", 2},
      {run_out + " --quiet --quiet", "--quiet is given twice (set, then set)", 2},
      {run_out + " --quiet --noquiet",
       "--quiet is given twice (set, then false)", 2},
      {run_out + " --json=false --json", "--json is given twice", 2},
      {run + " --output " + base + "/a --output " + base + "/b",
       "--output is given twice", 2},
      {run_out + " --mu 1 --mu=2", "--mu is given twice (1, then 2)", 2},
      {run_out + " --time_limit 5 --time_limit 0",
       "--time_limit is given twice", 2},
      {run_out + " --minloglevel 0 --minloglevel=3",
       "--minloglevel is given twice", 2},
      {run_out + " --steps 4 --steps 4 --steps 4",
       "--steps is given twice (4, then 4)", 2},
      // Values from elsewhere are not taken, so cannot repeat a flag.
      {run_out + " --flagfile " + flags, "--flagfile is not a flag of geodesic",
       2},
      {run_out + " --flagfile=" + flags + " --steps 8",
       "--flagfile is not a flag of geodesic", 2},
      {run_out + " --fromenv=steps", "--fromenv is not a flag of geodesic", 2},
      {run_out + " --tryfromenv=steps --steps 3",
       "--tryfromenv is not a flag of geodesic", 2},
      // A flag gflags does not know: its own one-line error.
      {run_out + " --bogus 1 --bogus 2", "unknown command line flag 'bogus'", 1},
  };
  setenv("FLAGS_steps", "4", 1);  // for --fromenv
  int tried = 0, held = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    std::string err;
    ++tried;
    const int code = RunCli(c.args, nullptr, &err);
    const bool ok = code == c.code && Lines(err) == 1 &&
                    err.find(c.message) != std::string::npos &&
                    DirectoryListing(base) ==
                        std::vector<std::string>{"steps4.flags"};
    EXPECT_TRUE(ok) << "exit " << code << ": " << err;
    held += ok;
  }
  unsetenv("FLAGS_steps");
  // Each flag once: runs, with the values given.
  const struct {
    std::string args;
    int frames;
  } accepted[] = {
      {run_out + " --json --steps 3", 4},
      {run_out + " --json --steps=2 --noquiet", 3},
      {run_out + " -json=true --quiet=false -steps 4", 5},
  };
  for (const auto& c : accepted) {
    SCOPED_TRACE(c.args);
    std::string out, err;
    ++tried;
    const int code = RunCli(c.args, &out, &err);
    const bool ok = code == 0 && Number(out, "frames") == c.frames &&
                    DirectoryListing(base + "/g") == FramesAndSummary(c.frames);
    EXPECT_TRUE(ok) << "exit " << code << ": " << err;
    held += ok;
  }
  Report("repeated flags", tried, held);
}

}  // namespace
}  // namespace shellspace
