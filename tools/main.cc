// `shellspace VERB [SUBCOMMAND] [--flags]`: dispatches to the verbs
// registered in tools/verbs/verb_*.cc. Before a verb runs, main checks its flags
// against the verb's table (tools/verbs/verb_flags.h): a flag the verb does not
// take or a flag given twice (tools/run/flag_repeats.h) is rejected (exit 2),
// the verb's own defaults are applied, and
// required flags, numeric ranges and the values of string flags with a check
// are checked (exit 1). Input errors are
// printed as one line and exit with 1.
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/runtime/heap_reuse.h"
#include "shellspace/runtime/openmp_threads.h"
#include "shellspace/io/input_file.h"
#include "tools/run/common_flags.h"
#include "tools/run/flag_repeats.h"
#include "tools/run/run_output.h"
#include "tools/run/run_status.h"
#include "tools/run/stop_request.h"
#include "tools/verbs/verb.h"

namespace shellspace {

std::string MainVerbName();
int RunMain(int argc, char** argv);

std::map<std::string, Verb>& VerbRegistry() {
  static std::map<std::string, Verb> registry;
  return registry;
}

namespace {

// Flags of the logging library every verb accepts.
const std::set<std::string> kGlobalFlags = {"minloglevel", "v"};

bool IsHelp(const char* arg) {
  return !std::strcmp(arg, "--help") || !std::strcmp(arg, "-help") ||
         !std::strcmp(arg, "-h") || !std::strcmp(arg, "help");
}

void PrintUsage() {
  std::cout << "usage: shellspace VERB [--flag=value ...]\n\nverbs:\n";
  for (const auto& [name, verb] : VerbRegistry()) {
    std::cout << "  " << verb.usage << "\n";
  }
  std::cout << "\n`shellspace VERB --help` lists the flags of a verb.\n";
}

// The sub-commands registered under `group` ("branching" -> "simulate", ...).
std::vector<std::string> Subcommands(const std::string& group) {
  std::vector<std::string> names;
  for (const auto& [name, verb] : VerbRegistry()) {
    if (name.rfind(group + " ", 0) == 0) names.push_back(name.substr(group.size() + 1));
  }
  return names;
}

std::string Join(const std::vector<std::string>& items, const char* sep) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? sep : "") + items[i];
  return out;
}

bool GetFlag(const std::string& name, gflags::CommandLineFlagInfo* info) {
  return gflags::GetCommandLineFlagInfo(name.c_str(), info);
}

std::string DefaultOf(const FlagSpec& spec,
                      const gflags::CommandLineFlagInfo& info) {
  return spec.verb_default.empty() ? info.default_value : spec.verb_default;
}

// `shellspace VERB --help`: the verb's flags only.
void PrintVerbHelp(const Verb& verb) {
  std::cout << "usage: shellspace " << verb.usage << "\n\nflags of "
            << verb.name << ":\n";
  for (const FlagSpec& spec : verb.flags) {
    gflags::CommandLineFlagInfo info;
    if (!GetFlag(spec.name, &info)) continue;  // caught by CheckTable
    std::cout << "  --" << spec.name << " (" << info.type << ")  "
              << spec.meaning << "\n      ";
    if (spec.required) {
      std::cout << "required";
    } else {
      const std::string value = spec.shown_default.empty()
                                    ? DefaultOf(spec, info)
                                    : spec.shown_default;
      std::cout << "default: " << (value.empty() ? "\"\"" : value);
    }
    if (!spec.range.empty()) std::cout << "; valid: " << spec.range;
    std::cout << "\n";
  }
  std::cout << "  --minloglevel (int32)  0 also shows the solvers' warnings "
               "and errors\n"
            << "      default: 3 (fatal only)\n";
}

