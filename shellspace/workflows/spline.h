// The spline workflow (the `spline` verb, shellspace.spline): the initial
// path through validated keyframes (the LΘA spline or the piecewise
// geodesic), then the Riemannian spline minimising F_K from it (method
// nonlinear) or the LΘA spline alone (method ltheta), its energy split and
// status.
#ifndef SHELLSPACE_WORKFLOWS_SPLINE_H_
#define SHELLSPACE_WORKFLOWS_SPLINE_H_

#include <functional>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/problems/splines/spline.h"
#include "shellspace/problems/splines/spline_initial_path.h"
#include "shellspace/workflows/common.h"
#include "shellspace/workflows/solve_status.h"

namespace shellspace {
namespace workflows {

// How the spline is made: "nonlinear" or "ltheta" (SplineOptions::method).
enum class SplineMethod { kNonlinear, kLTheta };
// SplineMethod of "nonlinear" or "ltheta"; InputError starting with `name`
// (the caller's name of the option: "--method", "method") otherwise.
SplineMethod ParseSplineMethod(const std::string& value,
                               const std::string& name);
const char* SplineMethodName(SplineMethod method);
// InputError unless `init` goes with `method` (method ltheta is the LΘA
// spline itself: init ltheta), naming the options as the caller does.
void CheckSplineMethod(SplineMethod method, SplineInit init,
                       const std::string& method_name,
                       const std::string& init_name);

struct SplineOptions {
  // The first keyframe, validated, with its topology; every keyframe's
  // positions and its time index.
  Mesh reference;
  Topology topology;
  std::vector<Positions> keyframes;
  std::vector<int> at;
  int steps = 8;
  bool periodic = false;
  // kNonlinear (L-BFGS on F_K from the initial path) or kLTheta (the LΘA
  // spline alone; init must be SplineInit::kLTheta, CheckSplineMethod).
  SplineMethod method = SplineMethod::kNonlinear;
  SplineInit init = SplineInit::kLTheta;
  // Method ltheta: also evaluate F_K of the path (false: the LΘA path
  // alone, "not optimised").
  bool evaluate_energy = true;
  MaterialChoice material;
  // The initial path's solves (LM per LΘA frame or per geodesic segment)
  // and the spline's (the outer L-BFGS and the midpoint solves); each stop
  // poll is the front end's stop request.
  SolverSettings init_settings;
  SplineSettings settings;
  // One line per step of the initial path; may be empty.
  std::function<void(const std::string&)> log;
};

struct SplineResult {
  Mesh reference;
  std::string method;
  SplineInitialPath initial;
  // The spline (method ltheta: F_K of the LΘA path, converged if every
  // frame's reconstruction did); evaluated false and the initial path if
  // F_K was not evaluated (evaluate_energy false).
  shellspace::SplineResult spline;
  bool optimised = false;  // the outer L-BFGS ran (method nonlinear)
  bool energy_evaluated = false;
  EnergySplit energy_split;  // of the path's E_K, computed once
  MaterialChoice material;
  bool stopped = false;
  // Not converged: the LΘA frames short of the tolerance (method ltheta),
  // or the L-BFGS's shortfall (SplineShortfall, regress.h).
  SolveStatus status;

  const ShellPath& path() const { return spline.path; }
};

// InputError for an unknown method, init geodesic with method ltheta, and
// what the library refuses (keyframes, at, steps).
SplineResult RunSpline(const SplineOptions& options);

// method, the initial path's keys (AddSplineInitJson), energy_split, then
// reports' SplineJson (its keys, `seconds` and frames); without F_K:
// iterations 0, converged, termination "not optimised", seconds, frames.
JsonObject ToJson(const SplineResult& result, double seconds);

}  // namespace workflows
}  // namespace shellspace

#endif  // SHELLSPACE_WORKFLOWS_SPLINE_H_
