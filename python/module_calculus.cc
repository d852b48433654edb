// The module's geodesic calculus: geodesic, log, shoot, transport, compare.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "python/array_arguments.h"
#include "python/module_common.h"
#include "python/module_options.h"
#include "python/module_results.h"
#include "python/parameter_docs.h"
#include "shellspace/geometry/memory_limits.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/problems/calculus/parallel_transport.h"
#include "shellspace/problems/calculus/shape_comparison.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/workflows/solve_choice_words.h"
#include "shellspace/workflows/geodesic.h"
#include "shellspace/workflows/shoot.h"
#include "shellspace/workflows/transport.h"

namespace shellspace {
namespace pymodule {
namespace {

// The geodesic workflow's options of the keywords of geodesic and log: the
// ends (the start validated, the end compatible), steps (bounded by the
// CLI's memory model), the mask, the material, the solve choices and the
// solver keywords.
workflows::GeodesicOptions GeodesicOptionsOf(
    const py::object& start_v, const py::object& end_v, const py::object& F,
    int steps, const py::object& mask, const std::string& multires,
    const std::string& linear_solver, const std::string& lm,
    const std::string& init, const MaterialArgs& material_args,
    const SolverOptions& solver, const std::string& label) {
  CheckAtLeast("steps", steps, 1);
  Shell start = MakeShell(start_v, F, "start");
  Positions end = CompatiblePositions(end_v, start, "end");
  workflows::GeodesicOptions options;
  options.material = MaterialChoiceOf(material_args, start.mesh);
  const int vertices = start.mesh.num_vertices();
  CheckSteps("steps", steps, 1, GeodesicBytes(vertices, steps), vertices,
             kGeodesicModel);
  options.fixed_vertices = MaskArgument(mask, vertices);
  options.start = std::move(start.mesh);
  options.topology = std::move(start.topology);
  options.end = std::move(end);
  options.steps = steps;
  options.multires = ParseMultiresolution(multires, "multires");
  options.linear_solver = ParsePathLinearSolver(linear_solver, "linear_solver");
  options.lm = ParseGeodesicLm(lm, "lm");
  options.init = ParseGeodesicInit(init, "init");
  options.settings = solver.Settings(label);
  return options;
}

// Keywords -> options -> the workflow -> files and (path, summary).
py::object GeodesicPy(const py::object& start_v, const py::object& end_v,
                      const py::object& F, int steps, const py::object& mask,
                      const std::string& multires,
                      const std::string& linear_solver, const std::string& lm,
                      const std::string& init,
                      bool report, const std::optional<std::string>& output,
                      const std::optional<std::string>& png,
                      const std::optional<std::string>& gltf,
                      const MaterialArgs& material_args,
                      const SolverOptions& solver) {
  const auto clock = Clock::now();
  CheckOutputs(output, png, gltf, MaskInputPaths(mask));
  const workflows::GeodesicOptions options =
      GeodesicOptionsOf(start_v, end_v, F, steps, mask, multires,
                        linear_solver, lm, init, material_args, solver,
                        "geodesic");
  CheckPngMemory(png, steps + 1);
  workflows::GeodesicResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = workflows::RunGeodesic(options);
  }
  if (report)
    py::print(result.geodesic().summary.FullReport(),
              py::arg("file") = py::module_::import("sys").attr("stderr"));
  const JsonObject json =
      WorkflowJson(workflows::ToJson(result), result.material, result.start,
                      Seconds(clock), solver, output);
  if (!result.status.failed()) {
    WritePath(output, png, gltf, result.start.faces, result.path(), json);
  }
  const py::object summary = ToDict(json);
  py::object value = FromPath(result.path());
  return FinishResult(solver, "geodesic", std::move(result), std::move(value),
                      summary);
}

py::object LogPy(const py::object& start_v, const py::object& end_v,
                 const py::object& F, int steps, const py::object& mask,
                 const std::string& multires, const std::string& linear_solver,
                 const std::string& lm, const std::string& init,
                 const std::optional<std::string>& output,
                 const MaterialArgs& material_args,
                 const SolverOptions& solver) {
  const auto clock = Clock::now();
  CheckOutputFile(output, MaskInputPaths(mask));
  const workflows::GeodesicOptions options =
      GeodesicOptionsOf(start_v, end_v, F, steps, mask, multires,
                        linear_solver, lm, init, material_args, solver, "log");
  workflows::LogResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = workflows::RunLog(options);
  }
  const workflows::GeodesicResult& geodesic = result.geodesic;
  if (output && !geodesic.status.failed()) {
    WriteMesh(Mesh{geodesic.start.positions + result.log,
                   geodesic.start.faces},
              *output);
  }
  const py::object summary =
      WorkflowSummary(workflows::ToJson(result), geodesic.material,
                      geodesic.start, Seconds(clock), solver, output);
  py::object value = FromPositions(result.log);
  return FinishResult(solver, "log", std::move(result), std::move(value),
                      summary);
}

// Keywords -> options -> the workflow -> files and (path, summary).
py::object ShootPy(const py::object& first_v, const py::object& second_v,
                   const py::object& F, int steps, bool backward,
                   const py::object& mask,
                   const std::optional<std::string>& output,
                   const std::optional<std::string>& png,
                   const std::optional<std::string>& gltf,
                   const MaterialArgs& material_args,
                   const SolverOptions& solver) {
  const auto clock = Clock::now();
  CheckAtLeast("steps", steps, 1);
  CheckOutputs(output, png, gltf, MaskInputPaths(mask));
  Shell first = MakeShell(first_v, F, "first");
  workflows::ShootOptions options;
  options.second = CompatiblePositions(second_v, first, "second");
  options.material = MaterialChoiceOf(material_args, first.mesh);
  const int vertices = first.mesh.num_vertices();
  CheckSteps("steps", steps, 1, PathBytes(vertices, steps + 1), vertices,
             kPathModel);
  CheckPngMemory(png, steps + 1);
  options.fixed_vertices = MaskArgument(mask, vertices);
  options.first = std::move(first.mesh);
  options.topology = std::move(first.topology);
  options.steps = steps;
  options.backward = backward;
  options.settings = solver.Settings("shoot");
  workflows::ShootResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = workflows::RunShoot(options);
  }
  // An EXP step without a root is the CLI's unsolved step (exit 4).
  const JsonObject json =
      WorkflowJson(workflows::ToJson(result), result.material, result.first,
                      Seconds(clock), solver, output);
  WritePath(output, png, gltf, result.first.faces, result.path(), json);
  const py::object summary = ToDict(json);
  py::object value = FromPath(result.path());
  return FinishResult(solver, "shoot", std::move(result), std::move(value),
                      summary);
}