// A programming error in a verb's table: a name gflags does not know, or a
// numeric range on a non-numeric flag.
void CheckTable(const Verb& verb) {
  for (const FlagSpec& spec : verb.flags) {
    gflags::CommandLineFlagInfo info;
    if (!GetFlag(spec.name, &info)) {
      throw std::logic_error("verb " + verb.name + " lists undefined flag --" +
                             spec.name);
    }
    const bool numeric = info.type == "int32" || info.type == "double" ||
                         info.type == "int64" || info.type == "uint64" ||
                         info.type == "uint32";
    if (numeric != static_cast<bool>(spec.valid)) {
      throw std::logic_error("verb " + verb.name + ": --" + spec.name +
                             (numeric ? " needs" : " cannot have") +
                             " a valid range");
    }
  }
}

// The first flag set on the command line that `verb` does not take, or "".
std::string ForeignFlag(const Verb& verb) {
  std::vector<gflags::CommandLineFlagInfo> all;
  gflags::GetAllFlags(&all);
  for (const auto& info : all) {
    if (info.is_default) continue;
    if (FindFlag(verb.flags, info.name) || kGlobalFlags.count(info.name)) {
      continue;
    }
    return info.name;
  }
  return "";
}

// Applies the verb's defaults to the flags not given; throws InputError for
// a missing required flag or a value out of range.
void ApplyDefaultsAndValidate(const Verb& verb) {
  for (const FlagSpec& spec : verb.flags) {
    gflags::CommandLineFlagInfo info;
    GetFlag(spec.name, &info);
    if (!spec.verb_default.empty() && info.is_default) {
      gflags::SetCommandLineOptionWithMode(spec.name.c_str(),
                                           spec.verb_default.c_str(),
                                           gflags::SET_FLAGS_DEFAULT);
      GetFlag(spec.name, &info);
    }
    if (spec.required && info.current_value.empty()) {
      throw InputError("--" + spec.name + " is required");
    }
    if (spec.check) {
      try {
        spec.check(info.current_value);
      } catch (const InputError& error) {
        throw InputError("--" + spec.name + ": " + error.what());
      }
    }
    if (spec.valid && !(info.is_default && !spec.shown_default.empty())) {
      char* end = nullptr;
      const double value = std::strtod(info.current_value.c_str(), &end);
      if (*end != '\0' || !std::isfinite(value) || !spec.valid(value)) {
        throw InputError("--" + spec.name + " must be " + spec.range +
                         ", got " + info.current_value);
      }
    }
  }
}

// Checks the files gflags' --flagfile would read (on the command line and,
// recursively, in those files; a value is a comma-separated list) before
// gflags reads them: a regular file of at most 1 MiB, opened without
// blocking, so a FIFO or /dev/zero is one line (InputError), not a hang or
// a read until memory runs out.
void CheckFlagFiles(const std::vector<std::string>& args, int depth = 0) {
  for (size_t i = 0; i < args.size(); ++i) {
    std::string arg = args[i];
    while (!arg.empty() && (arg[0] == ' ' || arg[0] == '\t')) arg.erase(0, 1);
    const size_t name = arg.rfind("--", 0) == 0  ? 2
                        : arg.rfind("-", 0) == 0 ? 1
                                                 : 0;
    if (name == 0 || arg.compare(name, 8, "flagfile") != 0) continue;
    std::string value;
    if (arg.size() > name + 8 && arg[name + 8] == '=') {
      value = arg.substr(name + 9);
    } else if (arg.size() == name + 8 && i + 1 < args.size()) {
      value = args[++i];
    } else {
      continue;  // another flag, or no value (gflags' error)
    }
    if (depth > 8) throw InputError("flag files nested more than 8 deep");
    std::stringstream list(value);
    for (std::string file; std::getline(list, file, ',');) {
      if (file.empty()) continue;
      std::stringstream lines(
          ReadInputFile(file, "flag file", kMaxFlagFileBytes));
      std::vector<std::string> nested;
      for (std::string line; std::getline(lines, line);) nested.push_back(line);
      CheckFlagFiles(nested, depth + 1);
    }
  }
}

