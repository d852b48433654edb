// The module's statistics: mean, pca.
#include <algorithm>
#include <string>
#include <vector>

#include "python/module_common.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/statistics/leave_one_out.h"
#include "shellspace/problems/statistics/procrustes_pca.h"
#include "shellspace/problems/statistics/shell_pca.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/reports/shape_reports.h"
#include "tools/run/memory_limits.h"

namespace shellspace {
namespace pymodule {
namespace {

// What an unconverged elastic mean missed (the CLI's text).
std::vector<std::string> MeanFailures(const ElasticMeanResult& mean,
                                      const std::string& what) {
  if (mean.converged) return {};
  return {what + ": |grad| " + Short(mean.gradient_norm) +
          " above the target " + Short(mean.gradient_target) + " after " +
          std::to_string(mean.lm_iterations) + " LM + " +
          std::to_string(mean.newton_iterations) + " Newton iterations (" +
          mean.termination + ")"};
}

py::object MeanPy(const py::object& inputs_object, const py::object& F,
                  bool report, const std::optional<std::string>& output,
                  const MaterialArgs& material_args,
                  const SolverOptions& solver) {
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(material_args, set.first.mesh));
  const SolverSettings settings = solver.Settings("mean");
  ElasticMeanResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = ComputeElasticMean(space, set.shapes, settings);
  }
  if (result.summary.termination_type == ceres::FAILURE) {
    throw InputError("elastic mean failed: " + result.summary.message);
  }
  std::vector<std::string> far;
  for (int i : FarInputs(result.energies)) {
    far.push_back("inputs[" + std::to_string(i) + "]");
  }
  if (report)
    py::print(result.summary.FullReport(),
              py::arg("file") = py::module_::import("sys").attr("stderr"));
  if (output) WriteMesh(Mesh{result.mean, set.first.mesh.faces}, *output);
  JsonObject json = MeanJson(result, static_cast<int>(set.shapes.size()), far);
  json.Raw("energy_split", MeanEnergySplitJson(space, result.mean, set.shapes))
      .Raw("material", MaterialRecord(space, set.first.mesh, material_args))
      .Add("seconds", Seconds(clock));
  AddStopFields(json, *solver.control);
  const py::object summary = ToDict(AddOutput(json, output));
  return solver.Finish(py::make_tuple(FromPositions(result.mean), summary),
                       summary, "mean", MeanFailures(result, "elastic mean"));
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
  const ShellPcaOptions options = MakeShellPcaOptions(
      log_steps, exp_steps, max_exp_steps, displacement, "");
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  const int n = static_cast<int>(set.shapes.size());
  const int minimum = loo ? 3 : 2;
  if (n < minimum) {
    throw InputError("inputs needs at least " + std::to_string(minimum) +
                     " shells, got " + std::to_string(n));
  }
  CheckPcaModeCount(modes, n, loo, "");
  const int vertices = set.first.mesh.num_vertices();
  CheckSteps("log_steps", log_steps, 1, GeodesicBytes(vertices, log_steps),
             vertices, kGeodesicModel);
  CheckSteps("max_exp_steps", max_exp_steps, 1,
             PathBytes(vertices, max_exp_steps + 1), vertices, kPathModel);
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(material_args, set.first.mesh));
  const SolverSettings settings = solver.Settings("pca");
  SolverSettings inner = settings;
  inner.progress = false;
  SolveControl& control = *solver.control;

