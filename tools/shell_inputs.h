// Loading and checking the shells and options the verbs take as input.
#ifndef SHELLSPACE_TOOLS_SHELL_INPUTS_H_
#define SHELLSPACE_TOOLS_SHELL_INPUTS_H_

#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {

// Throws InputError "--NAME is required" if `value` is empty.
void RequireFlag(const std::string& name, const std::string& value);

// Reads and validates a shell (geometry/validation.h).
Mesh LoadShell(const std::string& path);

// Reads a shell and checks it has the connectivity of `like` (read from
// `like_path`).
Mesh LoadCompatibleShell(const std::string& path, const Mesh& like,
                         const std::string& like_path);

// Loads the shell pair of --start and --end (after checking --start, --end,
// --output are given and --steps >= 1): the first validated, the second
// checked compatible with it.
struct ShellPair {
  Mesh start, end;
};
ShellPair LoadStartEndFromFlags();

// The material from --mu, --lambda, --eta (validated).
ShellMaterial MaterialFromFlags();

// ShellSpace of a validated mesh with the flags' material.
ShellSpace SpaceFromFlags(const Mesh& mesh);

// Solver settings with progress on unless --quiet.
SolverSettings SettingsFromFlags(const std::string& label);

// Splits "a,b,c" at commas (empty items are an error).
std::vector<std::string> SplitList(const std::string& list,
                                   const std::string& flag);

// Creates directory `dir` (and parents) if missing; InputError on failure.
void MakeDirectory(const std::string& dir);

// Writes shapes as DIR/shape_000.ply ... (all written to temporary names
// first, then renamed, so a failure leaves no partial set).
void WriteFrames(const std::string& dir, const Faces& faces,
                 const std::vector<Positions>& frames);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_SHELL_INPUTS_H_
