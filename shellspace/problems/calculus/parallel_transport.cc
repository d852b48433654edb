#include "shellspace/problems/calculus/parallel_transport.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/runtime/blas_threads.h"
#include "shellspace/problems/calculus/geodesic.h"

namespace shellspace {

namespace {

// The midpoint of `start` and `end`: the middle shape of the 2-step
// geodesic between them, from their average (masked vertices stay there);
// its solve's iterations added to *iterations.
Positions RungMidpoint(const ShellSpace& space, const Positions& start,
                       const Positions& end,
                       const std::vector<int>& fixed_vertices,
                       const SolverSettings& settings, int* iterations) {
  GeodesicInput midpoint_input = GeodesicInput::Between(start, end, 2);
  midpoint_input.fixed_vertices = fixed_vertices;
  midpoint_input.initial = {start, 0.5 * (start + end), end};
  GeodesicResult midpoint_solve =
      SolveGeodesic(space, midpoint_input, settings);
  *iterations += midpoint_solve.iterations;
  return std::move(midpoint_solve.path[1]);
}

// One rung of the ladder, from p at s_{k-1} to s_k: the best of its tries
// (the rung from p, then from p halved towards s_{k-1}, ... until one is
// solved), its EXP residual and the scale it is relative to.
struct TransportRung {
  TransportResult::Rung rung;
  Positions best;
  double best_scale = 1;
  double best_residual = HUGE_VAL;
  bool stopped = false;  // a stop request inside the rung
};

// Rung k of the ladder along `path` from the transported shape `p`.
TransportRung SolveRung(const ShellSpace& space, const ShellPath& path,
                        size_t k, const Positions& p,
                        const std::vector<int>& fixed_vertices,
                        const SolverSettings& settings) {
  TransportRung out;
  TransportResult::Rung& rung = out.rung;
  for (int halvings = 0; halvings <= kMaxRungHalvings; ++halvings) {
    const int divisor = 1 << halvings;
    // The rung from p' = s_{k-1} + (p - s_{k-1}) / divisor.
    const Positions start =
        divisor == 1 ? p : Positions(path[k - 1] + (p - path[k - 1]) / divisor);
    const Positions midpoint =
        RungMidpoint(space, start, path[k], fixed_vertices, settings,
                     &rung.midpoint_iterations);
    if (settings.stop.stop_requested()) {
      out.stopped = true;
      break;
    }
    // Besides 2 m_k - s_{k-1}, start from s_k + (p_{k-1} - s_{k-1}): the
    // previous rung's variation at the new base point (the same point in
    // Euclidean space; the better one of the two on curved paths).
    const Positions carried = path[k] + (start - path[k - 1]);
    SolverSettings exp_settings = settings;
    if (halvings < kMaxRungHalvings) {
      exp_settings.max_iterations =
          std::min(exp_settings.max_iterations, kRungFallbackLmIterations);
    }
    const ExpStepResult step =
        ExpStep(space, path[k - 1], midpoint, StepDirection::kForward,
                fixed_vertices, exp_settings, &carried);
    if (StoppedByRequest(step.summary)) {
      out.stopped = true;
      break;
    }
    rung.newton_steps += step.newton_steps;
    rung.lm_iterations += step.lm_iterations;
    const bool better = step.solved ||
                        step.relative_residual < rung.relative_residual ||
                        halvings == 0;
    if (better) {
      rung.solved = step.solved;
      rung.relative_residual = step.relative_residual;
      rung.method = step.method;
      rung.divisor = divisor;
      out.best = divisor == 1
                     ? step.shape
                     : Positions(path[k] + divisor * (step.shape - path[k]));
      out.best_scale =
          EnergyGradient(space, path[k - 1], midpoint, ShellSide::kDeformed)
              .cwiseAbs()
              .maxCoeff();
      out.best_residual = step.residual_norm;
    }
    if (step.solved) break;
  }
  return out;
}

}  // namespace

TransportResult ParallelTransport(const ShellSpace& space,
                                  const ShellPath& path,
                                  const Positions& variation, double epsilon,
                                  const std::vector<int>& fixed_vertices,
                                  const SolverSettings& settings) {
  if (!(epsilon > 0)) throw InputError(
        "parallel transport: the step epsilon must be positive, got " +
        std::to_string(epsilon));
  if (path.size() < 2)
    throw InputError("transport needs a path of >= 2 shapes");
  // One BLAS thread for the rungs' midpoints and EXP steps (as ExpStep):
  // one-shape factorisations, where a second OpenBLAS thread spins.
  const ScopedBlasThreads blas(1);
  TransportResult result;
  result.variations.push_back(variation);
  Positions p = path[0] + epsilon * variation;
  result.shapes.push_back(p);
  for (size_t k = 1; k < path.size(); ++k) {
    if (settings.stop.stop_requested()) {  // the rungs done so far
      result.all_solved = false;
      break;
    }
    const TransportRung rung =
        SolveRung(space, path, k, p, fixed_vertices, settings);
    if (rung.stopped) {  // an unfinished rung is not kept, nor called solved
      result.all_solved = false;
      break;
    }
    p = rung.best;
    result.exp_residuals.push_back(rung.best_residual /
                                   std::max(rung.best_scale, 1e-300));
    result.all_solved = result.all_solved && rung.rung.solved;
    result.rungs.push_back(rung.rung);
    result.shapes.push_back(p);
    result.variations.push_back((p - path[k]) / epsilon);
    if (settings.progress) {
      std::fprintf(stderr, "%s rung %zu of %zu  relative EXP residual %.3e\n",
                   settings.progress_label.c_str(), k, path.size() - 1,
                   result.exp_residuals.back());
    }
  }
  return result;
}

}  // namespace shellspace
