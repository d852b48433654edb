// The geodesic workflow (the `geodesic` verb, shellspace.geodesic) and the
// logarithm built on it (`log`, shellspace.log): from two validated poses
// of one shell to the discrete geodesic, its energy split, its warnings and
// its status. The front ends read and validate the shells, resolve the
// material, bound the steps by memory, and write the files.
#ifndef SHELLSPACE_WORKFLOWS_GEODESIC_H_
#define SHELLSPACE_WORKFLOWS_GEODESIC_H_

#include <functional>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/solvers/solver_settings.h"
#include "shellspace/workflows/common.h"
#include "shellspace/workflows/solve_status.h"

namespace shellspace {
namespace workflows {

struct GeodesicOptions {
  // s_0, validated, with its topology; s_K (positions of the same mesh).
  Mesh start;
  Topology topology;
  Positions end;
  int steps = 8;                    // K >= 1
  std::vector<int> fixed_vertices;  // held at their linear positions
  MaterialChoice material;
  // The solve's choices (the front ends parse their words with
  // solve_choice_words.h): the coarse levels, the Newton finish's linear
  // solver, the LM stages' solver and the initial path.
  MultiresolutionChoice multires = MultiresolutionChoice::Automatic();
  PathLinearSolver linear_solver = PathLinearSolver::kAuto;
  GeodesicLm lm = GeodesicLm::kAuto;
  GeodesicInit init = GeodesicInit::kAuto;
  // The solves' settings; settings.stop is the front end's stop request
  // (a time limit, a signal), asked between iterations.
  SolverSettings settings;
  // Called before the solve with each warning about an input: which one
  // ("start" or "end") and the text (sliver triangles and folded edges of
  // s_0; those of s_K that s_0 does not have); may be empty.
  std::function<void(const std::string& input, const std::string& text)>
      warn;
};

struct GeodesicResult {
  Mesh start;  // s_0 and its faces (the frames' connectivity)
  // The levels of the solve and the fine geodesic (solve.geodesic: the
  // path, E_K, stages, iterations, gradients, converged).
  MultiresolutionResult solve;
  EnergySplit energy_split;  // of the path, computed once
  MaterialChoice material;   // as resolved
  SliverFaces slivers;       // of s_0 (and its folds), before the solve
  // The slivers and folds of s_K that s_0 does not have: a pose that
  // crushes triangles or folds the surface shut, which the path must do
  // too (named before the solve; a solve there is slow or fails).
  SliverFaces end_slivers;
  // The largest area ratio |f(s_k)| / |f(s_0)| of a sliver face of s_0 over
  // the path's shapes, and where (1, -1, -1 without slivers): how much the
  // path swells the slivers of the input.
  double sliver_swelling = 1;
  int sliver_swelling_face = -1, sliver_swelling_shape = -1;
  // Lines about the path (uneven step energies, a collapsing triangle).
  std::vector<std::string> warnings;
  bool stopped = false;  // the stop request cut a solve short
  SolveStatus status;

  const shellspace::GeodesicResult& geodesic() const { return solve.geodesic; }
  const ShellPath& path() const { return solve.geodesic.path; }
  double path_energy() const { return solve.geodesic.path_energy; }
};

// Where an unconverged geodesic is held: ", largest at vertex v of shape
// k" (GeodesicResult::gradient_peak; nothing if unknown) and, if that
// vertex lies on the triangle the path shrank most and the path crushed it
// below kCollapsingFaceAreaRatio of its start area, ", a vertex of face f,
// which the solve crushed to r of its start area while lowering E_K (a
// sliver or cap of the mesh: remesh it)". `faces`: the solve's faces
// (empty: no face is named).
std::string GradientPeakText(const shellspace::GeodesicResult& geodesic,
                             const Faces& faces);

// Solves the geodesic. InputError for bad options (a steps count below 1,
// an unknown word, a mask out of range, an end of another vertex count);
// a solve that could not run is status kFailed with the path it started
// from, not an exception.
GeodesicResult RunGeodesic(const GeodesicOptions& options);

// The summary of a geodesic: reports' GeodesicJson, then multires_levels,
// prolongation and energy_split. The front ends add their own keys
// (material, seconds, output, the stop fields).
JsonObject ToJson(const GeodesicResult& result);

// LOG_K(s_0 -> s_K) = K (s_1 - s_0) of the geodesic (the `log` verb).
struct LogResult {
  GeodesicResult geodesic;
  Positions log;
  double log_max_norm = 0;  // max |log| over the coordinates
};

// RunGeodesic, then the logarithm; status failures name "log: the
// geodesic".
LogResult RunLog(const GeodesicOptions& options);

// ToJson of the geodesic, then log_max_norm.
JsonObject ToJson(const LogResult& result);

}  // namespace workflows
}  // namespace shellspace

#endif  // SHELLSPACE_WORKFLOWS_GEODESIC_H_
