#include "shellspace/problems/calculus/multiresolution.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "shellspace/geometry/validation.h"
#include "shellspace/problems/calculus/deformation_transfer.h"
#include "shellspace/problems/calculus/geodesic_initial_path.h"
#include "shellspace/problems/calculus/rotation_blend_path.h"
#include "shellspace/problems/calculus/shared_decimation.h"

namespace shellspace {

namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
      .count();
}

MultiresolutionLevel LevelReport(const ShellSpace& space,
                                 const GeodesicResult& g, double seconds,
                                 double tolerance_reached) {
  MultiresolutionLevel level;
  level.vertices = space.num_vertices;
  level.faces = static_cast<int>(space.faces.rows());
  level.iterations = g.iterations;
  level.path_energy = g.path_energy;
  level.final_gradient = g.final_gradient;
  level.converged = g.final_gradient <= tolerance_reached;
  level.seconds = seconds;
  return level;
}

std::string Number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

}  // namespace

ProlongationCheck CheckProlongation(const ShellSpace& space,
                                    const ShellPath& prolongated,
                                    const ShellPath& initial,
                                    const InitialPathReport& init) {
  ProlongationCheck check;
  check.checked = true;
  const std::optional<double> energy = TryPathEnergy(space, prolongated);
  const std::optional<double> initial_energy = TryPathEnergy(space, initial);
  check.prolongated_energy =
      energy ? *energy : std::numeric_limits<double>::infinity();
  check.initial_energy =
      initial_energy ? *initial_energy : std::numeric_limits<double>::infinity();
  check.smallest_face_area = SmallestFaceAreaRatio(space.faces, prolongated);
  const FaceAreaRatio initial_smallest =
      SmallestFaceAreaRatio(space.faces, initial);
  // Triangles that turn over between consecutive shapes, on either path
  // (FindPathDegeneracy, the test of --init auto): the fine start may turn
  // some itself (a linear path through a large twist), so the prolongation
  // is held to the start's count, not to its normals. The slivers of the
  // start are not counted: a cap's normal flips when its apex crosses its
  // long edge by a hair.
  const std::vector<int> slivers =
      FindSliverFaces(Mesh{initial.front(), space.faces}).faces;
  check.turned_faces =
      FindPathDegeneracy(space.faces, prolongated, slivers).turned_faces;
  check.initial_turned_faces =
      FindPathDegeneracy(space.faces, initial, slivers).turned_faces;
  const std::string versus = "E_K " + Number(check.prolongated_energy) +
                             " against " + Number(check.initial_energy) +
                             " of the " + GeodesicInitName(init.used) +
                             " path";
  if (!energy) {
    check.reason = "rejected: a degenerate element";
  } else if (check.turned_faces > check.initial_turned_faces) {
    check.reason = "rejected: " + std::to_string(check.turned_faces) +
                   " triangles turn over between its shapes, " +
                   std::to_string(check.initial_turned_faces) + " on the " +
                   GeodesicInitName(init.used) + " path; " + versus;
  } else if (check.smallest_face_area.ratio < kCollapsingFaceAreaRatio &&
             check.smallest_face_area.ratio < initial_smallest.ratio) {
    check.reason = "rejected: triangle " +
                   std::to_string(check.smallest_face_area.face) +
                   " of shape " +
                   std::to_string(check.smallest_face_area.shape) +
                   " keeps " + Number(check.smallest_face_area.ratio) +
                   " of its area; " + versus;
  } else if (!(check.prolongated_energy < check.initial_energy)) {
    check.reason = "rejected: " + versus;
  } else {
    check.used = true;
    check.reason = versus;
  }
  return check;
}

