#include "shellspace/problems/calculus/geodesic.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>

#include "shellspace/cost_functions/deformation_energy_residuals.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/cost_functions/shell/shell_space_renumbering.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/runtime/parallel_for.h"
#include "shellspace/solvers/rigid_gauge.h"

namespace shellspace {

std::optional<double> TryPathEnergy(const ShellSpace& space,
                                    const ShellPath& path,
                                    std::vector<double>* step_energies,
                                    ElementFailure* failure) {
  const int steps = static_cast<int>(path.size()) - 1;
  double sum = 0;
  if (step_energies) step_energies->clear();
  for (int k = 1; k <= steps; ++k) {
    DeformationEnergy w;
    if (!TryEvaluateDeformationEnergy(space, path[k - 1], path[k], &w,
                                      failure)) {
      if (failure) {
        failure->description = "W[s_" + std::to_string(k - 1) + ", s_" +
                               std::to_string(k) + "]: " +
                               failure->description;
      }
      return std::nullopt;
    }
    if (step_energies) step_energies->push_back(w.total);
    sum += w.total;
  }
  return steps * sum;
}

double PathEnergy(const ShellSpace& space, const ShellPath& path,
                  std::vector<double>* step_energies) {
  ElementFailure failure;
  const std::optional<double> energy =
      TryPathEnergy(space, path, step_energies, &failure);
  if (!energy) {
    throw InputError("path energy: " + failure.description + " is degenerate");
  }
  return *energy;
}

double StepEnergyRatio(const std::vector<double>& step_energies) {
  if (step_energies.size() < 2) return 1;
  const auto [lo, hi] =
      std::minmax_element(step_energies.begin(), step_energies.end());
  if (*hi <= 0) return 1;
  if (*lo <= 0) return HUGE_VAL;
  return *hi / *lo;
}

ShellPath LinearPath(const Positions& a, const Positions& b, int steps) {
  ShellPath path;
  for (int k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    path.push_back((1 - t) * a + t * b);
  }
  return path;
}

namespace {

// Holds the masked vertices constant, or pins the rigid gauge.
void FixVerticesOrGauge(Positions* shape, const std::vector<int>& fixed,
                        ceres::Problem* problem, bool pin_gauge = true) {
  for (int v : fixed) problem->SetParameterBlockConstant(shape->data() + 3 * v);
  if (fixed.empty() && pin_gauge) PinRigidMotions(shape, problem);
}

// The LM problem of E_K over the inner shapes of `path` (K >= 2): each
// W[s_{k-1}, s_k] with weight K, masked vertices constant, or the gauge
// pinned.
void BuildPathProblem(const ShellSpace& space, const GeodesicInput& input,
                      ShellPath* path, ceres::Problem* problem) {
  const int K = input.steps;
  for (int k = 1; k <= K; ++k) {
    const ShellArgument ref = k == 1
                                  ? ShellArgument::Fixed((*path)[0])
                                  : ShellArgument::Variable(&(*path)[k - 1]);
    const ShellArgument def = k == K ? ShellArgument::Fixed((*path)[K])
                                     : ShellArgument::Variable(&(*path)[k]);
    AddDeformationEnergy(space, ref, def, K, problem);
  }
  for (int k = 1; k < K; ++k) {
    FixVerticesOrGauge(&(*path)[k], input.fixed_vertices, problem,
                       input.pin_gauge);
  }
}

}  // namespace

GeodesicLm ChooseGeodesicLm(GeodesicLm choice, PathLinearSolver linear_solver,
                            int unknowns) {
  if (choice != GeodesicLm::kAuto) return choice;
  return ChooseLinearSolver(linear_solver, unknowns) ==
                 PathLinearSolver::kBlockJacobi
             ? GeodesicLm::kEngine
             : GeodesicLm::kCeres;
}

namespace {

// The reduced unknowns of the path problem: (K - 1) x the free coordinates
// of one inner shape (3 x unmasked vertices, or 3n - 6 with the gauge).
int PathUnknowns(const ShellSpace& space, const GeodesicInput& input) {
  const int per_shape =
      input.fixed_vertices.empty()
          ? 3 * space.num_vertices - 6
          : 3 * (space.num_vertices -
                 static_cast<int>(input.fixed_vertices.size()));
  return (input.steps - 1) * per_shape;
}

}  // namespace

namespace {

// max |G_k| over the coordinates of the inner shapes that BuildPathProblem
// leaves free, G_k = K (D_2 W[s_{k-1}, s_k] + D_1 W[s_k, s_{k+1}]): the
// unmasked vertices, or without a mask the gauge of PinRigidMotions at
// `path` (GaugeFreeMaxNorm), or every coordinate if the gauge is not pinned.
// The gradient_max_norm of that Ceres problem, without building it (on the
// cactus x4 it has 1.1 M residual blocks). 0 if an element is degenerate
// (as GradientMaxNorm when Ceres' evaluation fails).
double PathGradientMaxNorm(const ShellSpace& space, const GeodesicInput& input,
                           const ShellPath& path, int threads) {
  const int K = static_cast<int>(path.size()) - 1;
  std::vector<char> is_fixed(space.num_vertices, 0);
  for (int v : input.fixed_vertices) is_fixed[v] = 1;
  std::vector<double> norm(K - 1, 0.0);
  const bool ok = ForEachInnerShapeGradient(
      space, path, threads, [&](int i, const Eigen::VectorXd& g) {
        if (!input.fixed_vertices.empty()) {
          for (int v = 0; v < space.num_vertices; ++v) {
            if (!is_fixed[v]) {
              norm[i] =
                  std::max(norm[i], g.segment<3>(3 * v).cwiseAbs().maxCoeff());
            }
          }
        } else if (input.pin_gauge) {
          norm[i] = GaugeFreeMaxNorm(MakeRigidGauge(path[i + 1]), g);
        } else {
          norm[i] = g.cwiseAbs().maxCoeff();
        }
      });
  if (!ok) return 0;
  return *std::max_element(norm.begin(), norm.end());
}

}  // namespace

bool TryInnerShapeGradient(const ShellSpace& space, const ShellPath& path,
                           int k, Eigen::VectorXd* gradient) {
  const int K = static_cast<int>(path.size()) - 1;
  Eigen::VectorXd incoming, outgoing;
  if (!TryEnergyGradient(space, path[k - 1], path[k], ShellSide::kDeformed,
                         &incoming) ||
      !TryEnergyGradient(space, path[k], path[k + 1], ShellSide::kReference,
                         &outgoing)) {
    return false;
  }
  *gradient = double(K) * (incoming + outgoing);
  return true;
}

bool ForEachInnerShapeGradient(
    const ShellSpace& space, const ShellPath& path, int threads,
    const std::function<void(int, const Eigen::VectorXd&)>& use) {
  const int K = static_cast<int>(path.size()) - 1;
  if (K < 2) return true;
  // Term by term, W[s_k, s_{k+1}] once for both of its inner shapes (the
  // ends need no gradient): K element passes instead of 2 (K - 1), the
  // same digits as TryInnerShapeGradient.
  std::vector<Eigen::VectorXd> of_reference(K), of_deformed(K);
  std::vector<char> ok(K, 1);
  ParallelFor(K, threads, [&](int k) {
    ok[k] = TryEnergyGradients(space, path[k], path[k + 1],
                               k > 0 ? &of_reference[k] : nullptr,
                               k + 1 < K ? &of_deformed[k] : nullptr);
  });
  if (!std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; })) {
    return false;
  }
  ParallelFor(K - 1, threads, [&](int i) {
    use(i, double(K) * (of_deformed[i] + of_reference[i + 1]));
  });
  return true;
}

