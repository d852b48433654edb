// `shellspace collection distances|mean|pca`: the fronts of the Python module
// shellspace.collections (many solves over a collection of shapes, in this
// process or on a Dask cluster; docs/collections.md). The flags are checked
// here like every verb's, then this process becomes `python3 -m
// shellspace.collections VERB ...` (exec: its progress, exit code and
// one-line errors are the run's), with this build's module first on
// PYTHONPATH (an installed module is on the interpreter's own path).
#include <gflags/gflags.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/io/ascii_lowercase.h"
#include "shellspace/io/scheduler_choice.h"
#include "tools/run/run_paths.h"
#include "tools/verbs/verb.h"

DECLARE_string(inputs);
DECLARE_string(output);
DECLARE_bool(quiet);
DECLARE_int32(steps);
DECLARE_double(tolerance);
DECLARE_int32(max_iterations);
DECLARE_double(time_limit);
DECLARE_int32(modes);
DECLARE_double(amplitude);
DECLARE_int32(log_steps);
DECLARE_int32(exp_steps);
DECLARE_int32(max_exp_steps);
DECLARE_double(mu);
DECLARE_double(lambda);
DECLARE_double(eta);
DECLARE_double(relative_eta);
DECLARE_string(bending);
DEFINE_string(scheduler, "none",
              "collection: none, local[:N] or a Dask scheduler's address");
DEFINE_double(pair_time_limit, 0, "collection distances: seconds per pair");
DEFINE_string(cache, "", "collection distances: the resumable cache");

#ifndef SHELLSPACE_PYTHON_EXECUTABLE
#define SHELLSPACE_PYTHON_EXECUTABLE "python3"
#endif
#ifndef SHELLSPACE_PYTHON_BUILD_DIR
#define SHELLSPACE_PYTHON_BUILD_DIR ""
#endif

