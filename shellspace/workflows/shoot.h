// The shooting workflow (the `shoot` verb, shellspace.shoot): EXP steps
// from two validated poses of one shell, the path's energy split and the
// status of its steps.
#ifndef SHELLSPACE_WORKFLOWS_SHOOT_H_
#define SHELLSPACE_WORKFLOWS_SHOOT_H_

#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/solvers/solver_settings.h"
#include "shellspace/workflows/common.h"
#include "shellspace/workflows/solve_status.h"

namespace shellspace {
namespace workflows {

struct ShootOptions {
  // s_0, validated, with its topology; s_1 (positions of the same mesh).
  Mesh first;
  Topology topology;
  Positions second;
  int steps = 8;          // K >= 1
  bool backward = false;  // extrapolate before s_0
  std::vector<int> fixed_vertices;
  MaterialChoice material;
  SolverSettings settings;  // settings.stop: the front end's stop request
};

struct ShootResult {
  Mesh first;  // s_0 and its faces
  shellspace::ShootResult shot;  // the path, its EXP steps and energies
  EnergySplit energy_split;      // of the path, computed once
  MaterialChoice material;
  bool stopped = false;
  // Not converged: one failure per EXP step without a root ("EXP step i not
  // solved: relative residual R > A (method)").
  SolveStatus status;

  const ShellPath& path() const { return shot.path; }
};

// InputError for steps < 1.
ShootResult RunShoot(const ShootOptions& options);

// reports' ShootJson, then energy_split.
JsonObject ToJson(const ShootResult& result);

}  // namespace workflows
}  // namespace shellspace

#endif  // SHELLSPACE_WORKFLOWS_SHOOT_H_
