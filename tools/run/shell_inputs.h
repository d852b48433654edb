// Loading the shells and options the verbs take as input. The flags these
// functions read are in each verb's table (tools/verbs/verb_flags.h); main has
// checked their ranges and required values before the verb runs.
#ifndef SHELLSPACE_TOOLS_RUN_SHELL_INPUTS_H_
#define SHELLSPACE_TOOLS_RUN_SHELL_INPUTS_H_

#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/solvers/solver_settings.h"
#include "shellspace/workflows/common.h"

namespace shellspace {

// A validated shell and its topology (built once, by the validation).
struct Shell {
  std::string path;
  Mesh mesh;
  Topology topology;
};

// Reads and validates a shell (geometry/validation.h).
Shell LoadShell(const std::string& path);

// Reads a shell and checks it has the connectivity of `like` (then only its
// positions are validated: the topology is `like`'s). Its faces are
// `like`'s.
Mesh LoadCompatibleShell(const std::string& path, const Shell& like);

// A comma list of compatible shells: the first one, and the positions of
// all of them in order. `flag` names the list in errors.
struct ShellSet {
  Shell first;
  std::vector<std::string> paths;
  std::vector<Positions> shapes;
};
ShellSet LoadShellList(const std::string& list, const std::string& flag);

// The same for files already listed (e.g. by ListFrameFiles). With `like`,
// every file (the first too) is checked compatible with it instead, and
// `first` is `like`.
ShellSet LoadShellFiles(const std::vector<std::string>& paths,
                        const Shell* like = nullptr);

// Two shells, the second checked compatible with the first
// (LoadCompatibleShell): --start and --end, --first and --second,
// --reference and --deformed or --targets.
struct ShellPair {
  Shell first;
  Mesh second;
};
ShellPair LoadShellPair(const std::string& first, const std::string& second);

// The bending model of --bending (InputError for an unknown name).
BendingModel BendingModelFromFlags();

// The material of --mu, --lambda, --eta / --relative_eta and --bending for
// shells whose reference is `reference`, as the workflows take it: eta is
// --eta if given (eta_absolute), else --relative_eta x SurfaceArea(reference)
// (relative_bending_weight.h); InputError if both are given. A verb puts
// workflows::MaterialChoiceJson of it in its summary.
workflows::MaterialChoice MaterialChoiceFromFlags(const Mesh& reference);

// The --mask vertices, or none if --mask is empty.
std::vector<int> MaskFromFlags(int num_vertices);

// Solver settings of --tolerance, --max_iterations, --threads, with
// progress on unless --quiet, stopped by --time_limit and SIGINT/SIGTERM
// (tools/run/stop_request.h).
SolverSettings SettingsFromFlags(const std::string& label);

// Splits "a,b,c" at commas (empty items are an error naming `flag`).
std::vector<std::string> SplitList(const std::string& list,
                                   const std::string& flag);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_RUN_SHELL_INPUTS_H_
