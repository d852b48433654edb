#include "shellspace/reports/path_reports.h"

#include <algorithm>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/geometry/named_values.h"
#include "shellspace/reports/relative_gradient.h"
#include "shellspace/reports/shape_reports.h"

namespace shellspace {

int LmIterations(const ceres::Solver::Summary& summary) {
  return std::max(0, static_cast<int>(summary.iterations.size()) - 1);
}

JsonObject PathEnergySplitJson(const ShellSpace& space, const ShellPath& path) {
  double membrane = 0, bending = 0;
  const double steps = path.size() > 1 ? path.size() - 1.0 : 0.0;
  for (size_t k = 1; k < path.size(); ++k) {
    const DeformationEnergy w =
        EvaluateDeformationEnergy(space, path[k - 1], path[k]);
    membrane += steps * w.membrane;
    bending += steps * (w.total - w.membrane);
  }
  return EnergySplitJson(membrane, bending);
}

std::vector<JsonObject> GeodesicStages(const GeodesicResult& result) {
  std::vector<JsonObject> stages;
  for (const GeodesicStage& stage : result.stages) {
    using Method = GeodesicStage::Method;
    static constexpr NamedValue<Method> kNames[] = {
        {Method::kLevenbergMarquardt, "levenberg-marquardt"},
        {Method::kNewton, "newton"},
        {Method::kProjectedNewton, "projected-newton"},
        {Method::kVertexRelaxation, "vertex-relaxation"}};
    stages.push_back(
        JsonObject()
            .Add("method", NameOf(kNames, stage.method))
            .Add("solver", stage.solver)
            .Add("iterations", stage.iterations)
            .Add("final_gradient_norm", stage.final_gradient)
            .Add("best_iterate_restored", stage.restored_best)
            .Add("termination", stage.termination));
  }
  return stages;
}

const char* ExpMethodName(ExpStepResult::Method method) {
  using Method = ExpStepResult::Method;
  static constexpr NamedValue<Method> kNames[] = {
      {Method::kNewton, "newton"},
      {Method::kLevenbergMarquardt, "levenberg-marquardt"}};
  return NameOf(kNames, method);
}

std::string ExpStepTermination(const ExpStepResult& step) {
  const std::string how = std::string(ExpMethodName(step.method)) + ": " +
                          step.summary.message;
  return (step.solved ? "solved (" : "not solved (") + how + ")";
}

std::vector<JsonObject> ExpStepStages(const ShootResult& result) {
  std::vector<JsonObject> stages;
  for (const ExpStepResult& step : result.exp_steps) {
    const int lm = LmIterations(step.summary);
    stages.push_back(
        JsonObject()
            .Add("method", ExpMethodName(step.method))
            .Add("solved", step.solved)
            .Add("newton_steps", step.newton_steps)
            .Add("lm_iterations", lm)
            .Add("iterations", step.newton_steps + lm)
            .Add("residual", step.residual_norm)
            .Add("relative_residual", step.relative_residual)
            .Add("termination", ExpStepTermination(step)));
  }
  return stages;
}

JsonObject InitialPathJson(const InitialPathReport& init) {
  JsonObject json;
  json.Add("requested", std::string(GeodesicInitName(init.requested)))
      .Add("used", std::string(GeodesicInitName(init.used)))
      .Add("reason", init.reason)
      .Add("rotation_degrees", init.rotation_degrees)
      .Add("rigid_motion_removed", init.rigid_motion_removed)
      .Add("linear_smallest_area_ratio", init.linear.smallest_area_ratio)
      .Add("linear_turned_faces", init.linear.turned_faces)
      .Add("ltheta_iterations", init.ltheta_iterations)
      .Add("ltheta_unconverged_frames", init.ltheta_unconverged)
      .Add("seconds", init.seconds);
  return json;
}

JsonObject ProlongationJson(const ProlongationCheck& check) {
  JsonObject json;
  json.Add("checked", check.checked)
      .Add("used", check.used)
      .Add("rotation_guided", check.rotation_guided)
      .Add("prolongated_energy", check.prolongated_energy)
      .Add("initial_energy", check.initial_energy)
      .Add("turned_faces", check.turned_faces)
      .Add("initial_turned_faces", check.initial_turned_faces)
      .Add("smallest_face_area_ratio", check.smallest_face_area.ratio)
      .Add("reason", check.reason);
  return json;
}

JsonObject GeodesicJson(const GeodesicResult& result) {
  const double relative =
      RelativeGradientNorm(result.final_gradient, result.initial_gradient);
  JsonObject json;
  json.Add("path_energy", result.path_energy)
      .Add("step_energies", result.step_energies)
      .Add("iterations", result.iterations)
      .Add("initial_gradient_norm", result.initial_gradient)
      .Add("final_gradient_norm", result.final_gradient)
      .Add("relative_gradient_norm", relative)
      .Add("converged", result.converged)
      .Add("converged_at_round_off", result.converged_at_round_off)
      .Add("gradient_round_off", result.gradient_round_off)
      .Add("termination", !result.stall.empty() ? result.stall
                          : result.stages.empty()
                              ? std::string("no unknowns")
                              : result.stages.back().termination)
      .Add("stages", GeodesicStages(result))
      .Add("best_iterate_restored", result.best_iterate_restored)
      .Add("newton_steps", result.newton.steps)
      .Add("newton_seconds", result.newton.seconds)
      .Add("factorizations", result.newton.factorizations)
      .Add("time_coupled_factorizations",
           result.newton.time_coupled_factorizations)
      .Add("cg_iterations", result.newton.cg_iterations)
      .Add("linear_solver", result.newton.linear_solver.empty()
                                ? std::string("none")
                                : result.newton.linear_solver)
      .Add("cg_not_converged", result.newton.cg_not_converged)
      .Add("newton_shifted_steps", result.newton.shifted_steps)
      .Add("newton_boundary_steps", result.newton.boundary_steps)
      .Add("newton_negative_curvature_steps",
           result.newton.negative_curvature_steps)
      .Add("newton_rejected_trials", result.newton.rejected_trials)
      .Add("newton_shifted_preconditioners",
           result.newton.shifted_preconditioners)
      .Add("stiff_vertices", result.stiff_vertices)
      .Add("elimination_newton_steps", result.elimination_newton_steps)
      .Add("init", InitialPathJson(result.init))
      .Add("step_energy_ratio", result.step_energy_ratio)
      .Add("uneven_steps", result.uneven_steps)
      .Add("smallest_face_area_ratio", result.smallest_face_area.ratio)
      .Add("smallest_face_area_shape", result.smallest_face_area.shape)
      .Add("smallest_face_area_face", result.smallest_face_area.face)
      .Add("collapsing_faces", result.collapsing_faces)
      .Add("largest_gradient", result.gradient_peak.value)
      .Add("largest_gradient_shape", result.gradient_peak.shape)
      .Add("largest_gradient_vertex", result.gradient_peak.vertex)
      .Add("frames", static_cast<int>(result.path.size()));
  return json;
}

std::vector<JsonObject> MultiresolutionJson(
    const MultiresolutionResult& result) {
  return JsonArrayOf(result.levels, [](const MultiresolutionLevel& level) {
    return JsonObject()
        .Add("vertices", level.vertices)
        .Add("faces", level.faces)
        .Add("iterations", level.iterations)
        .Add("path_energy", level.path_energy)
        .Add("final_gradient_norm", level.final_gradient)
        .Add("converged", level.converged)
        .Add("seconds", level.seconds);
  });
}

ShootTotals TotalsOf(const ShootResult& result) {
  ShootTotals totals;
  for (const ExpStepResult& step : result.exp_steps) {
    totals.iterations += step.newton_steps + LmIterations(step.summary);
    totals.max_residual = std::max(totals.max_residual, step.residual_norm);
    totals.max_relative_residual =
        std::max(totals.max_relative_residual, step.relative_residual);
    totals.converged &= step.solved;
  }
  totals.converged &= !result.stopped;  // a stopped shot did not get there
  return totals;
}

JsonObject ShootJson(const ShootResult& result) {
  const ShootTotals totals = TotalsOf(result);
  JsonObject json;
  json.Add("path_energy", result.path_energy)
      .Add("step_energies", result.step_energies)
      .Add("iterations", totals.iterations)
      .Add("max_exp_residual", totals.max_residual)
      .Add("max_relative_residual", totals.max_relative_residual)
      .Add("converged", totals.converged)
      .Add("stages", ExpStepStages(result))
      .Add("frames", static_cast<int>(result.path.size()));
  return json;
}

JsonObject TransportJson(const TransportResult& result, double epsilon) {
  std::vector<double> norms;
  for (const Positions& xi : result.variations) {
    norms.push_back(xi.cwiseAbs().maxCoeff());
  }
  std::vector<JsonObject> rungs;
  int iterations = 0;
  for (size_t k = 0; k < result.rungs.size(); ++k) {
    const TransportResult::Rung& rung = result.rungs[k];
    iterations +=
        rung.midpoint_iterations + rung.newton_steps + rung.lm_iterations;
    rungs.push_back(JsonObject()
                        .Add("rung", static_cast<int>(k + 1))
                        .Add("solved", rung.solved)
                        .Add("relative_residual", rung.relative_residual)
                        .Add("method", ExpMethodName(rung.method))
                        .Add("epsilon_divisor", rung.divisor)
                        .Add("newton_steps", rung.newton_steps)
                        .Add("lm_iterations", rung.lm_iterations)
                        .Add("midpoint_iterations", rung.midpoint_iterations));
  }
  JsonObject json;
  json.Add("variation_max_norms", norms)
      .Add("exp_residuals", result.exp_residuals)
      .Add("converged", result.all_solved)
      .Add("iterations", iterations)
      .Add("rungs", rungs)
      .Add("epsilon", epsilon)
      .Add("frames", static_cast<int>(result.shapes.size()));
  return json;
}

JsonObject SplineJson(JsonObject head, const SplineResult& result,
                      double seconds) {
  head.Add("spline_energy", result.spline_energy)
      .Add("data_energy", result.data_energy)
      .Add("objective", result.objective)
      .Add("iterations", result.iterations)
      .Add("lbfgs_rounds", result.rounds)
      .Add("initial_gradient_norm", result.initial_gradient_norm)
      .Add("final_gradient_norm", result.final_gradient_norm)
      .Add("relative_gradient_norm", result.relative_gradient_norm)
      .Add("gradient_criterion_met", result.gradient_criterion_met)
      .Add("converged", result.converged)
      .Add("evaluated", result.evaluated)
      .Add("termination", result.iterations > 0
                              ? ceres::TerminationTypeToString(
                                    result.summary.termination_type)
                              : "not optimised")
      .Add("seconds", seconds)
      .Add("frames", static_cast<int>(result.path.size()));
  return head;
}

JsonObject LThetaSplineJson(const LThetaSplineReport& report) {
  const std::vector<int> unconverged = report.unconverged_frames();
  JsonObject json;
  json.Add("frames_solved", static_cast<int>(report.solved_frames.size()))
      .Add("lm_iterations", report.lm_iterations())
      .Add("unconverged_frames", unconverged)
      .Add("spline_seconds", report.spline_seconds)
      .Add("solve_seconds", report.solve_seconds);
  return json;
}

JsonObject& AddSplineInitJson(JsonObject& head,
                              const SplineInitialPath& initial) {
  head.Add("init", SplineInitName(initial.init));
  if (initial.init == SplineInit::kLTheta) {
    return head.Add("ltheta_seconds", initial.seconds)
        .Add("ltheta", LThetaSplineJson(initial.ltheta));
  }
  return head.Add("init_seconds", initial.seconds)
      .Add("init_segments",
           JsonArrayOf(initial.segments, [](const GeodesicSegment& g) {
             return JsonObject()
                 .Add("from", g.from)
                 .Add("to", g.to)
                 .Add("path_energy", g.path_energy)
                 .Add("iterations", g.iterations)
                 .Add("converged", g.converged);
           }));
}

JsonObject ComparisonJson(const ShapeComparison& comparison, double tolerance,
                          double energy_tolerance) {
  std::vector<double> max_distance, mean_distance;
  for (const FrameDifference& d : comparison.frames) {
    max_distance.push_back(d.max_distance);
    mean_distance.push_back(d.mean_distance);
  }
  JsonObject json;
  json.Add("frames", static_cast<int>(comparison.frames.size()))
      .Add("max_distance", comparison.max_distance)
      .Add("mean_distance", comparison.mean_distance)
      .Add("diameter", comparison.diameter)
      .Add("relative_max_distance", comparison.relative_max_distance)
      .Add("frame_max_distance", max_distance)
      .Add("frame_mean_distance", mean_distance);
  if (comparison.frames.size() > 1) {
    json.Add("path_energy_a", comparison.energy_a)
        .Add("path_energy_b", comparison.energy_b)
        .Add("relative_energy_difference", comparison.relative_energy_difference);
  } else {
    json.Add("energy_a_to_b", comparison.energy_a_to_b);
  }
  json.Add("tolerance", tolerance)
      .Add("energy_tolerance", energy_tolerance)
      .Add("equal",
           JudgeComparison(comparison, tolerance, energy_tolerance).agree());
  return json;
}

}  // namespace shellspace
