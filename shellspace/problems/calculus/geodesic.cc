#include "shellspace/problems/calculus/geodesic.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "shellspace/cost_functions/deformation_energy_residuals.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/cost_functions/shell/shell_space_renumbering.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/geometry/vertex_flags.h"
#include "shellspace/problems/calculus/stiff_vertex_elimination.h"
#include "shellspace/problems/calculus/vertex_relaxation.h"
#include "shellspace/runtime/parallel_for.h"
#include "shellspace/solvers/rigid_gauge.h"

namespace shellspace {

double StepEnergyRatio(const std::vector<double>& step_energies) {
  if (step_energies.size() < 2) return 1;
  const auto [lo, hi] =
      std::minmax_element(step_energies.begin(), step_energies.end());
  if (*hi <= 0) return 1;
  if (*lo <= 0) return HUGE_VAL;
  return *hi / *lo;
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

// max |g| over the free coordinates of inner shape `shape` (the mask's
// vertices left out, or the gauge's pinned coordinates).
double FreeMaxNorm(const GeodesicInput& input,
                   const std::vector<char>& is_fixed, const Positions& shape,
                   const Eigen::VectorXd& g) {
  if (!input.fixed_vertices.empty()) return UnflaggedMaxNorm(g, is_fixed);
  if (input.pin_gauge) return GaugeFreeMaxNorm(MakeRigidGauge(shape), g);
  return g.cwiseAbs().maxCoeff();
}

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
  const std::vector<char> is_fixed =
      VertexFlags(space.num_vertices, input.fixed_vertices);
  std::vector<double> norm(K - 1, 0.0);
  const bool ok = ForEachInnerShapeGradient(
      space, path, threads, [&](int i, const Eigen::VectorXd& g) {
        norm[i] = FreeMaxNorm(input, is_fixed, path[i + 1], g);
      });
  if (!ok) return 0;
  return *std::max_element(norm.begin(), norm.end());
}

}  // namespace

double PathGradientNorm(const ShellSpace& space, const GeodesicInput& input,
                        const ShellPath& path, int threads) {
  if (path.size() < 3) return 0;
  return PathGradientMaxNorm(space, input, path, threads);
}

double GradientRoundOff(const ShellSpace& space, const GeodesicInput& input,
                        const ShellPath& path, int threads) {
  const int K = static_cast<int>(path.size()) - 1;
  if (K < 2) return 0;
  const std::vector<char> is_fixed =
      VertexFlags(space.num_vertices, input.fixed_vertices);
  std::vector<Eigen::VectorXd> base(K - 1);
  if (!ForEachInnerShapeGradient(
          space, path, threads,
          [&](int i, const Eigen::VectorXd& g) { base[i] = g; })) {
    return 0;
  }
  std::mt19937 signs(20261207u);  // fixed seed: the same probes every run
  double floor = 0;
  for (int probe = 0; probe < kRoundOffProbes; ++probe) {
    ShellPath moved = path;
    for (int k = 1; k < K; ++k) {
      for (int v = 0; v < space.num_vertices; ++v) {
        if (is_fixed[v]) continue;
        for (int c = 0; c < 3; ++c) {
          double& x = moved[k](v, c);
          x = std::nextafter(x, (signs() & 1u) != 0 ? HUGE_VAL : -HUGE_VAL);
        }
      }
    }
    std::vector<double> change(K - 1, 0.0);
    if (!ForEachInnerShapeGradient(
            space, moved, threads, [&](int i, const Eigen::VectorXd& g) {
              change[i] = FreeMaxNorm(input, is_fixed, path[i + 1],
                                      Eigen::VectorXd(g - base[i]));
            })) {
      continue;
    }
    floor = std::max(floor, *std::max_element(change.begin(), change.end()));
  }
  return floor;
}

double LinearPathGradient(const ShellSpace& space, const GeodesicInput& input) {
  if (input.steps < 2) return 0;
  return PathGradientMaxNorm(space, input,
                             LinearPath(input.start, input.end, input.steps),
                             /*threads=*/2);
}

