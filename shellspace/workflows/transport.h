// The transport workflow (the `transport` verb, shellspace.transport):
// Schild's ladder of a variation along a validated path, the energy split
// of the transported shapes and the status of its rungs.
#ifndef SHELLSPACE_WORKFLOWS_TRANSPORT_H_
#define SHELLSPACE_WORKFLOWS_TRANSPORT_H_

#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/problems/calculus/parallel_transport.h"
#include "shellspace/solvers/solver_settings.h"
#include "shellspace/workflows/common.h"
#include "shellspace/workflows/solve_status.h"

namespace shellspace {
namespace workflows {

struct TransportOptions {
  // The path's first frame, validated, with its topology; every frame's
  // positions (the first included, at least 2).
  Mesh first;
  Topology topology;
  std::vector<Positions> path;
  // s_0 + xi_0: the shape whose difference from s_0 is transported.
  Positions variation;
  double epsilon = 1.0;  // > 0
  std::vector<int> fixed_vertices;
  MaterialChoice material;
  SolverSettings settings;  // settings.stop: the front end's stop request
};

struct TransportResult {
  Mesh first;
  shellspace::TransportResult transport;  // shapes s_k + eps xi_k, rungs
  EnergySplit energy_split;  // of the transported shapes, computed once
  MaterialChoice material;
  double epsilon = 1.0;
  // Rungs solved at epsilon / n and scaled back, one line each.
  std::vector<std::string> warnings;
  bool stopped = false;
  // Not converged: one failure per rung without an EXP solution ("rung k
  // not solved: EXP residual R > A (also at epsilon / n)").
  SolveStatus status;

  const std::vector<Positions>& shapes() const { return transport.shapes; }
};

// InputError for epsilon <= 0 or fewer than 2 frames.
TransportResult RunTransport(const TransportOptions& options);

// reports' TransportJson, then energy_split.
JsonObject ToJson(const TransportResult& result);

}  // namespace workflows
}  // namespace shellspace

#endif  // SHELLSPACE_WORKFLOWS_TRANSPORT_H_