// The verb named by argv[1] (and argv[2] for a verb with sub-commands):
// *first_flag is the index of its first flag. Returns -1 to go on, or the
// exit code of a usage line printed here (help, a missing sub-command, an
// unknown verb).
int ResolveVerb(int argc, char** argv, std::string* name, int* first_flag) {
  if (argc < 2 || IsHelp(argv[1])) {
    PrintUsage();
    return argc < 2 ? 1 : 0;
  }
  *name = argv[1];
  *first_flag = 2;
  const std::vector<std::string> subcommands = Subcommands(*name);
  if (!subcommands.empty()) {
    if (argc < 3 || argv[2][0] == '-' || IsHelp(argv[2])) {
      if (argc >= 3 && IsHelp(argv[2])) {
        std::cout << "usage: shellspace " << *name << " "
                  << Join(subcommands, "|") << " [--flags]\n\n`shellspace "
                  << *name
                  << " SUBCOMMAND --help` lists the flags of a sub-command.\n";
        return 0;
      }
      std::cerr << "shellspace " << *name
                << ": expected a sub-command: " << Join(subcommands, ", ")
                << "\n";
      return 2;
    }
    *name += std::string(" ") + argv[2];
    *first_flag = 3;
  }
  if (VerbRegistry().find(*name) == VerbRegistry().end()) {
    std::cerr << "shellspace: unknown verb '" << *name
              << "' (run `shellspace --help`)\n";
    return 2;
  }
  return -1;
}

// Checks the verb's table, answers --help, reads the flag files and lets
// gflags parse the flags after the verb; refuses stray arguments, repeated
// flags and flags of other verbs. Returns -1 to go on, or the exit code.
int ParseVerbFlags(const Verb& verb, int argc, char** argv, int first_flag) {
  const std::string& name = verb.name;
  try {
    CheckTable(verb);
  } catch (const std::exception& error) {
    std::cerr << "shellspace " << name << ": internal error: " << error.what()
              << "\n";
    return 3;
  }
  for (int i = first_flag; i < argc; ++i) {
    if (IsHelp(argv[i])) {
      PrintVerbHelp(verb);
      return 0;
    }
  }
  const std::vector<std::string> given(argv + first_flag, argv + argc);
  try {
    CheckFlagFiles(given);
  } catch (const InputError& error) {
    std::cerr << "shellspace " << name << ": error: " << error.what() << "\n";
    return 1;
  }
  std::vector<char*> args;
  std::string program = std::string(argv[0]) + " " + name;
  args.push_back(program.data());
  for (int i = first_flag; i < argc; ++i) args.push_back(argv[i]);
  int new_argc = static_cast<int>(args.size());
  char** new_argv = args.data();
  gflags::SetUsageMessage("shellspace " + verb.usage);
  gflags::ParseCommandLineNonHelpFlags(&new_argc, &new_argv, true);
  if (new_argc > 1) {
    std::cerr << "shellspace " << name << ": unexpected argument '"
              << new_argv[1] << "'\n";
    return 2;
  }
  const std::string repeated = RepeatedFlagProblem(given);
  if (!repeated.empty()) {
    std::cerr << "shellspace " << name << ": " << repeated << "\n";
    return 2;
  }
  const std::string foreign = ForeignFlag(verb);
  if (!foreign.empty()) {
    std::cerr << "shellspace " << name << ": --" << foreign
              << " is not a flag of " << name << " (`shellspace " << name
              << " --help` lists them)\n";
    return 2;
  }
  return -1;
}

// Ceres' warnings and errors (an LM step retried after a failed
// factorisation of a nearly singular Gauss-Newton matrix, an evaluation at a
// degenerate trial shape) are routine here and our own status lines say how
// a solve went: hidden unless the user passes --minloglevel=0.
void QuietCeresLogging(const char* program) {
  gflags::CommandLineFlagInfo loglevel;
  if (gflags::GetCommandLineFlagInfo("minloglevel", &loglevel) &&
      loglevel.is_default) {
    FLAGS_minloglevel = google::GLOG_FATAL;
  }
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(program);
}

