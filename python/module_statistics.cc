// The module's statistics: mean, pca.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "python/module_common.h"
#include "python/module_options.h"
#include "python/module_results.h"
#include "python/parameter_docs.h"
#include "shellspace/geometry/memory_limits.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/io/output_directory.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/statistics/leave_one_out.h"
#include "shellspace/problems/statistics/procrustes_pca.h"
#include "shellspace/problems/statistics/shell_pca.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/reports/shape_reports.h"
#include "shellspace/workflows/mean.h"
#include "shellspace/workflows/pca.h"

namespace shellspace {
namespace pymodule {
namespace {

// The options every statistics workflow takes from the inputs (named
// "inputs[i]"), the material and solver keywords.
template <class Options>
Options OptionsOfInputs(const ShapeSet& set, const MaterialArgs& material_args,
                        const SolverOptions& solver, const std::string& label) {
  Options options;
  options.reference = set.first.mesh;
  options.topology = set.first.topology;
  options.shapes = set.shapes;
  options.material = MaterialChoiceOf(material_args, set.first.mesh);
  options.settings = solver.Settings(label);
  return options;
}

// Keywords -> options -> the workflow -> the file and (mean, summary).
py::object MeanPy(const py::object& inputs_object, const py::object& F,
                  bool report, const std::optional<std::string>& output,
                  const MaterialArgs& material_args,
                  const SolverOptions& solver) {
  const auto clock = Clock::now();
  CheckOutputFile(output);
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  const auto options = OptionsOfInputs<workflows::MeanOptions>(
      set, material_args, solver, "mean");
  workflows::MeanResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = workflows::RunMean(options);
  }
  if (report)
    py::print(result.mean.summary.FullReport(),
              py::arg("file") = py::module_::import("sys").attr("stderr"));
  if (output && !result.status.failed()) {
    WriteMesh(Mesh{result.mean.mean, set.first.mesh.faces}, *output);
  }
  const py::object summary =
      WorkflowSummary(workflows::ToJson(result), result.material,
                      set.first.mesh, Seconds(clock), solver, output);
  py::object value = FromPositions(result.mean.mean);
  return FinishResult(solver, "mean", std::move(result), std::move(value),
                      summary);
}

// The CLI's files of a pca run, each if given: `output` (the PLY set and
// pca.json, together) and `png` (the film strip of the mean and the shell
// mode shapes; not after a stop).
void WritePcaFiles(const workflows::PcaResult& result, const Faces& faces,
                   const JsonObject& json,
                   const std::optional<std::string>& output,
                   const std::optional<std::string>& png) {
  if (output) {
    // Replaced whole, with its summary.json, as the CLI's directory.
    StagedRun run(*output);
    for (const auto& [name, positions] : result.shapes) {
      WriteMesh(Mesh{positions, faces}, run.File(name + ".ply"));
    }
    WriteFileAtomically(run.File("pca.json"), json.str() + "\n");
    run.Commit(json.str());
  }
  if (png && result.stopped_in.empty()) {
    std::vector<Positions> strip;
    for (const auto& [name, positions] : result.shapes) {
      if (name == "mean" || name.rfind("mode_", 0) == 0) {
        strip.push_back(positions);
      }
    }
    CheckPngMemory(png, static_cast<int>(strip.size()));
    WriteFilmStrip(strip, faces, RenderOptions(), *png);
  }
}

// The `pca` verb: elastic mean, shell PCA modes shot by EXP_K, optionally
// the Procrustes baseline and the leave-one-out table. Returns ({name:
// shape} with the names of the CLI's files without ".ply", summary). A stop
// (time_limit, SIGINT) in any phase ends it with the mean alone, as the
// CLI: {'mean': ...} and "stopped_in" the phase, "modes": 0.
py::object PcaPy(const py::object& inputs_object, const py::object& F,
                 int modes, const std::string& baseline, bool loo,
                 double amplitude, int log_steps, int exp_steps,
                 int max_exp_steps, const std::string& displacement,
                 const std::optional<std::string>& output,
                 const std::optional<std::string>& png,
                 const MaterialArgs& material_args,
                 const SolverOptions& solver) {
  if (baseline != "" && baseline != "procrustes") {
    throw InputError("baseline must be 'procrustes' (or empty), got '" +
                     baseline + "'");
  }
  CheckAtLeast("modes", modes, 1);
  CheckAtLeast("log_steps", log_steps, 1);
  CheckAtLeast("exp_steps", exp_steps, 1);
  if (max_exp_steps < exp_steps) {
    throw InputError("max_exp_steps must be at least exp_steps");
  }
  if (!(amplitude >= 0) || !std::isfinite(amplitude)) {
    throw InputError("amplitude must be >= 0");
  }
  CheckOutputs(output, png, std::nullopt);
  const ShellPcaOptions pca =
      MakeShellPcaOptions(log_steps, exp_steps, max_exp_steps,
                          ParseDisplacementKind(displacement, "displacement"));
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  const int n = static_cast<int>(set.shapes.size());
  const int minimum = loo ? 3 : 2;
  if (n < minimum) {
    throw InputError("inputs needs at least " + std::to_string(minimum) +
                     " shells, got " + std::to_string(n));
  }
  CheckPcaModeCount(modes, n, loo, "modes", "loo");
  CheckPngMemory(png, 1 + 2 * modes);  // the mean and the mode shapes
  const int vertices = set.first.mesh.num_vertices();
  CheckSteps("log_steps", log_steps, 1, GeodesicBytes(vertices, log_steps),
             vertices, kGeodesicModel);
  CheckSteps("max_exp_steps", max_exp_steps, 1,
             PathBytes(vertices, max_exp_steps + 1), vertices, kPathModel);
  auto options = OptionsOfInputs<workflows::PcaOptions>(set, material_args,
                                                        solver, "pca");
  options.modes = modes;
  options.procrustes = baseline == "procrustes";
  options.leave_one_out = loo;
  options.amplitude = amplitude;
  options.pca = pca;
  workflows::PcaResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = workflows::RunPca(options);
  }
  JsonObject json = workflows::ToJson(result, options);
  json.Add("material",
           workflows::MaterialChoiceJson(result.material, set.first.mesh))
      .Add("seconds", Seconds(clock));
  AddStopFields(json, *solver.control);
  AddOutput(json, output);
  if (!result.status.failed()) {
    WritePcaFiles(result, set.first.mesh.faces, json, output, png);
  }
  py::dict out;
  for (const auto& [name, positions] : result.shapes) {
    out[py::str(name)] = FromPositions(positions);
  }
  const py::object summary = ToDict(json);
  py::object value = out;
  return FinishResult(solver, "pca", std::move(result), std::move(value),
                      summary);
}

}  // namespace