namespace shellspace {
namespace {

// The --scheduler flag: io/scheduler_choice.h's values.
void CheckScheduler(const std::string& value) { ParseScheduler(value); }

FlagTable CommonFlags(const std::string& output) {
  return Flags({MaterialFlags(), {
      TextFlag("inputs", "comma-separated meshes of one connectivity (>= 2)")
          .Required(),
      TextFlag("output", output).Required(),
      TextFlag("scheduler",
               "none (in this process), local[:N] (a local cluster of N "
               "worker processes, one thread each; N = 2 by default) or the "
               "address of a running Dask scheduler (tcp://HOST:8786)")
          .Check(CheckScheduler),
      RealFlag("tolerance", "relative gradient tolerance of every solve", 0,
               End::kOpen),
      RealFlag("time_limit",
               "stop after this many seconds of wall clock (what is finished "
               "is written; exit 124); 0: no limit",
               0, End::kClosed),
      TextFlag("quiet", "no progress counter on stderr"),
  }});
}

FlagTable DistancesFlags() {
  FlagTable table = CommonFlags(
      "the matrix (.npz: distances, energies, status, seconds, messages)");
  table.push_back(IntegerFlag("steps", "K of every geodesic", 1, 4096)
                      .Default("4"));
  table.push_back(IntegerFlag("max_iterations", "per geodesic", 1));
  table.push_back(RealFlag("pair_time_limit",
                           "seconds per geodesic (a pair it stops is retried "
                           "on resume); 0: no limit",
                           0, End::kClosed));
  table.push_back(TextFlag(
      "cache", "the resumable cache (.npz); default OUTPUT.cache.npz"));
  return table;
}

FlagTable MeanFlags() {
  FlagTable table = CommonFlags("the elastic mean: PLY, OBJ or OFF");
  table.push_back(
      IntegerFlag("max_iterations", "Newton steps", 1).Default("100"));
  return table;
}

FlagTable PcaFlags() {
  FlagTable table = CommonFlags(
      "the model (.npz: mean, eigenvalues, modes, gram, displacements, "
      "mode shapes, statuses)");
  table.push_back(IntegerFlag("modes", "modes shot (at most inputs - 1)", 1));
  table.push_back(IntegerFlag("log_steps", "K of LOG_K", 1, 4096));
  table.push_back(IntegerFlag("exp_steps", "K of EXP_K", 1, 4096));
  table.push_back(
      IntegerFlag("max_exp_steps", "largest K of the EXP safeguard", 1, 4096));
  table.push_back(RealFlag("amplitude", "mode shapes at +-t sqrt(lambda)", 0,
                           End::kClosed));
  table.push_back(IntegerFlag("max_iterations", "per LOG and EXP solve", 1));
  return table;
}

std::string Number(double value) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

// The output's extension fits the verb: .npz, or a mesh for mean.
void CheckOutputName(const std::string& verb) {
  const std::string lower = AsciiLowercase(FLAGS_output);
  auto ends = [&](const std::string& tail) {
    return lower.size() > tail.size() &&
           lower.compare(lower.size() - tail.size(), tail.size(), tail) == 0;
  };
  if (verb == "mean") {
    if (!ends(".ply") && !ends(".obj") && !ends(".off")) {
      throw InputError("--output must end in .ply, .obj or .off");
    }
  } else if (!ends(".npz") || FLAGS_output.compare(FLAGS_output.size() - 4, 4,
                                                   ".npz") != 0) {
    throw InputError("--output must end in .npz");
  }
  if (verb == "distances" && !FLAGS_cache.empty() &&
      (FLAGS_cache.size() <= 4 ||
       FLAGS_cache.compare(FLAGS_cache.size() - 4, 4, ".npz") != 0)) {
    throw InputError("--cache must end in .npz");
  }
}

// What the interpreter runs: SIGINT and SIGTERM, blocked across the exec,
// get a one-line handler before they are unblocked (a stop during start-up
// is one line and 130 / 143, not a KeyboardInterrupt traceback or a death by
// the signal), then the module as `python3 -m shellspace.collections`,
// whose main installs the handlers that write partial results.
constexpr const char* kCollectionsBootstrap =
    "import os, signal, sys\n"
    "def stopped(number, frame):\n"
    "    name = 'SIGINT' if number == signal.SIGINT else 'SIGTERM'\n"
    "    sys.stderr.write('shellspace.collections: stopped (' + name +\n"
    "                     ') while starting: no output\\n')\n"
    "    sys.stderr.flush()\n"
    "    os._exit(130 if number == signal.SIGINT else 143)\n"
    "signal.signal(signal.SIGINT, stopped)\n"
    "signal.signal(signal.SIGTERM, stopped)\n"
    "signal.pthread_sigmask(signal.SIG_UNBLOCK,\n"
    "                       {signal.SIGINT, signal.SIGTERM})\n"
    "import runpy\n"
    "runpy.run_module('shellspace.collections', run_name='__main__',\n"
    "                 alter_sys=True)\n";

// Becomes python3 -m shellspace.collections VERB with the flags, once the
// paths passed the output policy (io/output_paths.h): nothing is solved
// for a run that could not write its output.
int RunCollection(const std::string& verb) {
  CheckOutputName(verb);
  RunPaths paths;
  paths.InputList("inputs", FLAGS_inputs).OutputFile("output", FLAGS_output);
  if (verb == "distances") {
    paths.OutputFile("cache",
                     FLAGS_cache.empty()
                         ? FLAGS_output.substr(0, FLAGS_output.size() - 4) +
                               ".cache.npz"
                         : FLAGS_cache);
  }
  paths.Check();
  std::vector<std::string> args = {
      SHELLSPACE_PYTHON_EXECUTABLE, "-c", kCollectionsBootstrap, verb,
      "--inputs", FLAGS_inputs, "--output", FLAGS_output, "--scheduler",
      FLAGS_scheduler, "--tolerance", Number(FLAGS_tolerance),
      "--max_iterations", std::to_string(FLAGS_max_iterations)};
  if (FLAGS_time_limit > 0) {
    args.insert(args.end(), {"--time_limit", Number(FLAGS_time_limit)});
  }
  if (FLAGS_quiet) args.push_back("--quiet");
  args.insert(args.end(), {"--mu", Number(FLAGS_mu), "--lambda",
                           Number(FLAGS_lambda), "--bending", FLAGS_bending});
  gflags::CommandLineFlagInfo eta, relative_eta;
  gflags::GetCommandLineFlagInfo("eta", &eta);
  gflags::GetCommandLineFlagInfo("relative_eta", &relative_eta);
  if (!eta.is_default && !relative_eta.is_default) {
    throw InputError("--eta and --relative_eta: give one, not both");
  }
  if (!eta.is_default) args.insert(args.end(), {"--eta", Number(FLAGS_eta)});
  if (!relative_eta.is_default) {
    args.insert(args.end(), {"--relative_eta", Number(FLAGS_relative_eta)});
  }
  if (verb == "distances") {
    args.insert(args.end(), {"--steps", std::to_string(FLAGS_steps)});
    if (FLAGS_pair_time_limit > 0) {
      args.insert(args.end(),
                  {"--pair_time_limit", Number(FLAGS_pair_time_limit)});
    }
    if (!FLAGS_cache.empty()) args.insert(args.end(), {"--cache", FLAGS_cache});
  } else if (verb == "pca") {
    args.insert(args.end(),
                {"--modes", std::to_string(FLAGS_modes), "--log_steps",
                 std::to_string(FLAGS_log_steps), "--exp_steps",
                 std::to_string(FLAGS_exp_steps), "--max_exp_steps",
                 std::to_string(FLAGS_max_exp_steps), "--amplitude",
                 Number(FLAGS_amplitude)});
  }
  // This build's module first (if it is there: an installed binary finds
  // the installed module on the interpreter's path).
  const std::string build_dir = SHELLSPACE_PYTHON_BUILD_DIR;
  struct stat info {};
  if (!build_dir.empty() &&
      stat((build_dir + "/shellspace/collections/__init__.py").c_str(),
           &info) == 0) {
    const char* old = std::getenv("PYTHONPATH");
    const std::string path =
        old && *old ? build_dir + ":" + old : build_dir;
    setenv("PYTHONPATH", path.c_str(), 1);
  }
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  sigset_t stops;
  sigemptyset(&stops);
  sigaddset(&stops, SIGINT);
  sigaddset(&stops, SIGTERM);
  sigprocmask(SIG_BLOCK, &stops, nullptr);  // the bootstrap unblocks them
  execvp(argv[0], argv.data());
  sigprocmask(SIG_UNBLOCK, &stops, nullptr);
  throw InputError(std::string("cannot run ") + argv[0] + ": " +
                   std::strerror(errno));
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "collection distances",
    "collection distances --inputs a.ply,b.ply,... --output D.npz "
    "[--scheduler none|local[:N]|ADDRESS] [--steps 4] [--time_limit S] "
    "[--pair_time_limit S] [--cache C.npz] (sqrt(E_K) of every pair, on "
    "Dask)",
    shellspace::DistancesFlags(),
    [] { return shellspace::RunCollection("distances"); });
SHELLSPACE_REGISTER_VERB(
    "collection mean",
    "collection mean --inputs a.ply,b.ply,... --output M.ply "
    "[--scheduler none|local[:N]|ADDRESS] [--time_limit S] (the elastic "
    "mean, its per-shape terms on Dask)",
    shellspace::MeanFlags(), [] { return shellspace::RunCollection("mean"); });
SHELLSPACE_REGISTER_VERB(
    "collection pca",
    "collection pca --inputs a.ply,b.ply,... --output P.npz [--modes 3] "
    "[--scheduler none|local[:N]|ADDRESS] [--time_limit S] (shell PCA, the "
    "LOGs and mode shots on Dask)",
    shellspace::PcaFlags(), [] { return shellspace::RunCollection("pca"); });