  std::vector<std::pair<std::string, Positions>> shapes;
  std::vector<Positions> strip;
  std::vector<std::string> failed_shapes, far;
  JsonObject json;
  ElasticMeanResult mean;
  std::string stopped_in;  // the phase a stop ended, or ""
  {
    SolveControl::Solving solving(control);
    mean = ComputeElasticMean(space, set.shapes, settings);
    if (mean.summary.termination_type == ceres::FAILURE) {
      throw InputError("elastic mean failed: " + mean.summary.message);
    }
    for (int i : FarInputs(mean.energies)) {
      far.push_back("inputs[" + std::to_string(i) + "]");
    }
    shapes.emplace_back("mean", mean.mean);
    strip.push_back(mean.mean);
    std::optional<ShellPcaModel> model;
    if (control.stopped()) {
      stopped_in = "mean";
    } else {
      model = ComputeShellPca(space, mean.mean, set.shapes, options, inner);
      if (control.stopped()) {
        stopped_in = "displacements";
        model.reset();
      }
    }
    const int shell_modes =
        model ? std::min<int>(modes, static_cast<int>(model->modes.size()))
              : 0;
    for (int j = 0; j < shell_modes; ++j) {
      for (const double sign : {-1.0, 1.0}) {
        if (control.stopped()) break;  // no new shot once stopped
        const std::string name =
            "mode_" + std::to_string(j + 1) + (sign < 0 ? "_minus" : "_plus");
        // A mode shape whose EXP shot has no solution is not returned; it
        // is listed in the summary (as the CLI does).
        Positions shape;
        if (TryShellModeShape(space, *model, j, sign * amplitude, options,
                              inner, &shape)) {
          shapes.emplace_back(name, shape);
          strip.push_back(std::move(shape));
        } else {
          failed_shapes.push_back(name + ".ply");
        }
      }
    }
    if (model && control.stopped()) stopped_in = "mode shapes";
    if (stopped_in.empty()) {
      json = PcaJson(n, mean, displacement, options, *model, shell_modes,
                     failed_shapes, far, amplitude);
      json.Raw("material",
               MaterialRecord(space, set.first.mesh, material_args));
      if (baseline == "procrustes") {
        for (auto& shape : AddProcrustesBaseline(
                 ComputeProcrustesPca(set.shapes), modes, amplitude, &json)) {
          shapes.push_back(std::move(shape));
        }
      }
      if (loo) {
        LeaveOneOutOptions loo_options;
        loo_options.max_modes = modes;
        loo_options.pca = options;
        loo_options.initial_mean = mean.mean;
        const LeaveOneOutTable table =
            EvaluateLeaveOneOut(space, set.shapes, loo_options, inner);
        if (control.stopped()) {
          stopped_in = "leave-one-out";
        } else {
          json.Raw("leave_one_out", LeaveOneOutJson(table));
        }
      }
    }
  }
  if (!stopped_in.empty()) {  // the mean alone
    shapes.resize(1);
    strip.resize(1);
    json = PcaMeanJson(n, mean);
    json.Add("modes", 0).Add("stopped_in", stopped_in);
    json.Raw("material", MaterialRecord(space, set.first.mesh, material_args));
  }
  json.Add("seconds", Seconds(clock));
  AddStopFields(json, control);
  AddOutput(json, output);
  if (output) {  // the CLI's files: the PLY set and pca.json, together
    MakeDirectory(*output);
    AtomicFileSet files;
    std::vector<Mesh> meshes;
    meshes.reserve(shapes.size());
    for (const auto& [name, positions] : shapes) {
      meshes.push_back(Mesh{positions, set.first.mesh.faces});
      const std::string path = *output + "/" + name + ".ply";
      files.Add(path, MeshWriter(meshes.back(), path));
    }
    files.Add(*output + "/pca.json", json.str() + "\n");
    files.Commit();
  }
  if (png && stopped_in.empty()) {
    WriteFilmStrip(strip, set.first.mesh.faces, RenderOptions(), *png);
  }
  py::dict out;
  for (const auto& [name, positions] : shapes) {
    out[py::str(name)] = FromPositions(positions);
  }
  const py::object summary = ToDict(json);
  return solver.Finish(py::make_tuple(out, summary), summary, "pca",
                       MeanFailures(mean, "the elastic mean"));
}

}  // namespace

void RegisterStatistics(py::module_& m) {
  m.def(
      "pca",
      WithMaterialAndSolverArgs(&PcaPy),
      py::arg("inputs"), py::arg("F"), py::arg("modes") = 3,
      py::arg("baseline") = "", py::arg("loo") = false,
      py::arg("amplitude") = 1.0, py::arg("log_steps") = 2,
      py::arg("exp_steps") = 4, py::arg("max_exp_steps") = 16,
      py::arg("displacement") = "log", py::arg("output") = py::none(),
      py::arg("png") = py::none(), SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS,
      "Shell PCA at the elastic mean (and the Procrustes baseline, "
      "leave-one-out): returns ({'mean': ..., 'mode_1_minus': ..., ...}, "
      "summary). output: the CLI's directory (PLY files and pca.json).");
  m.def(
      "mean",
      WithMaterialAndSolverArgs(&MeanPy),
      py::arg("inputs"), py::arg("F"), py::arg("report") = false,
      py::arg("output") = py::none(), SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS,
      "Elastic mean argmin_s sum_i W[inputs_i, s]: returns (mean #V x 3, "
      "summary).");
}

}  // namespace pymodule
}  // namespace shellspace
