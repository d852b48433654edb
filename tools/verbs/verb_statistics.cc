// `shellspace mean` and `shellspace pca`: the elastic mean of a set of shells,
// shell PCA at that mean (modes shot by EXP_K), the Procrustes PCA baseline,
// and the leave-one-out comparison of the two (docs/math.md, "Elastic mean and
// shell PCA").
#include <gflags/gflags.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "shellspace/io/atomic_file.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/io/png_writer.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/statistics/leave_one_out.h"
#include "shellspace/problems/statistics/procrustes_pca.h"
#include "shellspace/problems/statistics/shell_pca.h"
#include "shellspace/render/film_strip.h"
#include "tools/run/common_flags.h"
#include "tools/verbs/film_strip_flags.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/reports/shape_reports.h"
#include "tools/run/run_status.h"
#include "tools/run/shell_inputs.h"
#include "tools/run/run_output.h"
#include "tools/run/run_paths.h"
#include "shellspace/workflows/mean.h"
#include "shellspace/workflows/pca.h"
#include "tools/verbs/geodesic_solve.h"
#include "tools/verbs/path_summary.h"
#include "tools/verbs/verb.h"

DEFINE_int32(modes, 3, "pca: number of modes");
DEFINE_string(baseline, "", "pca: '' or 'procrustes'");
DEFINE_bool(loo, false, "pca: leave-one-out evaluation");
DEFINE_double(amplitude, 1.0, "pca: mode amplitude");
DEFINE_int32(log_steps, 2, "pca: K of LOG_K");
DEFINE_int32(exp_steps, 4, "pca: K of EXP_K");
DEFINE_int32(max_exp_steps, 16, "pca: largest K of the EXP safeguard");
DEFINE_string(displacement, "log", "pca: log or difference");
DEFINE_string(mean, "", "pca: a computed elastic mean to start from");

namespace shellspace {
namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since)
      .count();
}

FlagTable MeanFlags() {
  return Flags({{
                    TextFlag("inputs", "comma-separated input shells")
                        .Required(),
                    TextFlag("output", "the elastic mean: PLY, OBJ or OFF")
                        .Required(),
                    TextFlag("report", "print Ceres' full report on stderr"),
                },
                MaterialFlags(), SolverFlags(), JsonFlag()});
}

FlagTable PcaFlags() {
  return Flags(
      {{
           TextFlag("inputs", "comma-separated input shells").Required(),
           TextFlag("output",
                    "directory of mean.ply, mode_J_{minus,plus}.ply, pca.json")
               .Required(),
           IntegerFlag("modes",
                       "number of modes written (and m = 1..modes of --loo); "
                       "at most the number of inputs - 1",
                       1)
               .Default(FlagDefault(workflows::PcaOptions().modes)),
           TextFlag("baseline",
                    "'procrustes' also writes the Procrustes PCA model "
                    "(procrustes_mean.ply, "
                    "procrustes_mode_J_{minus,plus}.ply); '' none"),
           TextFlag("loo",
                    "leave-one-out evaluation of shell vs Procrustes PCA "
                    "(m = 0..modes), table printed and in the JSON")
               .Default(BoolFlagDefault(workflows::PcaOptions().leave_one_out)),
           RealFlag("amplitude",
                    "mode shapes at +- amplitude sqrt(lambda_j) w_j", 0,
                    End::kClosed)
               .Default(FlagDefault(workflows::PcaOptions().amplitude)),
           IntegerFlag("log_steps", "K of LOG_K (displacements)", 1)
               .Default(FlagDefault(ShellPcaOptions().steps)),
           IntegerFlag("exp_steps",
                       "K of EXP_K (mode shapes, reconstructions); doubled up "
                       "to --max_exp_steps while a shot fails or its step "
                       "energies drift by more than 50%",
                       1),
           IntegerFlag("max_exp_steps",
                       "largest K of the EXP safeguard (>= --exp_steps)", 1)
               .Default(FlagDefault(ShellPcaOptions().max_exp_steps)),
           TextFlag("displacement",
                    "'log' (v_i = LOG_K(mean -> S_i)) or 'difference' "
                    "(v_i = S_i - mean after rigid alignment)")
               .Default(DisplacementKindName(ShellPcaOptions().displacement)),
           PngFlag("the mean and the modes"),
           HtmlFlag(),
           TextFlag("mean",
                    "an elastic mean of the inputs computed before (e.g. by "
                    "`shellspace mean`): the mean solve starts there and "
                    "only checks it (no iterations if it meets the "
                    "tolerance)"),
       },
       MaterialFlags(),
       SolverFlags(),
       JsonFlag(),
       FilmStripFlags()});
}

// Loads --inputs (at least `minimum` shells with one connectivity).
ShellSet LoadInputs(size_t minimum) {
  const size_t count = SplitList(FLAGS_inputs, "inputs").size();
  if (count < minimum) {
    throw InputError("--inputs needs at least " + std::to_string(minimum) +
                     " shells, got " + std::to_string(count));
  }
  return LoadShellList(FLAGS_inputs, "inputs");
}