namespace {

// One geodesic solve as a pipeline of named stages (SolveGeodesic):
//   Start        the initial path (MakeGeodesicInitialPath, or the given one);
//   Prepare      the space the engine's stages run in (renumbered for
//                locality) or Ceres' problem;
//   Globalise    LM stages and exact Newton attempts, LM alone once the
//                attempts are spent, and where that stops short with
//                budget left, projected-Newton stages with exact Newton
//                probes (GeodesicGlobalisation);
//   Finish       the path mapped back to the caller's numbering;
//   Report       E_K, its steps, the smallest triangle, converged.
// Every stage's iterations are counted in result.iterations and listed in
// result.stages. The globalising stages (LM, projected Newton) never raise
// E_K; an exact Newton probe of the projected phase that stops short hands
// on its iterate with the smallest gradient max norm
// (PathNewtonSettings::keep_best_iterate), never a larger gradient than it
// received. A solve that ends unconverged reports the path with the
// smallest gradient it met (Finish).
class GeodesicSolve {
 public:
  GeodesicSolve(const ShellSpace& space, const GeodesicInput& input,
                const SolverSettings& settings, GeodesicResult* result)
      : space_(space), input_(input), settings_(settings), result_(*result) {}

  void Start();
  void Prepare();
  void Globalise();
  void Finish();
  void Report();

 private:
  // The engine settings shared by every stage it runs.
  PathNewtonSettings EngineStage(const std::string& label);
  // LM down to `relative` x max(1, g_0) (or the tolerance), from where the
  // path is.
  void RunLmStage(double relative, double hand_over_contraction);
  void RunEngineLm(double target, double hand_over_contraction,
                   GeodesicStage* stage);
  void RunCeresLm(double relative, GeodesicStage* stage);
  // A Newton stage of the engine on `model`: the trust region, to the
  // tolerance, as a basin probe if `probe`.
  PathNewtonReport RunNewtonStage(HessianModel model, bool probe);
  // The projected phase: projected-Newton stages, each followed by an exact
  // probe, until converged, stopped, the budget is spent or a round lowers
  // the gradient by less than half.
  void RunProjectedPhase();
  // At a stall: goes back to the best iterate, measures the gradient's
  // round-off there (GradientRoundOff) and counts the solve converged if
  // the gradient is within it.
  void AcceptRoundOffFloor();
  // The path with the smallest gradient any stage ended on, if that is
  // smaller than the current one (best_iterate_restored).
  void RestoreBestIterate();
  // A sweep of RelaxPeakVertices on the path (GeodesicInput::
  // relax_peak_vertices), recorded as a stage.
  void RelaxPeakVerticesStage();
  // The stiff vertices of the initial path brought to equilibrium once
  // before the first stage, as every trial's are: the first step's gradient
  // contraction (the early hand-over to Newton) then compares two
  // eliminated paths, not the raw start with an eliminated trial.
  void EliminateAtStart();
  void Record(GeodesicStage stage);
  // The input with the mask in the solve space's numbering.
  GeodesicInput SolveInput() const {
    GeodesicInput solve_input = input_;
    solve_input.fixed_vertices = *solve_mask_;
    return solve_input;
  }
  bool Converged() const {
    return result_.final_gradient <= tolerance_ || at_round_off_;
  }

