// `shellspace VERB [--flags]`: dispatches to the verbs registered in
// tools/verb_*.cc. Input errors are printed as one line and exit with 1.
#include <gflags/gflags.h>
#include <glog/logging.h>

#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/tools/verb.h"

namespace shellspace {

std::map<std::string, Verb>& VerbRegistry() {
  static std::map<std::string, Verb> registry;
  return registry;
}

std::set<std::string>& VerbsWithSubcommand() {
  static std::set<std::string> verbs;
  return verbs;
}

std::vector<std::string>& VerbPositionalArgs() {
  static std::vector<std::string> args;
  return args;
}

namespace {

void PrintUsage() {
  std::cout << "usage: shellspace VERB [--flag=value ...]\n\nverbs:\n";
  for (const auto& [name, verb] : VerbRegistry()) {
    std::cout << "  " << verb.usage << "\n";
  }
  std::cout << "\n`shellspace VERB --help` lists the flags of a verb.\n";
}

void PrintVerbHelp(const Verb& verb) {
  std::cout << "usage: shellspace " << verb.usage << "\n\nflags:\n";
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);
  for (const auto& flag : flags) {
    const bool own = flag.filename == verb.source;
    const bool common =
        flag.filename.find("tools/common_flags") != std::string::npos;
    if (!own && !common) continue;
    std::cout << "  --" << flag.name << " (" << flag.description
              << ") default: \"" << flag.default_value << "\"\n";
  }
}

}  // namespace
}  // namespace shellspace

int main(int argc, char** argv) {
  using shellspace::VerbRegistry;
  if (argc < 2 || !std::strcmp(argv[1], "--help") ||
      !std::strcmp(argv[1], "help") || !std::strcmp(argv[1], "-h")) {
    shellspace::PrintUsage();
    return argc < 2 ? 1 : 0;
  }
  const std::string name = argv[1];
  auto it = VerbRegistry().find(name);
  if (it == VerbRegistry().end()) {
    std::cerr << "shellspace: unknown verb '" << name
              << "' (run `shellspace --help`)\n";
    return 2;
  }
  for (int i = 2; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-help") ||
        !std::strcmp(argv[i], "-h")) {
      shellspace::PrintVerbHelp(it->second);
      return 0;
    }
  }
  // A verb with a sub-command keeps its first non-flag word.
  int first_flag = 2;
  if (shellspace::VerbsWithSubcommand().count(name) && argc > 2 &&
      argv[2][0] != '-') {
    shellspace::VerbPositionalArgs().push_back(argv[2]);
    first_flag = 3;
  }
  // Let gflags parse everything after the verb.
  std::vector<char*> args;
  std::string program = std::string(argv[0]) + " " + name;
  args.push_back(program.data());
  for (int i = first_flag; i < argc; ++i) args.push_back(argv[i]);
  int new_argc = static_cast<int>(args.size());
  char** new_argv = args.data();
  // Ceres' warnings (an LM step retried after a failed factorisation of a
  // nearly singular Gauss-Newton matrix, in EXP steps) are routine here and
  // our own progress lines say how a solve goes: hidden unless the user
  // passes --minloglevel=0.
  FLAGS_minloglevel = google::GLOG_ERROR;
  gflags::SetUsageMessage("shellspace " + it->second.usage);
  gflags::ParseCommandLineNonHelpFlags(&new_argc, &new_argv, true);
  if (new_argc > 1) {
    std::cerr << "shellspace " << name << ": unexpected argument '"
              << new_argv[1] << "'\n";
    return 2;
  }
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);
  try {
    return it->second.run();
  } catch (const shellspace::InputError& error) {
    std::cerr << "shellspace " << name << ": error: " << error.what() << "\n";
    return 1;
  } catch (const std::exception& error) {
    std::cerr << "shellspace " << name << ": internal error: " << error.what()
              << "\n";
    return 3;
  }
}
