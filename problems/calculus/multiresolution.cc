#include "shellspace/problems/calculus/multiresolution.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "shellspace/problems/calculus/deformation_transfer.h"
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
  if (coarsen) {
    // The fine finish stops where a solve from the linear path would.
    fine.reference_gradient = LinearPathGradient(space, input);
    const SharedDecimation level = DecimateShared(
        space.faces, {input.start, input.end}, target, input.fixed_vertices);
    Mesh coarse_mesh;
    coarse_mesh.faces = level.faces;
    coarse_mesh.positions = level.shapes[0];
    const ShellSpace coarse_space(coarse_mesh, Topology::Build(coarse_mesh),
                                  space.material);
    GeodesicInput coarse_input;
    coarse_input.start = level.shapes[0];
    coarse_input.end = level.shapes[1];
    coarse_input.steps = input.steps;
    coarse_input.pin_gauge = input.pin_gauge;
    coarse_input.newton_from = input.newton_from;
    coarse_input.linear_solver = input.linear_solver;
    coarse_input.lm = input.lm;
    std::vector<int> coarse_of(n, -1);
    for (int i = 0; i < level.num_vertices(); ++i) {
      coarse_of[level.survivors[i]] = i;
    }
    for (int v : input.fixed_vertices) {
      if (coarse_of[v] >= 0) coarse_input.fixed_vertices.push_back(coarse_of[v]);
    }
    std::sort(coarse_input.fixed_vertices.begin(),
              coarse_input.fixed_vertices.end());
    SolverSettings coarse_settings = settings;
    coarse_settings.gradient_tolerance =
        std::max(settings.gradient_tolerance, multires.coarse_gradient_tolerance);
    coarse_settings.progress_label = settings.progress_label + " coarse";
    MultiresolutionSettings next = multires;
    next.levels = multires.levels - 1;
    MultiresolutionResult coarse = SolveGeodesicMultiresolution(
        coarse_space, coarse_input, coarse_settings, next);
    result.levels = std::move(coarse.levels);
    // Prolongation of each inner shape from the nearer end.
    const auto prolong_clock = std::chrono::steady_clock::now();
    const Prolongation from_start(space.faces, input.start, level,
                                  level.shapes[0]);
    const Prolongation from_end(space.faces, input.end, level, level.shapes[1]);
    const int K = input.steps;
    const ShellPath linear = LinearPath(input.start, input.end, K);
    fine.initial = linear;
    for (int k = 1; k < K; ++k) {
      const Prolongation& p = 2 * k <= K ? from_start : from_end;
      fine.initial[k] = p.Apply(coarse.geodesic.path[k]);
      for (int v : input.fixed_vertices) fine.initial[k].row(v) = linear[k].row(v);
    }
    prolongation_seconds = SecondsSince(prolong_clock);
  }
  const auto fine_clock = std::chrono::steady_clock::now();
  result.geodesic = SolveGeodesic(space, fine, settings);
  const double tolerance =
      settings.gradient_tolerance *
      std::max(1.0, coarsen ? fine.reference_gradient
                            : result.geodesic.initial_gradient);
  result.levels.push_back(LevelReport(
      space, result.geodesic,
      prolongation_seconds + SecondsSince(fine_clock), tolerance));
  return result;
}

}  // namespace shellspace