  const ShellSpace& space_;
  const GeodesicInput& input_;
  const SolverSettings& settings_;
  GeodesicResult& result_;
  double g0_ = 0, tolerance_ = 0;
  int budget_ = 0;  // iterations left of settings.max_iterations
  bool engine_lm_ = false;
  std::optional<RenumberedShellSpace> renumbered_;
  const ShellSpace* solve_space_ = nullptr;
  const std::vector<int>* solve_mask_ = nullptr;
  ShellPath* solve_path_ = nullptr;
  ShellPath renumbered_path_;
  std::vector<int> renumbered_mask_;
  std::unique_ptr<ceres::Problem> problem_;  // Ceres' LM stages only
  PathLinearSolvers solvers_;
  bool lm_failed_ = false, stopped_ = false, lm_handed_over_ = false;
  double lm_damping_ = 0, resume_damping_ = 0;
  bool newton_ran_ = false;  // a Newton stage (attempt or probe) has run
  bool projected_phase_ = false;  // RunProjectedPhase has begun
  bool at_round_off_ = false;     // AcceptRoundOffFloor found it within
  // The path with the smallest gradient max norm after a stage, and that
  // norm (Finish).
  ShellPath best_path_;
  double best_gradient_ = HUGE_VAL;
  StiffVertexElimination elimination_;
};

void GeodesicSolve::Start() {
  if (input_.steps < 1) {
    throw InputError(
        "geodesic: the number of steps K must be at least 1, got " +
        std::to_string(input_.steps));
  }
  if (input_.initial.empty()) {
    result_.path = MakeGeodesicInitialPath(
        space_, input_.start, input_.end, input_.steps, input_.fixed_vertices,
        input_.init, settings_, &result_.init);
  } else {
    result_.path = input_.initial;
    result_.init.requested = input_.init;
    result_.init.reason = "given";
  }
  if (static_cast<int>(result_.path.size()) != input_.steps + 1) {
    throw InputError("geodesic: the initial path must have K + 1 = " +
                     std::to_string(input_.steps + 1) + " shapes, got " +
                     std::to_string(result_.path.size()));
  }
  result_.path.front() = input_.start;
  result_.path.back() = input_.end;
}

void GeodesicSolve::Prepare() {
  result_.final_gradient = PathGradientMaxNorm(space_, input_, result_.path,
                                               settings_.num_threads);
  g0_ = input_.reference_gradient >= 0 ? input_.reference_gradient
                                       : result_.final_gradient;
  tolerance_ = settings_.gradient_tolerance * std::max(1.0, g0_);
  result_.gradient_target = tolerance_;
  result_.initial_gradient = g0_;
  budget_ = settings_.max_iterations;
  // Slivers of the input: the engine's LM, whose trials respect the step
  // limit (kStepMinAreaFraction); Ceres' LM may crush a sliver and crawl.
  engine_lm_ =
      ChooseGeodesicLm(input_.lm, input_.linear_solver,
                       PathUnknowns(space_, input_)) == GeodesicLm::kEngine ||
      (input_.lm == GeodesicLm::kAuto &&
       !FindSliverFaces(Mesh{input_.start, space_.faces}).faces.empty());
  solve_space_ = &space_;
  solve_mask_ = &input_.fixed_vertices;
  solve_path_ = &result_.path;
  if (engine_lm_) {
    // The engine's stages run in the space renumbered for locality
    // (shell_space_renumbering.h: on the GOAST cactus about 10 % less CPU);
    // the path is mapped back in Finish.
    renumbered_ = RenumberForLocality(space_);
    for (const Positions& shape : result_.path) {
      renumbered_path_.push_back(renumbered_->ToRenumbered(shape));
    }
    renumbered_mask_ = renumbered_->ToRenumbered(input_.fixed_vertices);
    solve_space_ = &renumbered_->space;
    solve_mask_ = &renumbered_mask_;
    solve_path_ = &renumbered_path_;
  } else {
    // Ceres' stages, and the engine's stages after them, work on the
    // caller's path, whose coordinates Ceres' problem holds; built once.
    problem_ = std::make_unique<ceres::Problem>();
    BuildPathProblem(space_, input_, &result_.path, problem_.get());
  }
  if (input_.eliminate_stiff_vertices) {
    const std::vector<int> stiff =
        FindStiffVertices(solve_space_->faces, (*solve_path_)[0], *solve_mask_,
                          kStiffAngleDegrees);
    if (!stiff.empty() &&
        stiff.size() <= kMaxStiffFraction * solve_space_->num_vertices) {
      elimination_ =
          StiffVertexElimination(*solve_space_, stiff, kStepMinAreaFraction);
      result_.stiff_vertices = static_cast<int>(stiff.size());
    }
  }
  if (input_.keep_best_iterate) {
    best_gradient_ = result_.final_gradient;
    best_path_ = *solve_path_;
  }
}

PathNewtonSettings GeodesicSolve::EngineStage(const std::string& label) {
  PathNewtonSettings stage;
  stage.linear_solver = input_.linear_solver;
  stage.gradient_tolerance = tolerance_;
  stage.num_threads = settings_.num_threads;
  stage.min_area_fraction = kStepMinAreaFraction;
  stage.progress = settings_.progress;
  stage.progress_label = settings_.progress_label + " " + label;
  stage.stop = settings_.stop;
  stage.solvers = &solvers_;
  stage.keep_best_iterate = false;  // RunNewtonStage: exact stages only
  stage.renumbering = renumbered_ ? &*renumbered_ : nullptr;
  stage.elimination = elimination_.empty() ? nullptr : &elimination_;
  return stage;
}

void GeodesicSolve::Record(GeodesicStage stage) {
  stage.final_gradient = result_.final_gradient;
  result_.iterations += stage.iterations;
  budget_ -= stage.iterations;
  result_.stages.push_back(stage);
  if (result_.final_gradient < best_gradient_ && input_.keep_best_iterate) {
    best_gradient_ = result_.final_gradient;
    best_path_ = *solve_path_;
  }
}

void GeodesicSolve::RunEngineLm(double target, double hand_over_contraction,
                                GeodesicStage* stage) {
  PathNewtonSettings lm = EngineStage("lm");
  lm.globalisation = NewtonSettings::Globalisation::kLevenbergMarquardt;
  lm.model = HessianModel::kGaussNewton;
  lm.gradient_tolerance = target;
  lm.max_steps = std::max(0, budget_);
  lm.hand_over_contraction = hand_over_contraction;
  // After a Newton stage stopped short, with another attempt to follow: LM
  // stalled for kLmStallSteps steps hands over to it instead of spending
  // the budget.
  if (newton_ran_ && target > tolerance_) lm.stall_steps = kLmStallSteps;
  if (resume_damping_ > 0) lm.lm_initial = resume_damping_;
  const PathNewtonReport report =
      PolishPathNewton(*solve_space_, *solve_mask_, lm, solve_path_);
  stage->termination = report.stop_reason;
  stage->iterations = report.steps;
  stage->solver = report.linear_solver;
  stage->restored_best = report.restored_best;
  result_.final_gradient = report.final_gradient;
  lm_failed_ = report.stop == NewtonStop::kInfeasibleStart ||
               report.stop == NewtonStop::kAssemblyFailed;
  if (lm_failed_) result_.failure = report.stop_reason;
  stopped_ = report.stop == NewtonStop::kStopped;
  lm_handed_over_ = report.stop == NewtonStop::kHandedOver;
  lm_damping_ = report.final_damping;
}

void GeodesicSolve::RunCeresLm(double relative, GeodesicStage* stage) {
  SolverSettings lm = settings_;
  lm.gradient_tolerance = relative;
  lm.max_iterations = std::max(0, budget_);
  result_.summary = SolveWithSettings(problem_.get(), lm, g0_);
  stage->termination =
      ceres::TerminationTypeToString(result_.summary.termination_type);
  stage->solver = "ceres";
  if (!result_.summary.iterations.empty()) {
    stage->iterations =
        static_cast<int>(result_.summary.iterations.size()) - 1;
    result_.final_gradient =
        result_.summary.iterations.back().gradient_max_norm;
  }
  lm_failed_ = result_.summary.termination_type == ceres::FAILURE;
  if (lm_failed_) result_.failure = result_.summary.message;
  stopped_ = StoppedByRequest(result_.summary);
}

void GeodesicSolve::RunLmStage(double relative, double hand_over_contraction) {
  GeodesicStage stage;
  const double lm_relative = std::max(settings_.gradient_tolerance, relative);
  lm_handed_over_ = false;
  if (engine_lm_) {
    RunEngineLm(lm_relative * std::max(1.0, g0_), hand_over_contraction,
                &stage);
  } else {
    RunCeresLm(lm_relative, &stage);
  }
  Record(stage);
}

PathNewtonReport GeodesicSolve::RunNewtonStage(HessianModel model,
                                               bool probe) {
  const bool projected = model == HessianModel::kProjected;
  PathNewtonSettings newton = EngineStage(projected ? "projected" : "newton");
  newton.max_steps = std::min(newton.max_steps, budget_);
  if (engine_lm_ || projected ||
      input_.newton == GeodesicNewton::kTrustRegion) {
    // The trust region with Steihaug-Toint CG: the inexact Newton step
    // wherever CG stays inside the region, steps to its boundary (along
    // negative curvature on the exact Hessian) elsewhere.
    newton.globalisation = NewtonSettings::Globalisation::kTrustRegion;
    newton.model = model;
    newton.max_steps = std::min(4 * newton.max_steps, budget_);
  }
  if (probe) newton.basin_ratio = kNewtonBasinRatio;
  if (!projected && !probe) newton.stall_steps = kNewtonStallSteps;
  // The probes of the projected phase keep their best iterate; the exact
  // attempts between LM stages hand on their last one, as LM resumes from
  // there.
  newton.keep_best_iterate =
      !projected && projected_phase_ && input_.keep_best_iterate;
  if (projected) {
    // Away from the geodesic, projected Newton converges linearly where
    // terms are not convex: the stage ends at a tenth of the gradient it
    // received (or a step that cuts it tenfold), and an exact probe tries
    // the quadratic finish from there; a stage whose gradient has not
    // halved in kLmStallSteps steps ends too.
    newton.gradient_tolerance =
        std::max(tolerance_, kProjectedStageContraction * result_.final_gradient);
    newton.hand_over_contraction = input_.newton_contraction;
    newton.stall_steps = kLmStallSteps;
    newton.max_steps = budget_;
  }
  const PathNewtonReport report =
      PolishPathNewton(*solve_space_, *solve_mask_, newton, solve_path_);
  newton_ran_ = true;
  result_.newton.Append(report);
  result_.final_gradient = report.final_gradient;
  stopped_ = stopped_ || report.stop == NewtonStop::kStopped;
  GeodesicStage stage;
  stage.method = projected ? GeodesicStage::Method::kProjectedNewton
                           : GeodesicStage::Method::kNewton;
  stage.solver = report.linear_solver;
  stage.iterations = report.steps;
  stage.termination = report.stop_reason;
  stage.restored_best = report.restored_best;
  Record(stage);
  return report;
}

void GeodesicSolve::RelaxPeakVerticesStage() {
  if (!input_.relax_peak_vertices || Converged() || stopped_ ||
      budget_ <= 0) {
    return;
  }
  const VertexRelaxationReport relaxed =
      RelaxPeakVertices(*solve_space_, *solve_mask_, kRelaxationFraction,
                        kRelaxationNewtonSteps, settings_.num_threads,
                        solve_path_);
  if (relaxed.vertices == 0) return;
  result_.final_gradient = PathGradientMaxNorm(
      *solve_space_, SolveInput(), *solve_path_, settings_.num_threads);
  GeodesicStage stage;
  stage.method = GeodesicStage::Method::kVertexRelaxation;
  stage.iterations = 1;
  stage.solver = "vertex-newton";
  char text[160];
  std::snprintf(text, sizeof text,
                "%d vertices, %d Newton steps; E_K %.10g -> %.10g",
                relaxed.vertices, relaxed.newton_steps, relaxed.energy_before,
                relaxed.energy_after);
  stage.termination = text;
  if (settings_.progress) {
    std::fprintf(stderr, "%s relax %s |grad| %.3e\n",
                 settings_.progress_label.c_str(), text,
                 result_.final_gradient);
  }
  Record(stage);
}

void GeodesicSolve::EliminateAtStart() {
  if (elimination_.empty()) return;
  const StiffEliminationReport report =
      elimination_.Solve(kEliminationNewtonSteps, tolerance_, solve_path_);
  if (report.steps == 0) return;
  result_.final_gradient = PathGradientMaxNorm(
      *solve_space_, SolveInput(), *solve_path_, settings_.num_threads);
}

void GeodesicSolve::RunProjectedPhase() {
  projected_phase_ = true;
  while (!Converged() && !stopped_ && budget_ > 0) {
    RelaxPeakVerticesStage();
    if (Converged() || budget_ <= 0) return;
    const double round_start = result_.final_gradient;
    const std::optional<double> energy_start =
        TryPathEnergy(*solve_space_, *solve_path_);
    const PathNewtonReport projected =
        RunNewtonStage(HessianModel::kProjected, /*probe=*/false);
    if (Converged() || stopped_ || budget_ <= 0) return;
    if (projected.stop == NewtonStop::kInfeasibleStart ||
        projected.stop == NewtonStop::kAssemblyFailed) {
      result_.failure = projected.stop_reason;
      return;
    }
    RunNewtonStage(HessianModel::kExact, /*probe=*/true);
    if (Converged() || stopped_) return;
    const std::optional<double> energy_end =
        TryPathEnergy(*solve_space_, *solve_path_);
    const bool energy_fell =
        energy_start && energy_end &&
        *energy_end < (1 - kRoundEnergyProgress) * *energy_start;
    if (!(result_.final_gradient <= kRoundProgress * round_start) &&
        !energy_fell) {
      char text[240];
      std::snprintf(text, sizeof text,
                    "no progress: a projected-Newton stage and an exact "
                    "Newton probe left |grad| at %.3g from %.3g and E_K "
                    "within %.0e of its value",
                    result_.final_gradient, round_start,
                    kRoundEnergyProgress);
      result_.stall = text;
      AcceptRoundOffFloor();
      return;
    }
  }
}

void GeodesicSolve::AcceptRoundOffFloor() {
  RestoreBestIterate();  // the floor is measured where the report will be
  result_.gradient_round_off = GradientRoundOff(
      *solve_space_, SolveInput(), *solve_path_, settings_.num_threads);
  if (!(result_.final_gradient <= result_.gradient_round_off)) return;
  at_round_off_ = true;
  result_.converged_at_round_off = true;
  if (settings_.progress) {
    std::fprintf(stderr,
                 "%s |grad| %.3e is within the gradient's round-off %.3e "
                 "(one-ulp moves of the positions change it that much): "
                 "converged\n",
                 settings_.progress_label.c_str(), result_.final_gradient,
                 result_.gradient_round_off);
  }
}

void GeodesicSolve::Globalise() {
  EliminateAtStart();
  double threshold = input_.newton_from;
  // The early hand-over (newton_contraction) is tried once: its Newton
  // stage is a probe of the basin, and where it stops short, LM goes on
  // down to the threshold as if it had not been tried.
  bool early = engine_lm_ && input_.newton_contraction > 0;
  for (int attempt = 0;;) {
    const bool newton = threshold > settings_.gradient_tolerance &&
                        attempt < GeodesicInput::kMaxNewtonAttempts;
    RunLmStage(newton ? threshold : settings_.gradient_tolerance,
               newton && early ? input_.newton_contraction : 0.0);
    if (!newton && !Converged() && !lm_failed_ && !stopped_ && budget_ > 0 &&
        input_.newton_from > 0 &&
        input_.globalisation == GeodesicGlobalisation::kProjectedNewton) {
      // The exact attempts are spent and LM alone stopped short of the
      // tolerance with budget left (Ceres' cost no longer decreasing, or
      // the engine's LM rejecting its steps): projected Newton goes on.
      RunProjectedPhase();
      return;
    }
    if (!newton || Converged() || lm_failed_ || stopped_ || budget_ <= 0) {
      return;
    }
    const bool probe = lm_handed_over_;
    early = false;
    const PathNewtonReport report = RunNewtonStage(HessianModel::kExact, probe);
    if (report.converged || budget_ <= 0 || stopped_) return;
    if (probe) {  // LM on to the threshold; not an attempt
      resume_damping_ = lm_damping_;
      continue;
    }
    resume_damping_ = 0;
    ++attempt;
    threshold *= 0.1;  // not yet in Newton's basin: more LM first
    RelaxPeakVerticesStage();
    if (Converged() || budget_ <= 0) return;
  }
}

void GeodesicSolve::RestoreBestIterate() {
  if (best_path_.empty() || !(best_gradient_ < result_.final_gradient)) return;
  for (int k = 1; k < input_.steps; ++k) (*solve_path_)[k] = best_path_[k];
  result_.final_gradient = best_gradient_;
  result_.best_iterate_restored = true;
}

void GeodesicSolve::Finish() {
  result_.elimination_newton_steps = elimination_.newton_steps();
  // Unconverged: the path with the smallest gradient the solve met, not
  // its last (whose E_K may be lower, its gradient larger).
  if (!Converged()) RestoreBestIterate();
  if (renumbered_) {
    for (int k = 1; k < input_.steps; ++k) {
      result_.path[k] = renumbered_->ToOriginal(renumbered_path_[k]);
    }
  }
  result_.converged = Converged();
}

void GeodesicSolve::Report() {
  result_.path_energy =
      PathEnergy(space_, result_.path, &result_.step_energies);
  result_.step_energy_ratio = StepEnergyRatio(result_.step_energies);
  result_.uneven_steps = result_.step_energy_ratio > kUnevenStepEnergyRatio;
  result_.smallest_face_area = SmallestFaceAreaRatio(space_.faces, result_.path);
  result_.collapsing_faces =
      result_.smallest_face_area.ratio < kCollapsingFaceAreaRatio;
  result_.gradient_peak = LargestPathGradient(
      space_, input_.fixed_vertices, result_.path, settings_.num_threads);
}

}  // namespace