namespace {

// The coarse level's problem: the decimated ends, the masked vertices that
// survive (renumbered from the n fine ones, sorted), the other options as
// in `input`.
GeodesicInput CoarseInput(const GeodesicInput& input,
                          const SharedDecimation& level, int n) {
  GeodesicInput coarse_input;
  coarse_input.start = level.shapes[0];
  coarse_input.end = level.shapes[1];
  coarse_input.steps = input.steps;
  coarse_input.pin_gauge = input.pin_gauge;
  coarse_input.newton_from = input.newton_from;
  coarse_input.newton_contraction = input.newton_contraction;
  coarse_input.linear_solver = input.linear_solver;
  coarse_input.lm = input.lm;
  coarse_input.init = input.init;
  std::vector<int> coarse_of(n, -1);
  for (int i = 0; i < level.num_vertices(); ++i) {
    coarse_of[level.survivors[i]] = i;
  }
  for (int v : input.fixed_vertices) {
    if (coarse_of[v] >= 0) coarse_input.fixed_vertices.push_back(coarse_of[v]);
  }
  std::sort(coarse_input.fixed_vertices.begin(),
            coarse_input.fixed_vertices.end());
  return coarse_input;
}

// The coarse level's settings: the looser of the two gradient tolerances,
// and " coarse" after the progress label.
SolverSettings CoarseSettings(const SolverSettings& settings,
                              const MultiresolutionSettings& multires) {
  SolverSettings coarse_settings = settings;
  coarse_settings.gradient_tolerance =
      std::max(settings.gradient_tolerance, multires.coarse_gradient_tolerance);
  coarse_settings.progress_label = settings.progress_label + " coarse";
  return coarse_settings;
}

// The coarse geodesic `coarse_path` prolongated: each inner shape of
// `initial` (K = steps) replaced by its prolongation from the nearer end,
// but for the masked vertices.
ShellPath ProlongatedPath(const Prolongation& from_start,
                          const Prolongation& from_end,
                          const ShellPath& coarse_path,
                          const ShellPath& initial,
                          const std::vector<int>& fixed_vertices, int steps) {
  const int K = steps;
  ShellPath prolongated = initial;
  for (int k = 1; k < K; ++k) {
    const Prolongation& p = 2 * k <= K ? from_start : from_end;
    prolongated[k] = p.Apply(coarse_path[k]);
    // Masked vertices at their positions in the initial path (linear).
    for (int v : fixed_vertices) {
      prolongated[k].row(v) = initial[k].row(v);
    }
  }
  return prolongated;
}

// RotationGuidedPath's guide: per shape k = 0..steps and fine face, the
// rotation of its coarse face from coarse_path[0] to coarse_path[k].
std::vector<std::vector<Eigen::Matrix3d>> CoarseRotationGuide(
    const Faces& fine_faces, const Faces& coarse_faces,
    const ShellPath& coarse_path, const Prolongation& from_start, int steps) {
  const int K = steps;
  std::vector<std::vector<Eigen::Matrix3d>> guide(K + 1);
  for (int k = 0; k <= K; ++k) {
    const std::vector<Eigen::Matrix3d> coarse_rotations =
        FaceRotations(coarse_faces, coarse_path[0], coarse_path[k]);
    guide[k].resize(fine_faces.rows());
    for (int f = 0; f < fine_faces.rows(); ++f) {
      guide[k][f] = coarse_rotations[from_start.coarse_face_of()[f]];
    }
  }
  return guide;
}

// Makes the rotation-guided path *guided the prolongation (moved into
// *prolongated, *check its check) if it passes CheckProlongation against
// `initial` with a lower E_K than *prolongated, or *prolongated did not
// pass.
void PreferRotationGuided(const ShellSpace& space, const ShellPath& initial,
                          const InitialPathReport& init, ShellPath* guided,
                          ShellPath* prolongated, ProlongationCheck* check) {
  ProlongationCheck guided_check =
      CheckProlongation(space, *guided, initial, init);
  if (guided_check.used && (!check->used || guided_check.prolongated_energy <
                                                check->prolongated_energy)) {
    guided_check.rotation_guided = true;
    guided_check.reason = "rotation-guided; " + guided_check.reason;
    *check = guided_check;
    *prolongated = std::move(*guided);
  }
}

// The coarse levels of SolveGeodesicMultiresolution: fine->initial is set to
// the fine level's own initial path (its report in *fine_init) and
// fine->reference_gradient; the geodesic on the decimation to `target`
// vertices is solved (its levels into result->levels) and prolongated
// (result->prolongation), the prolongation made fine->initial if it passes.
// Returns the seconds the prolongation took.
double SolveCoarseAndProlongate(const ShellSpace& space,
                                const GeodesicInput& input,
                                const SolverSettings& settings,
                                const MultiresolutionSettings& multires,
                                int target, GeodesicInput* fine,
                                InitialPathReport* fine_init,
                                MultiresolutionResult* result) {
  // The fine level's own initial path: the start to beat, and the fine
  // finish stops where a solve from it would.
  fine->initial = MakeGeodesicInitialPath(space, input.start, input.end,
                                          input.steps, input.fixed_vertices,
                                          input.init, settings, fine_init);
  fine->reference_gradient =
      PathGradientNorm(space, input, fine->initial, settings.num_threads);
  const SharedDecimation level = DecimateShared(
      space.faces, {input.start, input.end}, target, input.fixed_vertices);
  Mesh coarse_mesh;
  coarse_mesh.faces = level.faces;
  coarse_mesh.positions = level.shapes[0];
  const ShellSpace coarse_space(coarse_mesh, Topology::Build(coarse_mesh),
                                space.material);
  const GeodesicInput coarse_input =
      CoarseInput(input, level, space.num_vertices);
  const SolverSettings coarse_settings = CoarseSettings(settings, multires);
  MultiresolutionSettings next = multires;
  next.levels = multires.levels - 1;
  MultiresolutionResult coarse = SolveGeodesicMultiresolution(
      coarse_space, coarse_input, coarse_settings, next);
  result->levels = std::move(coarse.levels);
  // Prolongation of each inner shape from the nearer end.
  const auto prolong_clock = std::chrono::steady_clock::now();
  const Prolongation from_start(space.faces, input.start, level,
                                level.shapes[0]);
  const Prolongation from_end(space.faces, input.end, level, level.shapes[1]);
  ShellPath prolongated =
      ProlongatedPath(from_start, from_end, coarse.geodesic.path, fine->initial,
                      input.fixed_vertices, input.steps);
  result->prolongation =
      CheckProlongation(space, prolongated, fine->initial, *fine_init);
  // The fine shapes turned as the coarse geodesic turns its faces
  // (RotationGuidedPath): where the decimation thinned out a part, the
  // deformation transfer carries the coarse face's stretch onto fine
  // triangles it does not fit, the rotations carry over.
  const std::vector<std::vector<Eigen::Matrix3d>> guide = CoarseRotationGuide(
      space.faces, level.faces, coarse.geodesic.path, from_start, input.steps);
  ShellPath guided =
      RotationGuidedPath(space.faces, input.start, input.end, guide,
                         prolongated, input.fixed_vertices);
  if (!guided.empty()) {
    PreferRotationGuided(space, fine->initial, *fine_init, &guided,
                         &prolongated, &result->prolongation);
  }
  if (result->prolongation.used) fine->initial = std::move(prolongated);
  return SecondsSince(prolong_clock);
}

}  // namespace