double PathGradientNorm(const ShellSpace& space, const GeodesicInput& input,
                        const ShellPath& path, int threads) {
  if (path.size() < 3) return 0;
  return PathGradientMaxNorm(space, input, path, threads);
}

double LinearPathGradient(const ShellSpace& space, const GeodesicInput& input) {
  if (input.steps < 2) return 0;
  return PathGradientMaxNorm(space, input,
                             LinearPath(input.start, input.end, input.steps),
                             /*threads=*/2);
}

GeodesicResult SolveGeodesic(const ShellSpace& space,
                             const GeodesicInput& input,
                             const SolverSettings& settings) {
  if (input.steps < 1) {
    throw InputError(
        "geodesic: the number of steps K must be at least 1, got " +
        std::to_string(input.steps));
  }
  GeodesicResult result;
  if (input.initial.empty()) {
    result.path = MakeGeodesicInitialPath(space, input.start, input.end,
                                          input.steps, input.fixed_vertices,
                                          input.init, settings, &result.init);
  } else {
    result.path = input.initial;
    result.init.requested = input.init;
    result.init.reason = "given";
  }
  if (static_cast<int>(result.path.size()) != input.steps + 1) {
    throw InputError("geodesic: the initial path must have K + 1 = " +
                     std::to_string(input.steps + 1) + " shapes, got " +
                     std::to_string(result.path.size()));
  }
  result.path.front() = input.start;
  result.path.back() = input.end;
  const int K = input.steps;
  if (K >= 2) {
    result.final_gradient =
        PathGradientMaxNorm(space, input, result.path, settings.num_threads);
    const double g0 = input.reference_gradient >= 0 ? input.reference_gradient
                                                    : result.final_gradient;
    const double tolerance = settings.gradient_tolerance * std::max(1.0, g0);
    result.gradient_target = tolerance;
    // Iterations left of settings.max_iterations (LM iterations and Newton
    // steps of all stages).
    int lm_left = settings.max_iterations;
    // Slivers of the input: the engine's LM, whose trials respect the step
    // limit (kStepMinAreaFraction); Ceres' LM may crush a sliver and crawl.
    const bool engine_lm =
        ChooseGeodesicLm(input.lm, input.linear_solver,
                         PathUnknowns(space, input)) == GeodesicLm::kEngine ||
        (input.lm == GeodesicLm::kAuto &&
         !FindSliverFaces(Mesh{input.start, space.faces}).faces.empty());
    // The engine's stages run in the space renumbered for locality
    // (shell_space_renumbering.h: on the GOAST cactus about 10 % less CPU)
    // and the path is mapped back at the end; Ceres' stages, and a Newton
    // finish after them, work on the caller's path, whose coordinates
    // Ceres' problem holds.
    std::optional<RenumberedShellSpace> renumbered;
    const ShellSpace* solve_space = &space;
    const std::vector<int>* solve_mask = &input.fixed_vertices;
    ShellPath* solve_path = &result.path;
    ShellPath renumbered_path;
    std::vector<int> renumbered_mask;
    if (engine_lm) {
      renumbered = RenumberForLocality(space);
      for (const Positions& shape : result.path) {
        renumbered_path.push_back(renumbered->ToRenumbered(shape));
      }
      renumbered_mask = renumbered->ToRenumbered(input.fixed_vertices);
      solve_space = &renumbered->space;
      solve_mask = &renumbered_mask;
      solve_path = &renumbered_path;
    }
    const RenumberedShellSpace* renumbering =
        renumbered ? &*renumbered : nullptr;
    // Ceres' LM problem, built once for all its stages (only if Ceres runs
    // them: the engine needs no residual blocks).
    std::unique_ptr<ceres::Problem> problem;
    if (!engine_lm) {
      problem = std::make_unique<ceres::Problem>();
      BuildPathProblem(space, input, &result.path, problem.get());
    }
    bool lm_failed = false, lm_stopped = false, lm_handed_over = false;
    // After a basin probe LM resumes with the damping it had reached, so
    // that it goes on as if it had not been interrupted.
    double lm_damping = 0, resume_damping = 0;
    // The engine's stages share their block-Jacobi solver: the slices'
    // pattern analysis is done once (every stage still factorises afresh).
    PathLinearSolvers solvers;
    bool newton_ran = false;  // a Newton stage (attempt or probe) has run
    // LM down to `relative` (or the tolerance), continuing from where it is.
    const auto run_lm = [&](double relative, double hand_over_contraction) {
      GeodesicStage stage;
      const double lm_tolerance =
          std::max(settings.gradient_tolerance, relative);
      if (engine_lm) {
        PathNewtonSettings lm;
        lm.globalisation = NewtonSettings::Globalisation::kLevenbergMarquardt;
        lm.model = HessianModel::kGaussNewton;
        lm.linear_solver = input.linear_solver;
        lm.gradient_tolerance = lm_tolerance * std::max(1.0, g0);
        lm.max_steps = std::max(0, lm_left);
        lm.num_threads = settings.num_threads;
        lm.min_area_fraction = kStepMinAreaFraction;
        lm.hand_over_contraction = hand_over_contraction;
        // After a Newton stage stopped short, with another attempt to
        // follow: LM stalled for kLmStallSteps steps hands over to it
        // instead of spending the budget.
        if (newton_ran && relative > settings.gradient_tolerance) {
          lm.stall_steps = kLmStallSteps;
        }
        if (resume_damping > 0) lm.lm_initial = resume_damping;
        lm.progress = settings.progress;
        lm.progress_label = settings.progress_label + " lm";
        lm.stop = settings.stop;
        lm.solvers = &solvers;
        lm.renumbering = renumbering;
        const PathNewtonReport report =
            PolishPathNewton(*solve_space, *solve_mask, lm, solve_path);
        stage.termination = report.stop_reason;
        stage.iterations = report.steps;
        stage.solver = report.linear_solver;
        result.final_gradient = report.final_gradient;
        lm_failed = report.stop == NewtonStop::kInfeasibleStart ||
                    report.stop == NewtonStop::kAssemblyFailed;
        if (lm_failed) result.failure = report.stop_reason;
        lm_stopped = report.stop == NewtonStop::kStopped;
        lm_handed_over = report.stop == NewtonStop::kHandedOver;
        lm_damping = report.final_damping;
      } else {
        SolverSettings lm = settings;
        lm.gradient_tolerance = lm_tolerance;
        lm.max_iterations = std::max(0, lm_left);
        result.summary = SolveWithSettings(problem.get(), lm, g0);
        stage.termination =
            ceres::TerminationTypeToString(result.summary.termination_type);
        stage.solver = "ceres";
        if (!result.summary.iterations.empty()) {
          stage.iterations =
              static_cast<int>(result.summary.iterations.size()) - 1;
          result.final_gradient =
              result.summary.iterations.back().gradient_max_norm;
        }
        lm_failed = result.summary.termination_type == ceres::FAILURE;
        if (lm_failed) result.failure = result.summary.message;
        lm_stopped = StoppedByRequest(result.summary);
      }
      stage.final_gradient = result.final_gradient;
      result.iterations += stage.iterations;
      lm_left -= stage.iterations;
      result.stages.push_back(stage);
    };
    double threshold = input.newton_from;
    // The early hand-over (newton_contraction) is tried once: its Newton
    // stage is a probe of the basin, and where it stops short, LM goes on
    // down to the threshold as if it had not been tried.
    bool early = engine_lm && input.newton_contraction > 0;
    for (int attempt = 0;;) {
      const bool newton = threshold > settings.gradient_tolerance &&
                          attempt < GeodesicInput::kMaxNewtonAttempts;
      lm_handed_over = false;
      run_lm(newton ? threshold : settings.gradient_tolerance,
             newton && early ? input.newton_contraction : 0.0);
      if (!newton || result.final_gradient <= tolerance || lm_failed ||
          lm_stopped) {
        break;
      }
      if (lm_left <= 0) break;  // the budget is spent
      PathNewtonSettings polish;
      polish.linear_solver = input.linear_solver;
      polish.gradient_tolerance = tolerance;
      polish.num_threads = settings.num_threads;
      polish.progress = settings.progress;
      polish.progress_label = settings.progress_label + " newton";
      polish.max_steps = std::min(polish.max_steps, lm_left);
      if (engine_lm || input.newton == GeodesicNewton::kTrustRegion) {
        // The trust region on the exact Hessian with Steihaug-Toint CG: the
        // inexact Newton step wherever CG stays inside the region, steps
        // to its boundary along negative curvature elsewhere.
        polish.globalisation = NewtonSettings::Globalisation::kTrustRegion;
        polish.model = HessianModel::kExact;
        polish.max_steps = std::min(4 * polish.max_steps, lm_left);
      }
      polish.min_area_fraction = kStepMinAreaFraction;
      const bool probe = lm_handed_over;
      if (probe) polish.basin_ratio = kNewtonBasinRatio;
      early = false;
      polish.stop = settings.stop;
      polish.solvers = &solvers;
      polish.renumbering = renumbering;
      const PathNewtonReport report =
          PolishPathNewton(*solve_space, *solve_mask, polish, solve_path);
      newton_ran = true;
      result.newton.Append(report);
      result.iterations += report.steps;
      lm_left -= report.steps;
      result.final_gradient = report.final_gradient;
      GeodesicStage stage;
      stage.method = GeodesicStage::Method::kNewton;
      stage.solver = report.linear_solver;
      stage.iterations = report.steps;
      stage.final_gradient = report.final_gradient;
      stage.termination = report.stop_reason;
      result.stages.push_back(stage);
      if (report.converged || lm_left <= 0 ||
          report.stop == NewtonStop::kStopped) {
        break;
      }
      if (probe) {  // LM on to the threshold; not an attempt
        resume_damping = lm_damping;
        continue;
      }
      resume_damping = 0;
      ++attempt;
      threshold *= 0.1;  // not yet in Newton's basin: more LM first
    }
    if (renumbered) {
      for (int k = 1; k < K; ++k) {
        result.path[k] = renumbered->ToOriginal(renumbered_path[k]);
      }
    }
    result.initial_gradient = g0;
    result.converged = result.final_gradient <= tolerance;
  } else {
    result.converged = true;  // K = 1: no unknowns
  }
  result.path_energy = PathEnergy(space, result.path, &result.step_energies);
  result.step_energy_ratio = StepEnergyRatio(result.step_energies);
  result.uneven_steps = result.step_energy_ratio > kUnevenStepEnergyRatio;
  result.smallest_face_area = SmallestFaceAreaRatio(space.faces, result.path);
  result.collapsing_faces =
      result.smallest_face_area.ratio < kCollapsingFaceAreaRatio;
  return result;
}