// The options every statistics workflow takes from --inputs and the
// material and solver flags.
template <class Options>
Options OptionsOfInputs(const ShellSet& inputs, const std::string& verb) {
  Options options;
  options.reference = inputs.first.mesh;
  options.topology = inputs.first.topology;
  options.shapes = inputs.shapes;
  options.names = inputs.paths;
  options.material = MaterialChoiceFromFlags(inputs.first.mesh);
  options.settings = SettingsFromFlags(verb);
  return options;
}

// The inputs far from the others (the result's far_input_indices), each
// with a warning on stderr unless --quiet: such an input dominates the mean
// and the leading shell PCA mode, and EXP shots along that mode may have no
// solution.
void WarnAboutFarInputs(const std::vector<int>& far,
                        const std::vector<std::string>& names,
                        const ElasticMeanResult& mean, const char* verb) {
  if (FLAGS_quiet) return;
  for (int i : far) {
    std::cerr << verb << ": warning: input " << names[i]
              << " is far from the others: "
              << workflows::FarInputText(mean, i) << "\n";
  }
}

// Flags -> options -> the workflow -> the file and summary.
int RunMean() {
  const auto clock = std::chrono::steady_clock::now();
  RunPaths()
      .InputList("inputs", FLAGS_inputs)
      .OutputMesh("output", FLAGS_output)
      .Check();
  const ShellSet inputs = LoadInputs(1);
  const workflows::MeanResult result = workflows::RunMean(
      OptionsOfInputs<workflows::MeanOptions>(inputs, "mean"));
  if (result.status.failed()) return FailedSolveExit("mean", result.status);
  WarnAboutFarInputs(result.far_input_indices, inputs.paths, result.mean,
                     "mean");
  const ElasticMeanResult& mean = result.mean;
  if (FLAGS_report) std::cerr << mean.summary.FullReport() << "\n";
  RunStatus status("mean");
  RecordWorkflow(result.status, {}, "mean", &status);
  WriteMesh(Mesh{mean.mean, inputs.first.mesh.faces}, FLAGS_output);
  if (FLAGS_json) {
    JsonObject json = workflows::ToJson(result);
    json.Add("material",
             workflows::MaterialChoiceJson(result.material, inputs.first.mesh))
        .Add("bending_model", FLAGS_bending);
    std::cout << AddRunFields(json)
                     .Add("seconds", Seconds(clock))
                     .Add("output", FLAGS_output)
                     .str()
              << "\n";
  } else if (!FLAGS_quiet) {
    std::cerr << mean.summary.BriefReport() << "\n";
    std::cout << "sum_i W[S_i, mean] = " << mean.energy << " over "
              << inputs.shapes.size() << " shells (" << mean.lm_iterations
              << " LM + " << mean.newton_iterations
              << " Newton iterations, |grad| " << mean.gradient_norm
              << "); wrote " << FLAGS_output << "\n";
  }
  return status.Finish();
}

std::string TableText(const LeaveOneOutTable& table) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof(line), "%2s  %14s %14s %6s  %14s %14s\n", "m",
                "shell err", "shell W", "failed", "procrustes err",
                "procrustes W");
  out << "leave-one-out over " << table.folds.size()
      << " folds (mean vertex error after rigid alignment; W[truth, "
         "reconstruction]; shell columns over the folds whose EXP shot "
         "succeeded, 'failed' the others)\n"
      << line;
  for (const LeaveOneOutRow& row : table.rows) {
    std::snprintf(line, sizeof(line), "%2d  %14.6g %14.6g %6d  %14.6g %14.6g\n",
                  row.modes, row.shell_vertex_error, row.shell_energy,
                  row.shell_failed, row.procrustes_vertex_error,
                  row.procrustes_energy);
    out << line;
  }
  return out.str();
}

// The options of the pca workflow from the flags, --inputs loaded into
// `inputs` (at least 2, 3 with --loo).
workflows::PcaOptions PcaOptionsFromFlags(ShellSet* inputs) {
  if (FLAGS_baseline != "" && FLAGS_baseline != "procrustes") {
    throw InputError("--baseline must be 'procrustes' (or empty), got '" +
                     FLAGS_baseline + "'");
  }
  if (FLAGS_max_exp_steps < FLAGS_exp_steps) {
    throw InputError("--max_exp_steps must be at least --exp_steps");
  }
  const ShellPcaOptions pca = MakeShellPcaOptions(
      FLAGS_log_steps, FLAGS_exp_steps, FLAGS_max_exp_steps,
      ParseDisplacementKind(FLAGS_displacement, "--displacement"));
  RunPaths()
      .InputList("inputs", FLAGS_inputs)
      .InputFile("mean", FLAGS_mean)
      .OutputDirectory("output", FLAGS_output)
      .OutputPng("png", FLAGS_png)
      .OutputHtml("html", FLAGS_html)
      .Check();
  *inputs = LoadInputs(FLAGS_loo ? 3 : 2);
  CheckPcaModeCount(FLAGS_modes, static_cast<int>(inputs->shapes.size()),
                    FLAGS_loo, "--modes", "--loo");
  CheckPngMemory(1 + 2 * FLAGS_modes);  // the mean and the mode shapes
  workflows::PcaOptions options =
      OptionsOfInputs<workflows::PcaOptions>(*inputs, "pca");
  options.modes = FLAGS_modes;
  options.procrustes = FLAGS_baseline == "procrustes";
  options.leave_one_out = FLAGS_loo;
  options.amplitude = FLAGS_amplitude;
  options.pca = pca;
  if (!FLAGS_mean.empty()) {
    options.initial_mean =
        LoadCompatibleShell(FLAGS_mean, inputs->first).positions;
  }
  if (!FLAGS_quiet) {
    options.log = [](const std::string& line) {
      std::cerr << "pca: " << line << "\n";
    };
    options.leave_one_out_log = [](const std::string& line) {
      std::cerr << "loo: " << line << "\n";
    };
  }
  return options;
}