// Keywords -> options -> the workflow -> files and (shapes, summary).
py::object TransportPy(const py::object& path_object,
                       const py::object& variation_v, const py::object& F,
                       double epsilon, const py::object& mask,
                       const std::optional<std::string>& output,
                       const std::optional<std::string>& png,
                       const std::optional<std::string>& gltf,
                       const MaterialArgs& material_args,
                       const SolverOptions& solver) {
  const auto clock = Clock::now();
  if (!(epsilon > 0) || !std::isfinite(epsilon)) {
    throw InputError("epsilon must be > 0, got " + std::to_string(epsilon));
  }
  CheckOutputs(output, png, gltf, MaskInputPaths(mask));
  const std::vector<Positions> frames = ShapeListArgument(path_object, "path");
  if (frames.size() < 2) throw InputError("path: need at least 2 frames");
  CheckPngMemory(png, static_cast<int>(frames.size()));
  Shell first = MakeShell(frames[0], F, "path[0]");
  workflows::TransportOptions options;
  options.path = {first.mesh.positions};
  for (size_t k = 1; k < frames.size(); ++k) {
    options.path.push_back(CompatiblePositions(
        frames[k], first, "path[" + std::to_string(k) + "]"));
  }
  options.variation = CompatiblePositions(variation_v, first, "variation");
  options.material = MaterialChoiceOf(material_args, first.mesh);
  options.fixed_vertices = MaskArgument(mask, first.mesh.num_vertices());
  options.first = std::move(first.mesh);
  options.topology = std::move(first.topology);
  options.epsilon = epsilon;
  options.settings = solver.Settings("transport");
  workflows::TransportResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = workflows::RunTransport(options);
  }
  const JsonObject json =
      WorkflowJson(workflows::ToJson(result), result.material, result.first,
                      Seconds(clock), solver, output);
  WritePath(output, png, gltf, result.first.faces, result.shapes(), json);
  const py::object summary = ToDict(json);
  py::object value = FromPath(result.shapes());
  return FinishResult(solver, "transport", std::move(result), std::move(value),
                      summary);
}

