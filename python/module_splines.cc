// The module's splines: spline, regress.
#include <string>
#include <utility>
#include <vector>

#include "python/array_arguments.h"
#include "python/module_common.h"
#include "python/module_options.h"
#include "python/module_results.h"
#include "python/parameter_docs.h"
#include "shellspace/geometry/memory_limits.h"
#include "shellspace/problems/splines/ltheta_spline.h"
#include "shellspace/problems/splines/spline.h"
#include "shellspace/problems/splines/spline_initial_path.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/workflows/regress.h"
#include "shellspace/workflows/spline.h"

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
  settings.inner.stop = StopToken();
  settings.max_iterations = solver.max_iterations;
  settings.gradient_tolerance = solver.tolerance;
  settings.progress = !solver.quiet;
  settings.progress_label = label;
  return settings;
}

// The path verbs' (spline, regress) bound of steps: kMaxSteps and the
// path's memory (geometry/memory_limits.h's PathBytes).
void CheckPathSteps(int steps, int min, int vertices) {
  CheckSteps("steps", steps, min, PathBytes(vertices, steps + 1), vertices,
             kPathModel);
}

// Keywords -> options -> the workflow -> files and (path, summary).
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
  CheckOutputs(output, png, gltf);
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(keyframes_object, F, "keyframes");
  CheckPathSteps(steps, 2, set.first.mesh.num_vertices());
  CheckPngMemory(png, steps + 1);
  workflows::SplineOptions options;
  options.at = Indices(at_object, steps, set.shapes.size(), "keyframes");
  options.material = MaterialChoiceOf(material_args, set.first.mesh);
  options.init = ParseSplineInit(init);
  options.method = workflows::ParseSplineMethod(method, "method");
  workflows::CheckSplineMethod(options.method, options.init, "method",
                               "init");
  options.reference = set.first.mesh;
  options.topology = set.first.topology;
  options.keyframes = set.shapes;
  options.steps = steps;
  options.periodic = periodic;
  options.init_settings = solver.Settings(init);
  options.init_settings.progress = false;
  options.settings = SplineSettingsOf(solver, "spline");
  workflows::SplineResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = workflows::RunSpline(options);
  }
  const JsonObject json =
      WorkflowJson(
      workflows::ToJson(result, Seconds(clock)), result.material,
      set.first.mesh, std::nullopt, solver, output);
  WritePath(output, png, gltf, set.first.mesh.faces, result.path(), json);
  const py::object summary = ToDict(json);
  py::object value = FromPath(result.path());
  return FinishResult(solver, "spline", std::move(result), std::move(value),
                      summary);
}

// Keywords -> options -> the workflow -> files and (path, summary).
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
  CheckOutputs(output, png, gltf);
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  CheckPathSteps(steps, 2, set.first.mesh.num_vertices());
  CheckPngMemory(png, steps + 1);
  workflows::RegressOptions options;
  options.at = Indices(at_object, steps, set.shapes.size(), "inputs");
  options.reference = set.first.mesh;
  options.topology = set.first.topology;
  options.inputs = set.shapes;
  options.steps = steps;
  options.sigma = sigma;
  options.material = MaterialChoiceOf(material_args, set.first.mesh);
  options.settings = SplineSettingsOf(solver, "regress");
  workflows::RegressResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = workflows::RunRegress(options);
  }
  const JsonObject json =
      WorkflowJson(
      workflows::ToJson(result, Seconds(clock)), result.material,
      set.first.mesh, std::nullopt, solver, output);
  WritePath(output, png, gltf, set.first.mesh.faces, result.path(), json);
  const py::object summary = ToDict(json);
  py::object value = FromPath(result.path());
  return FinishResult(solver, "regress", std::move(result), std::move(value),
                      summary);
}

}  // namespace

void RegisterSplines(py::module_& m) {
  DefWithOptions(
      m, "spline", "SplineOptions", WithMaterialAndSolverArgs(&SplinePy),
      WithParameters(
          "spline",
          "Riemannian spline through keyframes at path indices `at`, from the "
          "initial path `init` (ltheta or geodesic, as the CLI's --init): "
          "returns a SplineResult (unpacks as (path, summary))."),
      py::arg("keyframes"), py::arg("at"), py::arg("F"),
      py::arg("steps") = workflows::SplineOptions().steps,
      py::arg("method") = std::string(
          workflows::SplineMethodName(workflows::SplineOptions().method)),
      py::arg("init") =
          std::string(SplineInitName(workflows::SplineOptions().init)),
      py::arg("periodic") = workflows::SplineOptions().periodic,
      SHELLSPACE_FRAME_OUTPUT_ARGS, SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS);
  DefWithOptions(
      m, "regress", "RegressOptions", WithMaterialAndSolverArgs(&RegressPy),
      WithParameters(
          "regress",
          "Shape regression (data term + sigma spline energy): returns a "
          "RegressResult (unpacks as (path, summary))."),
      py::arg("inputs"), py::arg("at"), py::arg("F"),
      py::arg("steps") = workflows::RegressOptions().steps,
      py::arg("sigma") = workflows::RegressOptions().sigma,
      SHELLSPACE_FRAME_OUTPUT_ARGS, SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS);
}

}  // namespace pymodule
}  // namespace shellspace