MultiresolutionResult SolveGeodesicMultiresolution(
    const ShellSpace& space, const GeodesicInput& input,
    const SolverSettings& settings, const MultiresolutionSettings& multires) {
  MultiresolutionResult result;
  double prolongation_seconds = 0;
  const int n = space.num_vertices;
  const int target = static_cast<int>(std::lround(multires.reduction * n));
  const bool coarsen = multires.levels > 0 && input.steps >= 2 &&
                       target >= multires.min_vertices && target < n;
  GeodesicInput fine = input;
  InitialPathReport fine_init;
  if (coarsen) {
    prolongation_seconds = SolveCoarseAndProlongate(
        space, input, settings, multires, target, &fine, &fine_init, &result);
  }
  const auto fine_clock = std::chrono::steady_clock::now();
  result.geodesic = SolveGeodesic(space, fine, settings);
  if (coarsen) {
    result.geodesic.init = fine_init;
    if (result.prolongation.used) {
      result.geodesic.init.reason =
          "prolongated from the coarse level (" + result.prolongation.reason +
          ")";
    }
  }
  const double tolerance =
      settings.gradient_tolerance *
      std::max(1.0, coarsen ? fine.reference_gradient
                            : result.geodesic.initial_gradient);
  result.levels.push_back(LevelReport(
      space, result.geodesic,
      prolongation_seconds + SecondsSince(fine_clock), tolerance));
  return result;
}

MultiresolutionSettings ResolveMultiresolution(
    const MultiresolutionChoice& choice, int num_vertices) {
  MultiresolutionSettings settings;
  if (!choice.automatic) {
    settings.levels = choice.levels;
    // "off" was levels 0 with the default min_vertices; a number, coarse
    // levels down to 20 vertices.
    if (choice.levels > 0) settings.min_vertices = 20;
    return settings;
  }
  settings.levels = 0;
  settings.min_vertices = kAutoMinVertices;
  for (double n = 0.25 * num_vertices; n >= kAutoMinVertices; n *= 0.25) {
    ++settings.levels;
  }
  return settings;
}

}  // namespace shellspace