// Applies the verb's defaults, validates its flags and runs it under the
// stop handlers; a stop request, input errors and internal errors end in
// one line on stderr and their exit codes.
int RunVerb(const Verb& verb) {
  const std::string& name = verb.name;
  try {
    ApplyDefaultsAndValidate(verb);
    InstallStopHandlers(FindFlag(verb.flags, "time_limit") ? FLAGS_time_limit
                                                           : 0);
    const int code = verb.run();
    const StopCause stop = RequestedStopCause();
    if (code != 0 || stop == StopCause::kNone) return code;
    std::cerr << "shellspace " << name << ": stopped (" << StopCauseText(stop)
              << "): "
              << (ObservedStopCause() != StopCause::kNone
                      ? "wrote the best state so far, marked partial"
                      : "after the solves; the output is complete");
    const std::string unmet = StoppedRunFailures();
    if (!unmet.empty()) std::cerr << "; not converged: " << unmet;
    std::cerr << "\n";
    return StopExitCode(stop);
  } catch (const ReadStopped& error) {
    // A signal while an input was read: nothing to write.
    const StopCause stop = RequestedStopCause();
    std::cerr << "shellspace " << name << ": stopped (" << StopCauseText(stop)
              << ") while reading " << error.path() << "\n";
    return stop == StopCause::kNone ? 1 : StopExitCode(stop);
  } catch (const InputError& error) {
    std::cerr << "shellspace " << name << ": error: " << error.what() << "\n";
    return 1;
  } catch (const std::exception& error) {
    std::cerr << "shellspace " << name << ": internal error: " << error.what()
              << "\n";
    return 3;
  }
}

// Standard output and error closed when the process started: each gets a
// read-only /dev/null in its place, so that no file the run opens takes
// descriptor 1 or 2 (and receives the report), and every write to it
// fails, which CheckedExit reports.
void ReserveStandardDescriptors() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    const int null = ::open("/dev/null", fd == 0 ? O_WRONLY : O_RDONLY);
    if (null >= 0 && null != fd) {
      ::dup2(null, fd);
      ::close(null);
    }
  }
}

// `code`, unless standard output or error could not be written, flushed
// or closed: then one line on stderr (if it can still be written) and
// exit 1 (or `code` if that already says failure). A report to /dev/full
// or to a closed stdout is a failed run, not exit 0.
int CheckedExit(const std::string& name, int code) {
  std::cout.flush();
  const bool out_failed = !std::cout.good() || std::fflush(stdout) != 0 ||
                          std::ferror(stdout) != 0;
  const int out_error = errno;
  const bool out_closed = out_failed ? false : ::close(1) != 0 &&
                                                   errno != EBADF;
  if (out_failed || out_closed) {
    std::cerr << "shellspace" << (name.empty() ? "" : " " + name)
              << ": error: cannot write standard output ("
              << std::strerror(out_failed ? out_error : errno) << ")\n";
    code = code == 0 ? 1 : code;
  }
  std::cerr.flush();
  if (!std::cerr.good() || std::fflush(stderr) != 0 ||
      std::ferror(stderr) != 0) {
    code = code == 0 ? 1 : code;
  }
  return code;
}

}  // namespace
}  // namespace shellspace

// The verb, its flags (parsed and validated), then the verb's run; the
// exit code says failure also when the report could not be written.
int main(int argc, char** argv) {
  shellspace::ReserveStandardDescriptors();
  const int code = shellspace::RunMain(argc, argv);
  return shellspace::CheckedExit(shellspace::MainVerbName(), code);
}

namespace shellspace {
namespace {
std::string& VerbNameStorage() {
  static std::string name;
  return name;
}
}  // namespace

std::string MainVerbName() { return VerbNameStorage(); }

int RunMain(int argc, char** argv) {
  shellspace::SetRunCommandLine(argc, argv);
  shellspace::SerialOpenMpInThisThread();
  shellspace::KeepFreedHeapForReuse();
  std::string name;
  int first_flag = 0;
  if (const int code = shellspace::ResolveVerb(argc, argv, &name, &first_flag);
      code >= 0) {
    return code;
  }
  VerbNameStorage() = name;
  const shellspace::Verb& verb = shellspace::VerbRegistry().at(name);
  if (const int code = shellspace::ParseVerbFlags(verb, argc, argv, first_flag);
      code >= 0) {
    return code;
  }
  shellspace::QuietCeresLogging(argv[0]);
  return shellspace::RunVerb(verb);
}

}  // namespace shellspace