// The directory of a pca run (`summary` its summary with the run fields):
// every shape of the result as NAME.ply, pca.json and summary.json (the
// same object) whole, and the film strip of the mean and the shell mode
// shapes and their viewer page (not after a stop).
void WritePcaRun(const workflows::PcaResult& result, const Faces& faces,
                 const JsonObject& summary) {
  RunDirectory output(FLAGS_output);
  std::vector<Positions> strip;
  for (const auto& [name, positions] : result.shapes) {
    WriteMesh(Mesh{positions, faces}, output.File(name + ".ply"));
    if (name == "mean" || name.rfind("mode_", 0) == 0) {
      strip.push_back(positions);
    }
  }
  WriteFileAtomically(output.File("pca.json"), summary.str() + "\n");
  if (result.stopped_in.empty()) AddViewerPage(&output, faces, strip);
  if (!FLAGS_png.empty() && result.stopped_in.empty()) {
    const RenderOptions render = FilmStripOptionsFromFlags();
    CheckFilmStripMemory(static_cast<int>(strip.size()), render, "--png");
    output.AddOutside(FLAGS_png,
                      EncodePng(RenderFilmStrip(strip, faces, render)));
  }
  output.CommitSummary(summary.str());
}

// Flags -> options -> the workflow -> the directory and summary.
int RunPca() {
  const auto clock = std::chrono::steady_clock::now();
  ShellSet inputs;
  const workflows::PcaOptions options = PcaOptionsFromFlags(&inputs);
  const workflows::PcaResult result = workflows::RunPca(options);
  if (result.status.failed()) return FailedSolveExit("pca", result.status);
  RunStatus status("pca");
  RecordWorkflow(result.status, {}, "pca", &status);
  JsonObject json = workflows::ToJson(result, options);
  json.Add("material",
           workflows::MaterialChoiceJson(options.material, inputs.first.mesh));
  if (!result.stopped_in.empty()) {
    // Stopped: the mean so far (or the converged mean, if the stop came
    // later), no modes. The exit code is the stop's (main).
    json.Add("seconds", Seconds(clock)).Add("output", FLAGS_output);
    WritePcaRun(result, inputs.first.mesh.faces, AddRunFields(json));
    if (FLAGS_json) std::cout << json.str() << "\n";
    return 0;
  }
  WarnAboutFarInputs(result.far_input_indices, inputs.paths, result.mean,
                     "pca");
  for (size_t i = 0; i < result.failed_shapes.size() && !FLAGS_quiet; ++i) {
    std::cerr << "pca: warning: " << result.failed_shapes[i]
              << ".ply not written: " << result.failed_shape_reasons[i]
              << "\n";
  }
  json.Add("bending_model", FLAGS_bending)
      .Add("converged", status.ok())  // the mean; mode shapes: warned
      .Add("seconds", Seconds(clock))
      .Add("output", FLAGS_output);
  WritePcaRun(result, inputs.first.mesh.faces, AddRunFields(json));
  const std::string table_text =
      result.leave_one_out ? TableText(*result.leave_one_out) : "";
  if (FLAGS_json) {
    std::cout << json.str() << "\n";
    if (!FLAGS_quiet && !table_text.empty()) std::cerr << table_text;
  } else {
    if (!table_text.empty()) std::cout << table_text;
    if (!FLAGS_quiet) {
      std::cout << "eigenvalues:";
      for (int j = 0; j < result.model->eigenvalues.size(); ++j) {
        std::cout << " " << result.model->eigenvalues(j);
      }
      std::cout << "\nwrote " << FLAGS_output << "/mean.ply and "
                << result.shell_modes << " mode pairs\n";
    }
  }
  return status.Finish();
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "mean",
    "mean --inputs a.ply,b.ply,... --output M.ply [--json] (elastic mean "
    "argmin_s sum_i W[S_i, s])",
    shellspace::MeanFlags(), shellspace::RunMean);
SHELLSPACE_REGISTER_VERB(
    "pca",
    "pca --inputs a.ply,b.ply,... --modes m --output DIR [--baseline "
    "procrustes] [--loo] [--amplitude t] [--log_steps K] [--exp_steps K] "
    "[--max_exp_steps K] [--displacement log|difference] [--mean M.ply] "
    "[--threads N] "
    "[--json] [--png strip.png] [--html page.html]",
    shellspace::PcaFlags(), shellspace::RunPca);
