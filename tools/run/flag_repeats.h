// Every flag is given once: `--steps 4 --steps 8` is refused (gflags would
// silently keep the last value), so are `--steps=4 -steps 4` and
// `--quiet --noquiet`. Values come from the command line only: --flagfile,
// --fromenv and --tryfromenv are not flags of any verb (main.cc refuses
// them as it refuses every flag outside the verb's table), so a flag file
// never repeats or overrides a command-line flag.
#ifndef SHELLSPACE_TOOLS_RUN_FLAG_REPEATS_H_
#define SHELLSPACE_TOOLS_RUN_FLAG_REPEATS_H_

#include <string>
#include <vector>

namespace shellspace {

// The arguments after the verb, as parsed by gflags (so every flag name is
// known). Returns "" if no flag repeats, else one line, e.g. "--steps is
// given twice (4, then 8): give each flag once".
std::string RepeatedFlagProblem(const std::vector<std::string>& args);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_RUN_FLAG_REPEATS_H_