FaceAreaRatio SmallestFaceAreaRatio(const Faces& faces, const ShellPath& path) {
  FaceAreaRatio smallest;
  const int K = static_cast<int>(path.size()) - 1;
  const auto area = [&](const Positions& x, int f) {
    const Eigen::Vector3d a = x.row(faces(f, 0)), b = x.row(faces(f, 1)),
                          c = x.row(faces(f, 2));
    return 0.5 * (b - a).cross(c - a).norm();
  };
  for (int f = 0; f < faces.rows(); ++f) {
    const double reference = area(path[0], f);
    if (!(reference > 0)) continue;
    for (int k = 1; k < K; ++k) {
      const double ratio = area(path[k], f) / reference;
      if (ratio < smallest.ratio) smallest = {ratio, k, f};
    }
  }
  return smallest;
}

Positions SolveWeightedMidpoint(const ShellSpace& space, const Positions& a,
                                const Positions& b, double weight_a,
                                double weight_b, const Positions& initial,
                                const std::vector<int>& fixed_vertices,
                                const SolverSettings& settings,
                                ceres::Solver::Summary* summary) {
  Positions s = initial;
  ceres::Problem problem;
  if (weight_a > 0) {
    AddDeformationEnergy(space, ShellArgument::Fixed(a),
                         ShellArgument::Variable(&s), weight_a, &problem);
  }
  if (weight_b > 0) {
    AddDeformationEnergy(space, ShellArgument::Variable(&s),
                         ShellArgument::Fixed(b), weight_b, &problem);
  }
  FixVerticesOrGauge(&s, fixed_vertices, &problem);
  const ceres::Solver::Summary local = SolveWithSettings(&problem, settings);
  if (summary) *summary = local;
  return s;
}

Positions GeodesicAtTime(const ShellSpace& space, const ShellPath& path,
                         double t, const std::vector<int>& fixed_vertices,
                         const SolverSettings& settings) {
  if (!(t >= 0 && t <= 1)) throw InputError("time t must lie in [0, 1]");
  const int K = static_cast<int>(path.size()) - 1;
  const int k = std::min(static_cast<int>(std::floor(t * K)), K);
  const double lambda = t * K - k;
  if (k == K || lambda <= 0) return path[k];
  const Positions initial = (1 - lambda) * path[k] + lambda * path[k + 1];
  return SolveWeightedMidpoint(space, path[k], path[k + 1], 1 - lambda, lambda,
                               initial, fixed_vertices, settings);
}

}  // namespace shellspace
