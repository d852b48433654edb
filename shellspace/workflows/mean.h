// The elastic mean workflow (the `mean` verb, shellspace.mean): from
// validated shapes of one shell to their elastic mean, its energy split,
// the inputs far from the others and its status.
#ifndef SHELLSPACE_WORKFLOWS_MEAN_H_
#define SHELLSPACE_WORKFLOWS_MEAN_H_

#include <optional>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/solvers/solver_settings.h"
#include "shellspace/workflows/common.h"
#include "shellspace/workflows/solve_status.h"

namespace shellspace {
namespace workflows {

struct MeanOptions {
  // The first input, validated, with its topology (the material's
  // reference), and every input's positions (the first included).
  Mesh reference;
  Topology topology;
  std::vector<Positions> shapes;
  // How the summary and warnings name each input (the CLI: its path;
  // Python: "inputs[i]"); empty: "inputs[i]".
  std::vector<std::string> names;
  MaterialChoice material;
  SolverSettings settings;  // settings.stop: the front end's stop request
  // A mean computed before: the solve starts there (the CLI's --mean).
  std::optional<Positions> initial_mean;
};

struct MeanResult {
  Mesh reference;
  ElasticMeanResult mean;  // the library's: mean, energies, iterations
  EnergySplit energy_split;  // of sum_i W[mean, s_i], computed once
  MaterialChoice material;
  int inputs = 0;
  // FarInputs of the energies: their indices and names.
  std::vector<int> far_input_indices;
  std::vector<std::string> far_inputs;
  bool stopped = false;
  SolveStatus status;  // failures name "elastic mean"
};

// InputError for bad input (no shapes, another vertex count); an LM solve
// that could not run is status kFailed (message "elastic mean failed:
// ..."), not an exception.
MeanResult RunMean(const MeanOptions& options);

// reports' MeanJson, then energy_split.
JsonObject ToJson(const MeanResult& result);

// The name of input i: names[i], or "inputs[i]" if names is empty.
std::string InputName(const std::vector<std::string>& names, int i);

// "W[S, mean] = 2.07, 46 times the median 0.045": why input i is far.
std::string FarInputText(const ElasticMeanResult& mean, int i);

// The unconverged mean's failure line, "WHAT: |grad| ... after N LM + M
// Newton iterations (termination)", or "" if it converged.
std::string MeanFailure(const ElasticMeanResult& mean, const std::string& what);

}  // namespace workflows
}  // namespace shellspace

#endif  // SHELLSPACE_WORKFLOWS_MEAN_H_
