#include "shellspace/problems/calculus/exponential_map.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "shellspace/cost_functions/gradient_field_residual.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/connected_components.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/geometry/vertex_flags.h"
#include "shellspace/problems/calculus/exp_step_continuation.h"
#include "shellspace/problems/calculus/exp_step_newton.h"
#include "shellspace/problems/calculus/rotation_blend_path.h"
#include "shellspace/runtime/blas_threads.h"
#include "shellspace/solvers/rigid_gauge.h"

namespace shellspace {

namespace {
// Newton's target for max |F| relative to max |D_2 W[s_{k-1}, s_k]|, the
// level below which a stalled Newton run (round-off) is still accepted, and
// its step limit.
constexpr double kExpNewtonTolerance = 1e-11;
constexpr double kExpNewtonAccept = kExpStepAcceptance;
constexpr int kMaxExpNewtonSteps = 20;
// a to b is a rigid motion (of each connected component) when, after the
// best rigid fit, no vertex is farther than this fraction of b's
// bounding-box diagonal from its place.
constexpr double kRigidStepTolerance = 1e-12;

// One EXP step's equation and what its stages share.
struct ExpStepContext {
  const ShellSpace& space;
  const Positions& a;
  const Positions& b;
  const std::vector<int>& fixed_vertices;
  const std::vector<char>& is_fixed;  // per vertex: in fixed_vertices
  const ExpStepEquation& equation;
  double scale;  // max |c| over the unknown vertices
};

// *result := `shape`, solved by Newton with max |F| = residual.
void SetSolvedByNewton(Positions shape, double residual, double scale,
                       const std::string& message, ExpStepResult* result) {
  result->shape = std::move(shape);
  result->residual_norm = residual;
  result->relative_residual = residual / scale;
  result->solved = true;
  result->method = ExpStepResult::Method::kNewton;
  result->summary.termination_type = ceres::CONVERGENCE;
  result->summary.message = message;
}

// A rigid step (a to b a rigid motion M of each connected component to
// round-off, no mask): the step beyond b is M(b) exactly -- W[b, M(b)] = 0
// at its minimum and D_2 W[a, b] = 0 -- with no iteration. (Backward, a =
// s_{k+1} and b = s_k: the same motion continued.)
bool TryRigidStep(const ExpStepContext& step, ExpStepResult* result) {
  if (!step.fixed_vertices.empty()) return false;
  const ComponentwiseRigidMotion motion = FitRigidMotions(
      step.a, step.b,
      ConnectedComponents(step.space.faces, step.space.num_vertices));
  const Positions moved = motion.Apply(step.a);
  const double diameter =
      (step.b.colwise().maxCoeff() - step.b.colwise().minCoeff()).norm();
  if ((moved - step.b).rowwise().norm().maxCoeff() >
      kRigidStepTolerance * diameter) {
    return false;
  }
  Positions shape = motion.Apply(step.b);
  const double residual = ExpResidualMaxNorm(step.equation, shape);
  SetSolvedByNewton(std::move(shape), residual, 1, 
                    "rigid step: the rigid motion continued", result);
  result->residual_scale = 0;
  result->relative_residual = 0;
  return true;
}

// Newton from the guess left its basin: follow the roots of t c + D W from
// b (t = 0) to t = 1 (exp_step_continuation.h). True if solved.
bool SolveByContinuation(const ExpStepContext& step,
                         const Positions& plain_guess,
                         const SolverSettings& settings,
                         ExpStepResult* result) {
  if (settings.stop.stop_requested()) return false;
  ExpContinuationSettings continuation;
  continuation.tolerance = kExpNewtonTolerance * step.scale;
  continuation.accept = kExpNewtonAccept * step.scale;
  continuation.intermediate_tolerance = kExpNewtonAccept * step.scale;
  Positions continued;
  const ExpContinuationReport report = SolveExpStepByContinuation(
      step.equation, plain_guess, continuation, &continued);
  result->newton_steps += report.newton_steps;
  result->continuation_substeps = report.substeps;
  if (settings.progress) {
    std::fprintf(stderr,
                 "%s EXP by continuation in the load: %.4g of 1 reached in "
                 "%d load steps, %d Newton steps (%s)\n",
                 settings.progress_label.c_str(), report.load,
                 report.substeps, report.newton_steps,
                 report.stop_reason.c_str());
  }
  if (!report.solved) return false;
  SetSolvedByNewton(std::move(continued), report.final_residual, step.scale,
                    "Newton on F by continuation in the load (" +
                        std::to_string(report.substeps) + " load steps)",
                    result);
  return true;
}

// The last resort: least squares of the per-vertex residuals F_v by sparse
// LM, from result->shape (or b if that has degenerate triangles).
void SolveByLeastSquares(const ExpStepContext& step,
                         const SolverSettings& settings,
                         ExpStepResult* result) {
  const ShellSpace& space = step.space;
  GradientFieldCache cache(space, step.b, step.equation.unknown_side,
                           &result->shape);
  cache.PrepareForEvaluation(false, true);
  if (!cache.ok()) {
    result->shape = step.b;
    for (int v : step.fixed_vertices) {
      result->shape.row(v) = 2 * step.b.row(v) - step.a.row(v);
    }
    cache.PrepareForEvaluation(false, true);
  }
  const std::vector<char>& is_fixed = step.is_fixed;
  std::vector<std::vector<int>> incident(space.num_vertices);
  for (int e = 0; e < static_cast<int>(cache.elements().size()); ++e) {
    const auto& element = cache.elements()[e];
    for (int k = 0; k < element.count; ++k) {
      incident[element.vertices[k]].push_back(e);
    }
  }
  ceres::Problem::Options options;
  options.evaluation_callback = &cache;
  ceres::Problem problem(options);
  for (int v = 0; v < space.num_vertices; ++v) {
    if (is_fixed[v] || incident[v].empty()) continue;
    VertexGradientResidual* residual = VertexGradientResidual::Create(
        &cache, v, step.equation.constant.data() + 3 * v, incident[v]);
    std::vector<double*> blocks;
    for (int w : residual->stencil())
      blocks.push_back(result->shape.data() + 3 * w);
    problem.AddResidualBlock(residual, nullptr, blocks);
  }
  for (int v : step.fixed_vertices) {
    double* block = result->shape.data() + 3 * v;
    if (problem.HasParameterBlock(block))
      problem.SetParameterBlockConstant(block);
  }
  if (step.fixed_vertices.empty()) {
    PinRigidMotions(&result->shape, &problem,
                    ConnectedComponents(space.faces, space.num_vertices));
  }
  SolverSettings step_settings = settings;
  step_settings.gradient_tolerance =
      std::min(settings.gradient_tolerance, 1e-10);
  step_settings.initial_trust_region_radius =
      1e16;  // Gauss-Newton from the start
  result->summary = SolveWithSettings(&problem, step_settings);
  result->residual_norm = ExpResidualMaxNorm(step.equation, result->shape);
  result->relative_residual = result->residual_norm / step.scale;
  result->solved = result->relative_residual <= kExpNewtonAccept;
  result->method = ExpStepResult::Method::kLevenbergMarquardt;
  result->lm_iterations =
      std::max(0, static_cast<int>(result->summary.iterations.size()) - 1);
}

}  // namespace

ExpStepResult ExpStep(const ShellSpace& space, const Positions& a,
                      const Positions& b, StepDirection direction,
                      const std::vector<int>& fixed_vertices,
                      const SolverSettings& settings,
                      const Positions* alternative_start) {
  // One BLAS thread: the step's sparse LU (and the LM fallback's Cholesky)
  // factorise one-shape systems whose dense fronts are small, where a second
  // OpenBLAS thread mostly spins (the faces transport and PCA rows of
  // bench/workflow_bench.sh spent 180 s of sys time in 240 s with two).
  const ScopedBlasThreads blas(1);
  const bool forward = direction == StepDirection::kForward;
  // Constant part: forward D_2 W[a, b]; backward D_1 W[b, a].
  const Eigen::VectorXd constant =
      forward ? EnergyGradient(space, a, b, ShellSide::kDeformed)
              : EnergyGradient(space, b, a, ShellSide::kReference);
  const ExpStepEquation equation{
      space, b, forward ? ShellSide::kDeformed : ShellSide::kReference,
      constant, fixed_vertices};
  const std::vector<char> is_fixed =
      VertexFlags(space.num_vertices, fixed_vertices);
  // max |c| over the unknown vertices
  const double scale = std::max(1e-300, UnflaggedMaxNorm(constant, is_fixed));
  const ExpStepContext step{space,    a,        b,    fixed_vertices,
                            is_fixed, equation, scale};

  ExpStepResult result;
  if (TryRigidStep(step, &result)) return result;
  result.residual_scale = scale;
  result.shape = 2 * b - a;
  if (alternative_start != nullptr) {
    Positions alternative = *alternative_start;
    for (int v : fixed_vertices) alternative.row(v) = result.shape.row(v);
    if (ExpResidualMaxNorm(equation, alternative) <
        ExpResidualMaxNorm(equation, result.shape)) {
      result.shape = alternative;
    }
  }
  // Newton on F with the exact Jacobian first (exp_step_newton.h); where it
  // does not get there, the continuation, then sparse LM on |F|^2 from the
  // same initial guess (where Newton fails, its iterates wander: LM from
  // them did worse on the finger's last transport rung).
  Positions trial = result.shape;
  const ExpNewtonReport newton = SolveExpStepNewton(
      equation,
      ExpNewtonStopping{kExpNewtonTolerance * scale, kExpNewtonAccept * scale,
                        kMaxExpNewtonSteps},
      &trial);
  result.newton_steps = newton.steps;
  if (newton.final_gradient <= kExpNewtonAccept * scale) {
    SetSolvedByNewton(std::move(trial), newton.final_gradient, scale,
                      "Newton on F: " + newton.stop_reason, &result);
    return result;
  }
  if (settings.max_iterations <= 0) {  // Newton only: no fallbacks
    result.residual_norm = ExpResidualMaxNorm(equation, result.shape);
    result.relative_residual = result.residual_norm / scale;
    result.solved = false;
    result.method = ExpStepResult::Method::kNewton;
    result.summary.termination_type = ceres::NO_CONVERGENCE;
    result.summary.message = "Newton on F did not converge (no fallback)";
    return result;
  }
  if (SolveByContinuation(step, result.shape, settings, &result)) {
    return result;
  }
  SolveByLeastSquares(step, settings, &result);
  return result;
}
namespace {

// ShootWithReport without the path energy.
ShootResult ShootSteps(const ShellSpace& space, const Positions& s0,
                       const Positions& s1, int steps, StepDirection direction,
                       const std::vector<int>& fixed_vertices,
                       const SolverSettings& settings) {
  if (steps < 1) {
    throw InputError("shooting: the number of steps must be at least 1, got " +
                     std::to_string(steps));
  }
  ShootResult result;
  // Forward: s_2, s_3, ... after (s0, s1); backward: s_{-1}, s_{-2}, ...
  // before (s0, s1), built in reverse order.
  const bool forward = direction == StepDirection::kForward;
  ShellPath& path = result.path;
  path = forward ? ShellPath{s0, s1} : ShellPath{s1, s0};
  for (int k = 2; k <= steps; ++k) {
    if (settings.stop.stop_requested()) {  // the steps done so far
      result.stopped = true;
      break;
    }
    // Besides 2 b - a, the rotation-blend continuation of a -> b
    // (RotationBlendShapes at t = 2): a bend or a twist carried on as one.
    const std::vector<Positions> turned =
        RotationBlendShapes(space.faces, space.topology, path[k - 2],
                            path[k - 1], {2.0}, fixed_vertices);
    ExpStepResult step =
        ExpStep(space, path[k - 2], path[k - 1], direction, fixed_vertices,
                settings, turned.empty() ? nullptr : &turned.front());
    if (StoppedByRequest(step.summary)) {  // an unfinished step
      result.stopped = true;
      break;
    }
    if (settings.progress) {
      std::fprintf(stderr, "%s step %d of %d  max |F| %.3e  %s\n",
                   settings.progress_label.c_str(), k, steps,
                   step.residual_norm,
                   ceres::TerminationTypeToString(step.summary.termination_type));
    }
    path.push_back(std::move(step.shape));
    step.shape = Positions();
    result.exp_steps.push_back(std::move(step));
  }
  if (!forward) std::reverse(path.begin(), path.end());
  return result;
}

}  // namespace

ShootResult ShootWithReport(const ShellSpace& space, const Positions& s0,
                            const Positions& s1, int steps,
                            StepDirection direction,
                            const std::vector<int>& fixed_vertices,
                            const SolverSettings& settings) {
  ShootResult result =
      ShootSteps(space, s0, s1, steps, direction, fixed_vertices, settings);
  result.path_energy = PathEnergy(space, result.path, &result.step_energies);
  return result;
}

ShellPath Shoot(const ShellSpace& space, const Positions& s0,
                const Positions& s1, int steps, StepDirection direction,
                const std::vector<int>& fixed_vertices,
                const SolverSettings& settings,
                std::vector<ceres::Solver::Summary>* summaries) {
  ShootResult result =
      ShootSteps(space, s0, s1, steps, direction, fixed_vertices, settings);
  if (summaries) {
    for (const ExpStepResult& step : result.exp_steps) {
      summaries->push_back(step.summary);
    }
  }
  return std::move(result.path);
}

Positions ExpK(const ShellSpace& space, const Positions& s0,
               const Positions& variation, int steps,
               const std::vector<int>& fixed_vertices,
               const SolverSettings& settings) {
  const Positions s1 = s0 + variation / steps;
  return Shoot(space, s0, s1, steps, StepDirection::kForward, fixed_vertices,
               settings)
      .back();
}

Positions LogOfGeodesic(const ShellPath& geodesic) {
  if (geodesic.size() < 2) {
    throw InputError("logarithm: a geodesic needs at least 2 shapes");
  }
  const int steps = static_cast<int>(geodesic.size()) - 1;
  return steps * (geodesic[1] - geodesic[0]);
}

Positions LogK(const ShellSpace& space, const Positions& a, const Positions& b,
               int steps, const std::vector<int>& fixed_vertices,
               const SolverSettings& settings, GeodesicResult* geodesic,
               const ShellPath* initial) {
  GeodesicInput input = GeodesicInput::Between(a, b, steps);
  input.fixed_vertices = fixed_vertices;
  if (initial != nullptr) input.initial = *initial;  // ends replaced
  GeodesicResult result = SolveGeodesic(space, input, settings);
  const Positions log = LogOfGeodesic(result.path);
  if (geodesic) *geodesic = std::move(result);
  return log;
}

}  // namespace shellspace
