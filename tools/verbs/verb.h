// Registry of the `shellspace` command's verbs. Each verb lives in a
// tools/verbs/verb_*.cc, lists the flags it takes in its own FlagTable
// (tools/verbs/verb_flags.h) and registers itself with SHELLSPACE_REGISTER_VERB.
// A verb with sub-commands registers each one as "VERB SUBCOMMAND"
// ("branching simulate"), each with its own flags.
#ifndef SHELLSPACE_TOOLS_VERBS_VERB_H_
#define SHELLSPACE_TOOLS_VERBS_VERB_H_

#include <functional>
#include <map>
#include <string>

#include "tools/verbs/verb_flags.h"

namespace shellspace {

struct Verb {
  std::string name;   // "geodesic", or "branching simulate"
  std::string usage;  // one line: the verb's synopsis
  FlagTable flags;    // the only flags the verb accepts
  // Runs the verb after main has parsed and validated its flags; returns
  // the exit code. Throws InputError for bad input (printed as one line).
  std::function<int()> run;
};

std::map<std::string, Verb>& VerbRegistry();

struct VerbRegistrar {
  VerbRegistrar(const std::string& name, const std::string& usage,
                FlagTable flags, std::function<int()> run) {
    VerbRegistry()[name] =
        Verb{name, usage, std::move(flags), std::move(run)};
  }
};

#define SHELLSPACE_VERB_CONCAT_INNER(a, b) a##b
#define SHELLSPACE_VERB_CONCAT(a, b) SHELLSPACE_VERB_CONCAT_INNER(a, b)
#define SHELLSPACE_REGISTER_VERB(name, usage, flags, function) \
  static ::shellspace::VerbRegistrar SHELLSPACE_VERB_CONCAT(   \
      verb_registrar_, __LINE__)(name, usage, flags, function)

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_VERBS_VERB_H_