// `compare`: a and b each one #V x 3 array (a shell) or a sequence / #frames
// x #V x 3 array (a path), with the connectivity F.
py::object ComparePy(const py::object& a_object, const py::object& b_object,
                     const py::object& F, double tolerance,
                     double energy_tolerance, const MaterialArgs& material_args) {
  for (const auto& [name, value] :
       {std::pair{"tolerance", tolerance}, {"energy_tolerance", energy_tolerance}}) {
    if (!(value >= 0) || !std::isfinite(value)) {
      throw InputError(std::string(name) + " must be >= 0, got " +
                       std::to_string(value));
    }
  }
  const std::vector<Positions> a_shapes = ShapeOrListArgument(a_object, "a");
  const std::vector<Positions> b_shapes = ShapeOrListArgument(b_object, "b");
  const Shell first = MakeShell(a_shapes[0], F, "a[0]");
  ShellPath a, b;
  for (size_t k = 0; k < a_shapes.size(); ++k) {
    a.push_back(CompatiblePositions(a_shapes[k], first, "a[" + std::to_string(k) + "]"));
  }
  for (size_t k = 0; k < b_shapes.size(); ++k) {
    b.push_back(CompatiblePositions(b_shapes[k], first, "b[" + std::to_string(k) + "]"));
  }
  const ShellSpace space(first.mesh, first.topology, Material(material_args, first.mesh));
  return ToDict(ComparisonJson(CompareShapes(space, a, b), tolerance,
                               energy_tolerance));
}

}  // namespace

void RegisterCalculus(py::module_& m) {
  m.def(
      "compare", WithMaterialArgs(&ComparePy), py::arg("a"), py::arg("b"),
      py::arg("F"), py::arg("tolerance") = 1e-6,
      py::arg("energy_tolerance") = 1e-6, SHELLSPACE_MATERIAL_ARGS,
      WithParameters(
          "compare",
          "Two shells (#V x 3 arrays) or two paths (sequences of them) up to "
          "rigid motion per frame: the `compare` verb's summary (max and mean "
          "vertex distance per frame, E_K of each path or W[a, b], `equal` "
          "against the tolerances).")
          .c_str());
  DefWithOptions(
      m, "geodesic", "GeodesicOptions", WithMaterialAndSolverArgs(&GeodesicPy),
      WithParameters(
          "geodesic",
          "Discrete geodesic from start to end in `steps` steps: returns a "
          "GeodesicResult (unpacks as (path, summary)). mask: vertex indices "
          "or a mask file held at their linear "
          "positions. lm: who runs the LM stages, 'auto' | 'ceres' | 'engine' "
          "(as the CLI's --lm). output: also write DIR/shape_000.ply ...; png: "
          "a "
          "film strip."),
      SHELLSPACE_GEODESIC_ARGS, py::arg("report") = false,
      SHELLSPACE_FRAME_OUTPUT_ARGS, SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS);
  DefWithOptions(
      m, "log", "LogOptions", WithMaterialAndSolverArgs(&LogPy),
      WithParameters(
          "log",
          "LOG_K(start -> end) = K (s_1 - s_0) of the discrete geodesic: "
          "returns a LogResult (unpacks as (log #V x 3, summary)). output: "
          "write start + log (as the CLI)."),
      SHELLSPACE_GEODESIC_ARGS, py::arg("output") = py::none(),
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS);
  DefWithOptions(
      m, "shoot", "ShootOptions", WithMaterialAndSolverArgs(&ShootPy),
      WithParameters(
          "shoot",
          "Geodesic shooting (EXP steps) from (first, second): returns a "
          "ShootResult (unpacks as (path, summary))."),
      py::arg("first"), py::arg("second"), py::arg("F"),
      py::arg("steps") = workflows::ShootOptions().steps,
      py::arg("backward") = workflows::ShootOptions().backward,
      py::arg("mask") = py::none(), SHELLSPACE_FRAME_OUTPUT_ARGS,
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS);
  DefWithOptions(
      m, "transport", "TransportOptions",
      WithMaterialAndSolverArgs(&TransportPy),
      WithParameters(
          "transport",
          "Schild's-ladder transport of variation - path[0] along "
          "path: returns a TransportResult (unpacks as (shapes s_k + "
          "epsilon xi_k, summary))."),
      py::arg("path"), py::arg("variation"), py::arg("F"),
      py::arg("epsilon") = workflows::TransportOptions().epsilon,
      py::arg("mask") = py::none(), SHELLSPACE_FRAME_OUTPUT_ARGS,
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS);
}

}  // namespace pymodule
}  // namespace shellspace
