// The module's splines: spline, regress.
#include <string>
#include <vector>

#include "python/module_common.h"
#include "shellspace/problems/splines/ltheta_spline.h"
#include "shellspace/problems/splines/spline.h"
#include "shellspace/problems/splines/spline_initial_path.h"
#include "shellspace/reports/path_reports.h"
#include "python/array_arguments.h"
#include "tools/run/memory_limits.h"

namespace shellspace {
namespace pymodule {
namespace {

// The keyframe indices `at` (integers in [0, steps], strictly increasing;
// the library checks them against steps and periodicity), one per shape.
std::vector<int> Indices(const py::object& at_object, int steps, size_t shapes,
                         const std::string& name) {
  const std::vector<int> at = IndexListArgument(at_object, "at", 0, steps);
  for (size_t i = 1; i < at.size(); ++i) {
    if (at[i] <= at[i - 1]) throw InputError("at must be strictly increasing");
  }
  if (at.size() != shapes) {
    throw InputError("at gives " + std::to_string(at.size()) +
                     " indices for " + std::to_string(shapes) + " " + name);
  }
  return at;
}

// The outer L-BFGS polls the call's stop; the midpoint solves do not, so
// that every evaluation of F_K used stays exact (as the CLI).
SplineSettings SplineSettingsOf(const SolverOptions& solver,
                                const std::string& label) {
  SplineSettings settings;
  settings.inner = solver.Settings(label + " midpoint");
  settings.inner.progress = false;
  settings.inner.gradient_tolerance = 1e-10;
  settings.stop = settings.inner.stop;
  settings.inner.stop = nullptr;
  settings.max_iterations = solver.max_iterations;
  settings.gradient_tolerance = solver.tolerance;
  settings.progress = !solver.quiet;
  settings.progress_label = label;
  return settings;
}

// What an unconverged spline or regression missed (the CLI's text).
std::vector<std::string> SplineFailures(const SplineResult& result,
                                        const std::string& verb,
                                        double tolerance) {
  if (result.converged) return {};
  if (!result.evaluated) {
    return {verb + ": stopped before the first evaluation of F_K finished"};
  }
  return {verb + ": relative gradient " + Short(result.relative_gradient_norm) +
          " above the tolerance " + Short(tolerance) + " after " +
          std::to_string(result.iterations) + " L-BFGS iterations (" +
          ceres::TerminationTypeToString(result.summary.termination_type) +
          ")"};
}

// The path verbs' (spline, regress) bound of steps: kMaxSteps and the
// path's memory (tools/run/memory_limits.h's PathBytes).
void CheckPathSteps(int steps, int min, int vertices) {
  CheckSteps("steps", steps, min, PathBytes(vertices, steps + 1), vertices,
             kPathModel);
}

py::object SplinePy(const py::object& keyframes_object,
                    const py::object& at_object, const py::object& F,
                    int steps, const std::string& method,
                    const std::string& init, bool periodic,
                    const std::optional<std::string>& output,
                    const std::optional<std::string>& png,
                    const std::optional<std::string>& gltf,
                    const MaterialArgs& material_args,
                    const SolverOptions& solver) {
  if (method != "nonlinear" && method != "ltheta") {
    throw InputError("method must be nonlinear or ltheta");
  }
  CheckAtLeast("steps", steps, 2);
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(keyframes_object, F, "keyframes");
  CheckPathSteps(steps, 2, set.first.mesh.num_vertices());
  const std::vector<int> at =
      Indices(at_object, steps, set.shapes.size(), "keyframes");
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(material_args, set.first.mesh));
  const SplineInit initial_path = ParseSplineInit(init);
  if (method == "ltheta" && initial_path != SplineInit::kLTheta) {
    throw InputError("init " + init +
                     " needs method nonlinear (method ltheta is the LΘA "
                     "spline itself)");
  }
  SolverSettings init_settings = solver.Settings(init);
  init_settings.progress = false;
  SplineSettings settings = SplineSettingsOf(solver, "spline");
  if (method == "ltheta") settings.max_iterations = 0;
  SplineResult result;
  SplineInitialPath initial;
  {
    SolveControl::Solving solving(*solver.control);
    initial = MakeSplineInitialPath(initial_path, space, set.shapes, at, steps,
                                    periodic, init_settings);
    result = SolveSpline(space, set.shapes, at, steps, periodic, initial.path,
                         settings);
  }
  std::vector<std::string> failures;
  if (method == "ltheta") {
    // The LΘA spline alone converged if every frame's reconstruction did.
    const std::vector<int> frames = initial.ltheta.unconverged_frames();
    result.converged = frames.empty();
    std::string list;
    for (size_t i = 0; i < frames.size(); ++i) {
      list += (i ? ", " : "") + std::to_string(frames[i]);
    }
    if (!frames.empty()) {
      failures.push_back("spline: the LΘA reconstruction of frame(s) " + list +
                         " stopped short of the tolerance " +
                         Short(solver.tolerance));
    }
  } else {
    failures = SplineFailures(result, "spline", solver.tolerance);
  }
  WritePath(output, png, gltf, set.first.mesh.faces, result.path);
  JsonObject head;
  head.Add("method", method);
  AddSplineInitJson(head, initial);
  head.Raw("energy_split", PathEnergySplitJson(space, result.path))
      .Raw("material", MaterialRecord(space, set.first.mesh, material_args));
  JsonObject json = SplineJson(head, result, Seconds(clock));
  AddStopFields(json, *solver.control);
  const py::object summary = ToDict(AddOutput(json, output));
  return solver.Finish(py::make_tuple(FromPath(result.path), summary), summary,
                       "spline", std::move(failures));
}

py::object RegressPy(const py::object& inputs_object,
                     const py::object& at_object, const py::object& F,
                     int steps, double sigma,
                     const std::optional<std::string>& output,
                     const std::optional<std::string>& png,
                     const std::optional<std::string>& gltf,
                     const MaterialArgs& material_args,
                     const SolverOptions& solver) {
  CheckAtLeast("steps", steps, 2);
  if (!(sigma >= 0) || !std::isfinite(sigma)) {
    throw InputError("sigma must be >= 0, got " + std::to_string(sigma));
  }
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  CheckPathSteps(steps, 2, set.first.mesh.num_vertices());
  const std::vector<int> at =
      Indices(at_object, steps, set.shapes.size(), "inputs");
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(material_args, set.first.mesh));
  const SplineSettings settings = SplineSettingsOf(solver, "regress");
  SplineResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = SolveRegression(space, set.shapes, at, steps, sigma, {}, settings);
  }
  WritePath(output, png, gltf, set.first.mesh.faces, result.path);
  JsonObject head;
  head.Add("sigma", sigma);
  head.Raw("energy_split", PathEnergySplitJson(space, result.path))
      .Raw("material", MaterialRecord(space, set.first.mesh, material_args));
  JsonObject json = SplineJson(head, result, Seconds(clock));
  AddStopFields(json, *solver.control);
  const py::object summary = ToDict(AddOutput(json, output));
  return solver.Finish(py::make_tuple(FromPath(result.path), summary), summary,
                       "regress",
                       SplineFailures(result, "regress", solver.tolerance));
}

}  // namespace

void RegisterSplines(py::module_& m) {
  m.def(
      "spline",
      WithMaterialAndSolverArgs(&SplinePy),
      py::arg("keyframes"), py::arg("at"), py::arg("F"), py::arg("steps") = 8,
      py::arg("method") = "nonlinear", py::arg("init") = "ltheta",
      py::arg("periodic") = false, SHELLSPACE_FRAME_OUTPUT_ARGS,
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS,
      "Riemannian spline through keyframes at path indices `at`, from the "
      "initial path `init` (ltheta or geodesic, as the CLI's --init): returns "
      "(path, summary).");
  m.def(
      "regress",
      WithMaterialAndSolverArgs(&RegressPy),
      py::arg("inputs"), py::arg("at"), py::arg("F"), py::arg("steps") = 8,
      py::arg("sigma") = 1.0, SHELLSPACE_FRAME_OUTPUT_ARGS,
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS,
      "Shape regression (data term + sigma spline energy): returns (path, "
      "summary).");
}

}  // namespace pymodule
}  // namespace shellspace
