// The regression workflow (the `regress` verb, shellspace.regress): the
// path of K + 1 shapes closest to validated inputs at given time indices
// plus sigma times the spline energy F_K, its energy split and status.
#ifndef SHELLSPACE_WORKFLOWS_REGRESS_H_
#define SHELLSPACE_WORKFLOWS_REGRESS_H_

#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/problems/splines/spline.h"
#include "shellspace/workflows/common.h"
#include "shellspace/workflows/solve_status.h"

namespace shellspace {
namespace workflows {

struct RegressOptions {
  // The first input, validated, with its topology; every input's
  // positions and its time index (strictly increasing, in [0, steps]).
  Mesh reference;
  Topology topology;
  std::vector<Positions> inputs;
  std::vector<int> at;
  int steps = 8;
  double sigma = 1.0;  // >= 0
  MaterialChoice material;
  // The outer L-BFGS (its stop: the front end's stop request) and the
  // midpoint solves.
  SplineSettings settings;
};

struct RegressResult {
  Mesh reference;
  shellspace::SplineResult spline;  // the path, F_K, data term, iterations
  EnergySplit energy_split;  // of the path's E_K, computed once
  MaterialChoice material;
  double sigma = 1.0;
  bool stopped = false;
  // Not converged: "regress: relative gradient ... (termination)", or
  // "regress: stopped before the first evaluation of F_K finished".
  SolveStatus status;

  const ShellPath& path() const { return spline.path; }
};

// InputError for sigma < 0 and what SolveRegression refuses.
RegressResult RunRegress(const RegressOptions& options);

// sigma, energy_split, then reports' SplineJson (its keys, `seconds` and
// frames).
JsonObject ToJson(const RegressResult& result, double seconds);

// What an unconverged spline or regression solve fell short of:
// "VERB: relative gradient G above the tolerance T, no function-tolerance
// stop, after N L-BFGS iterations (TERMINATION)", or "VERB: stopped before
// the first evaluation of F_K finished"; "" if it converged.
std::string SplineShortfall(const std::string& verb,
                            const shellspace::SplineResult& result,
                            double tolerance);

}  // namespace workflows
}  // namespace shellspace

#endif  // SHELLSPACE_WORKFLOWS_REGRESS_H_
