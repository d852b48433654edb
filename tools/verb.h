// Registry of the `shellspace` command's verbs. Each verb lives in its own
// tools/verb_*.cc, defines its gflags there and registers itself with
// SHELLSPACE_REGISTER_VERB; `shellspace VERB --help` lists the flags defined
// in that file.
#ifndef SHELLSPACE_TOOLS_VERB_H_
#define SHELLSPACE_TOOLS_VERB_H_

#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace shellspace {

struct Verb {
  std::string name;
  std::string usage;   // one line: the verb's synopsis
  std::string source;  // __FILE__ of the verb, to list its flags in --help
  // Runs the verb after flags are parsed; returns the exit code. Throws
  // InputError for bad input (printed as one line by main).
  std::function<int()> run;
};

std::map<std::string, Verb>& VerbRegistry();

struct VerbRegistrar {
  VerbRegistrar(const std::string& name, const std::string& usage,
                const std::string& source, std::function<int()> run) {
    VerbRegistry()[name] = Verb{name, usage, source, std::move(run)};
  }
};

// Verbs with a sub-command (`shellspace branching simulate --flags`): for a
// verb registered with SHELLSPACE_VERB_TAKES_SUBCOMMAND, main keeps a first
// non-flag word after the verb out of gflags and stores it here.
std::set<std::string>& VerbsWithSubcommand();
std::vector<std::string>& VerbPositionalArgs();

struct VerbSubcommandRegistrar {
  explicit VerbSubcommandRegistrar(const std::string& name) {
    VerbsWithSubcommand().insert(name);
  }
};

#define SHELLSPACE_VERB_TAKES_SUBCOMMAND(name)                         \
  static ::shellspace::VerbSubcommandRegistrar SHELLSPACE_VERB_CONCAT( \
      verb_subcommand_, __LINE__)(name)

#define SHELLSPACE_VERB_CONCAT_INNER(a, b) a##b
#define SHELLSPACE_VERB_CONCAT(a, b) SHELLSPACE_VERB_CONCAT_INNER(a, b)
#define SHELLSPACE_REGISTER_VERB(name, usage, function)      \
  static ::shellspace::VerbRegistrar SHELLSPACE_VERB_CONCAT( \
      verb_registrar_, __LINE__)(name, usage, __FILE__, function)

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_VERB_H_
