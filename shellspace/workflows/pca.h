// The shell PCA workflow (the `pca` verb, shellspace.pca): the elastic mean
// of the inputs, their displacements and the Gram matrix, the mode shapes
// shot by EXP_K, optionally the Procrustes baseline and the leave-one-out
// table. A stop request in any phase ends it with the mean alone
// (stopped_in names the phase): a LOG or EXP shot stopped midway would
// give a wrong mode.
#ifndef SHELLSPACE_WORKFLOWS_PCA_H_
#define SHELLSPACE_WORKFLOWS_PCA_H_

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/statistics/leave_one_out.h"
#include "shellspace/problems/statistics/procrustes_pca.h"
#include "shellspace/problems/statistics/shell_pca.h"
#include "shellspace/solvers/solver_settings.h"
#include "shellspace/workflows/common.h"
#include "shellspace/workflows/solve_status.h"

namespace shellspace {
namespace workflows {

struct PcaOptions {
  // As MeanOptions: the first input validated with its topology, every
  // input's positions, their names (empty: "inputs[i]").
  Mesh reference;
  Topology topology;
  std::vector<Positions> shapes;
  std::vector<std::string> names;
  MaterialChoice material;
  int modes = 3;                // mode pairs shot (and m of leave-one-out)
  bool procrustes = false;      // also the Procrustes baseline
  bool leave_one_out = false;   // also the leave-one-out table
  double amplitude = 1.0;       // mode shapes at -/+ amplitude sqrt(lambda)
  // LOG_K / EXP_K steps and the displacement kind (MakeShellPcaOptions).
  ShellPcaOptions pca;
  SolverSettings settings;  // settings.stop: the front end's stop request
  std::optional<Positions> initial_mean;  // the CLI's --mean
  // One line per finished phase, and one per leave-one-out step; may be
  // empty.
  std::function<void(const std::string&)> log;
  std::function<void(const std::string&)> leave_one_out_log;
};

struct PcaResult {
  Mesh reference;
  MaterialChoice material;
  int inputs = 0;
  ElasticMeanResult mean;
  // The shell PCA model (none if the run stopped before it was complete).
  std::optional<ShellPcaModel> model;
  int shell_modes = 0;  // mode pairs attempted (modes, at most the model's)
  // The shapes by name: "mean", then "mode_J_minus", "mode_J_plus" of
  // every shot that succeeded, then (procrustes) "procrustes_mean",
  // "procrustes_mode_J_minus", ...; the mean alone after a stop.
  std::vector<std::pair<std::string, Positions>> shapes;
  // The mode shapes whose EXP shot has no solution (names as above), and
  // why, one line each.
  std::vector<std::string> failed_shapes;
  std::vector<std::string> failed_shape_reasons;
  std::vector<int> far_input_indices;
  std::vector<std::string> far_inputs;
  std::optional<ProcrustesPcaModel> procrustes;
  std::optional<LeaveOneOutTable> leave_one_out;
  // "" or the phase a stop ended: "mean", "displacements", "mode shapes",
  // "leave-one-out".
  std::string stopped_in;
  bool stopped = false;
  // The elastic mean's (failures name "the elastic mean"); a mode shape
  // without a solution is listed in failed_shapes, not here.
  SolveStatus status;

  // The named shape, or null.
  const Positions* Shape(const std::string& name) const;
};

// InputError for bad options (fewer than 2 inputs, 3 with leave-one-out;
// more modes than the inputs allow; negative amplitude); a mean solve that
// could not run is status kFailed.
PcaResult RunPca(const PcaOptions& options);

// The summary: reports' PcaJson (failed shapes as their ".ply" files), the
// Procrustes and leave-one-out keys; after a stop PcaMeanJson, "modes": 0
// and stopped_in.
JsonObject ToJson(const PcaResult& result, const PcaOptions& options);

}  // namespace workflows
}  // namespace shellspace

#endif  // SHELLSPACE_WORKFLOWS_PCA_H_