void RegisterStatistics(py::module_& m) {
  DefWithOptions(
      m, "pca", "PcaOptions", WithMaterialAndSolverArgs(&PcaPy),
      WithParameters(
          "pca",
          "Shell PCA at the elastic mean (and the Procrustes baseline, "
          "leave-one-out): returns a PcaResult (unpacks as ({'mean': ..., "
          "'mode_1_minus': ..., ...}, summary)). output: the CLI's directory "
          "(PLY files and pca.json)."),
      py::arg("inputs"), py::arg("F"),
      py::arg("modes") = workflows::PcaOptions().modes,
      py::arg("baseline") = "",
      py::arg("loo") = workflows::PcaOptions().leave_one_out,
      py::arg("amplitude") = workflows::PcaOptions().amplitude,
      py::arg("log_steps") = ShellPcaOptions().steps,
      // The CLI's --exp_steps (ShellPcaOptions::exp_steps 0 means the
      // LOG's K; the verb shoots with 4).
      py::arg("exp_steps") = 4,
      py::arg("max_exp_steps") = ShellPcaOptions().max_exp_steps,
      py::arg("displacement") =
          std::string(DisplacementKindName(ShellPcaOptions().displacement)),
      py::arg("output") = py::none(), py::arg("png") = py::none(),
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS);
  DefWithOptions(
      m, "mean", "MeanOptions", WithMaterialAndSolverArgs(&MeanPy),
      WithParameters(
          "mean",
          "Elastic mean argmin_s sum_i W[inputs_i, s]: returns a MeanResult "
          "(unpacks as (mean #V x 3, summary))."),
      py::arg("inputs"), py::arg("F"), py::arg("report") = false,
      py::arg("output") = py::none(), SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS);
}

}  // namespace pymodule
}  // namespace shellspace