GeodesicResult SolveGeodesic(const ShellSpace& space,
                             const GeodesicInput& input,
                             const SolverSettings& settings) {
  GeodesicResult result;
  GeodesicSolve solve(space, input, settings, &result);
  solve.Start();
  if (input.steps >= 2) {
    solve.Prepare();
    solve.Globalise();
    solve.Finish();
  } else {
    result.converged = true;  // K = 1: no unknowns
  }
  solve.Report();
  return result;
}

GradientPeak LargestPathGradient(const ShellSpace& space,
                                 const std::vector<int>& fixed_vertices,
                                 const ShellPath& path, int threads) {
  const int K = static_cast<int>(path.size()) - 1;
  GradientPeak peak;
  if (K < 2) return peak;
  const std::vector<char> is_fixed =
      VertexFlags(space.num_vertices, fixed_vertices);
  std::vector<GradientPeak> per_shape(K - 1);
  const bool ok = ForEachInnerShapeGradient(
      space, path, threads, [&](int i, const Eigen::VectorXd& g) {
        GradientPeak& p = per_shape[i];
        for (int v = 0; v < space.num_vertices; ++v) {
          const double value = g.segment<3>(3 * v).cwiseAbs().maxCoeff();
          if (!is_fixed[v] && value > p.value) p = {value, i + 1, v};
        }
      });
  if (!ok) return peak;
  for (const GradientPeak& p : per_shape) {
    if (p.value > peak.value) peak = p;
  }
  return peak;
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
