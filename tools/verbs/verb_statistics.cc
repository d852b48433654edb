// `shellspace mean` and `shellspace pca`: the elastic mean of a set of shells,
// shell PCA at that mean (modes shot by EXP_K), the Procrustes PCA baseline,
// and the leave-one-out comparison of the two (calculus.md, "Elastic mean and
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
#include "tools/run/stop_request.h"
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
                       1),
           TextFlag("baseline",
                    "'procrustes' also writes the Procrustes PCA model "
                    "(procrustes_mean.ply, "
                    "procrustes_mode_J_{minus,plus}.ply); '' none"),
           TextFlag("loo",
                    "leave-one-out evaluation of shell vs Procrustes PCA "
                    "(m = 0..modes), table printed and in the JSON"),
           RealFlag("amplitude",
                    "mode shapes at +- amplitude sqrt(lambda_j) w_j", 0,
                    End::kClosed),
           IntegerFlag("log_steps", "K of LOG_K (displacements)", 1),
           IntegerFlag("exp_steps",
                       "K of EXP_K (mode shapes, reconstructions); doubled up "
                       "to --max_exp_steps while a shot fails or its step "
                       "energies drift by more than 50%",
                       1),
           IntegerFlag("max_exp_steps",
                       "largest K of the EXP safeguard (>= --exp_steps)", 1),
           TextFlag("displacement",
                    "'log' (v_i = LOG_K(mean -> S_i)) or 'difference' "
                    "(v_i = S_i - mean after rigid alignment)"),
           TextFlag("png",
                    "also write a PNG film strip of the mean and the modes"),
           TextFlag("mean",
                    "an elastic mean of the inputs computed before (e.g. by "
                    "`shellspace mean`): the mean solve starts there and "
                    "only checks it (no iterations if it meets the "
                    "tolerance)"),
       },
       MaterialFlags(), SolverFlags(), JsonFlag(), FilmStripFlags()});
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

void CheckSolve(const ceres::Solver::Summary& summary, const char* what) {
  if (summary.termination_type == ceres::FAILURE) {
    throw InputError(std::string(what) + " failed: " + summary.message);
  }
}

// The inputs far from the others (FarInputs), by path, each with a warning
// on stderr unless --quiet: such an input dominates the mean and the leading
// shell PCA mode, and EXP shots along that mode may have no solution.
std::vector<std::string> WarnAboutFarInputs(const ShellSet& inputs,
                                            const ElasticMeanResult& mean,
                                            const char* verb) {
  std::vector<std::string> far;
  const double median = Median(mean.energies);
  for (int i : FarInputs(mean.energies)) {
    far.push_back(inputs.paths[i]);
    if (FLAGS_quiet) continue;
    char text[160];
    std::snprintf(text, sizeof(text),
                  ": W[S, mean] = %.4g, %.0f times the median %.4g",
                  mean.energies[i], mean.energies[i] / median, median);
    std::cerr << verb << ": warning: input " << inputs.paths[i]
              << " is far from the others" << text << "\n";
  }
  return far;
}

// Records whether the elastic mean met its stopping criterion.
void CheckMean(const ElasticMeanResult& mean, const std::string& what,
               RunStatus* status) {
  status->Require(mean.converged,
                  what + ": " +
                      GradientAboveTarget(mean.gradient_norm,
                                          mean.gradient_target) +
                      " after " + std::to_string(mean.lm_iterations) +
                      " LM + " +
                      std::to_string(mean.newton_iterations) +
                      " Newton iterations (" + mean.termination + ")");
}

int RunMean() {
  const auto clock = std::chrono::steady_clock::now();
  RunPaths()
      .InputList("inputs", FLAGS_inputs)
      .OutputFile("output", FLAGS_output)
      .Check();
  const ShellSet inputs = LoadInputs(1);
  const ShellSpace space = SpaceFromFlags(inputs.first);
  const ElasticMeanResult result =
      ComputeElasticMean(space, inputs.shapes, SettingsFromFlags("mean"));
  CheckSolve(result.summary, "elastic mean");
  const std::vector<std::string> far =
      WarnAboutFarInputs(inputs, result, "mean");
  if (FLAGS_report) std::cerr << result.summary.FullReport() << "\n";
  RunStatus status("mean");
  CheckMean(result, "elastic mean", &status);
  WriteMesh(Mesh{result.mean, inputs.first.mesh.faces}, FLAGS_output);
  if (FLAGS_json) {
    JsonObject json =
        MeanJson(result, static_cast<int>(inputs.shapes.size()), far);
    json.Add("bending_model", FLAGS_bending)
        .Raw("energy_split", MeanEnergySplitJson(space, result.mean,
                                                 inputs.shapes));
    std::cout << AddRunFields(json)
                     .Add("seconds", Seconds(clock))
                     .Add("output", FLAGS_output)
                     .str()
              << "\n";
  } else if (!FLAGS_quiet) {
    std::cerr << result.summary.BriefReport() << "\n";
    std::cout << "sum_i W[S_i, mean] = " << result.energy << " over "
              << inputs.shapes.size() << " shells (" << result.lm_iterations
              << " LM + " << result.newton_iterations
              << " Newton iterations, |grad| " << result.gradient_norm
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

int RunPca() {
  if (FLAGS_baseline != "" && FLAGS_baseline != "procrustes") {
    throw InputError("--baseline must be 'procrustes' (or empty), got '" +
                     FLAGS_baseline + "'");
  }
  if (FLAGS_max_exp_steps < FLAGS_exp_steps) {
    throw InputError("--max_exp_steps must be at least --exp_steps");
  }
  const ShellPcaOptions options =
      MakeShellPcaOptions(FLAGS_log_steps, FLAGS_exp_steps,
                          FLAGS_max_exp_steps, FLAGS_displacement, "--");
  const auto clock = std::chrono::steady_clock::now();
  RunPaths()
      .InputList("inputs", FLAGS_inputs)
      .OutputDirectory("output", FLAGS_output)
      .OutputFile("png", FLAGS_png)
      .Check();
  const ShellSet inputs = LoadInputs(FLAGS_loo ? 3 : 2);
  const int n = static_cast<int>(inputs.shapes.size());
  CheckPcaModeCount(FLAGS_modes, n, FLAGS_loo, "--");
  const ShellSpace space = SpaceFromFlags(inputs.first);
  const SolverSettings settings = SettingsFromFlags("pca");
  SolverSettings inner = settings;
  inner.progress = false;
  // A stop (--time_limit, SIGINT, SIGTERM) in any phase ends the run with the
  // mean alone, marked partial: a LOG or EXP shot stopped midway would give a
  // wrong mode, so modes are written only by a run that was not stopped.

  // Shell model.
  Positions given_mean;
  if (!FLAGS_mean.empty()) {
    given_mean = LoadCompatibleShell(FLAGS_mean, inputs.first).positions;
  }
  if (!FLAGS_quiet) {
    std::cerr << "pca: elastic mean of " << n << " shells"
              << (FLAGS_mean.empty() ? "" : " from " + FLAGS_mean) << "\n";
  }
  const ElasticMeanResult mean = ComputeElasticMean(
      space, inputs.shapes, settings,
      FLAGS_mean.empty() ? nullptr : &given_mean);
  CheckSolve(mean.summary, "elastic mean");
  RunStatus status("pca");
  CheckMean(mean, "the elastic mean", &status);
  // Stopped: the mean so far (or the converged mean, if the stop came
  // later), no modes. The exit code is the stop's (main).
  const auto write_mean_only = [&](const char* phase) {
    JsonObject json = PcaMeanJson(n, mean);
    json.Add("modes", 0)
        .Add("stopped_in", phase)
        .Add("seconds", Seconds(clock))
        .Add("output", FLAGS_output);
    AddRunFields(json);
    RunDirectory output(FLAGS_output);
    WriteMesh(Mesh{mean.mean, inputs.first.mesh.faces},
              output.File("mean.ply"));
    WriteFileAtomically(output.File("pca.json"), json.str() + "\n");
    output.CommitSummary(json.str());
    if (FLAGS_json) std::cout << json.str() << "\n";
    return 0;
  };
  if (ObservedStop() != StopCause::kNone) return write_mean_only("mean");
  const std::vector<std::string> far = WarnAboutFarInputs(inputs, mean, "pca");
  if (!FLAGS_quiet) {
    std::cerr << "pca: elastic mean done (" << mean.lm_iterations << " LM + "
              << mean.newton_iterations << " Newton iterations, "
              << Seconds(clock) << " s); displacements ("
              << FLAGS_displacement << ") and the Gram matrix\n";
  }
  const ShellPcaModel shell =
      ComputeShellPca(space, mean.mean, inputs.shapes, options, inner);
  if (ObservedStop() != StopCause::kNone) {
    return write_mean_only("displacements");
  }
  const int shell_modes =
      std::min<int>(FLAGS_modes, static_cast<int>(shell.modes.size()));
  if (!FLAGS_quiet) {
    std::cerr << "pca: shell PCA done (" << Seconds(clock) << " s); "
              << 2 * shell_modes << " mode shapes by EXP_K\n";
  }
  std::vector<std::pair<std::string, Positions>> files = {
      {"mean.ply", mean.mean}};  // written at the end, with pca.json
  std::vector<Positions> strip = {mean.mean};
  // A mode shape whose EXP shot has no solution (TryShellModeShape false)
  // is not written; it is listed in the JSON and warned about.
  std::vector<std::string> failed_shapes;
  for (int j = 0; j < shell_modes; ++j) {
    for (const double sign : {-1.0, 1.0}) {
      // No new shot once a stop is requested (the mean is written alone).
      if (ObservedStop() != StopCause::kNone) break;
      const std::string name = "mode_" + std::to_string(j + 1) +
                               (sign < 0 ? "_minus.ply" : "_plus.ply");
      Positions shape;
      ExpShotReport shot;
      if (TryShellModeShape(space, shell, j, sign * FLAGS_amplitude, options,
                            inner, &shape, &shot)) {
        files.emplace_back(name, shape);
        strip.push_back(std::move(shape));
      } else {
        failed_shapes.push_back(name);
        if (!FLAGS_quiet) {
          std::cerr << "pca: warning: " << name
                    << " not written: " << shot.failure << "\n";
        }
      }
    }
  }
  if (ObservedStop() != StopCause::kNone) return write_mean_only("mode shapes");
  if (!FLAGS_quiet) std::cerr << "pca: shell modes done\n";

  JsonObject json = PcaJson(n, mean, FLAGS_displacement, options, shell,
                            shell_modes, failed_shapes, far, FLAGS_amplitude);
  json.Add("bending_model", FLAGS_bending)
      .Add("converged", status.ok());  // the mean; mode shapes: warned

  if (FLAGS_baseline == "procrustes") {
    for (auto& [name, shape] :
         AddProcrustesBaseline(ComputeProcrustesPca(inputs.shapes), FLAGS_modes,
                               FLAGS_amplitude, &json)) {
      files.emplace_back(name + ".ply", std::move(shape));
    }
  }

  std::string table_text;
  if (FLAGS_loo) {
    LeaveOneOutOptions loo;
    loo.max_modes = FLAGS_modes;
    loo.pca = options;
    loo.initial_mean = mean.mean;  // warm start; same minimiser per fold
    if (!FLAGS_quiet) {
      loo.log = [](const std::string& line) {
        std::cerr << "loo: " << line << "\n";
      };
    }
    const LeaveOneOutTable table =
        EvaluateLeaveOneOut(space, inputs.shapes, loo, inner);
    if (ObservedStop() != StopCause::kNone) {
      return write_mean_only("leave-one-out");
    }
    json.Raw("leave_one_out", LeaveOneOutJson(table));
    table_text = TableText(table);
  }
  json.Add("seconds", Seconds(clock)).Add("output", FLAGS_output);
  AddRunFields(json);

  // All results computed: write the directory (the PLY set, pca.json and
  // summary.json, the same object) whole, then the film strip.
  RunDirectory output(FLAGS_output);
  for (const auto& [name, positions] : files) {
    WriteMesh(Mesh{positions, inputs.first.mesh.faces}, output.File(name));
  }
  WriteFileAtomically(output.File("pca.json"), json.str() + "\n");
  if (!FLAGS_png.empty()) {
    const RenderOptions render = FilmStripOptionsFromFlags();
    output.AddOutside(
        FLAGS_png,
        EncodePng(RenderFilmStrip(strip, inputs.first.mesh.faces, render)));
  }
  output.CommitSummary(json.str());
  if (FLAGS_json) {
    std::cout << json.str() << "\n";
    if (!FLAGS_quiet && !table_text.empty()) std::cerr << table_text;
  } else {
    if (!table_text.empty()) std::cout << table_text;
    if (!FLAGS_quiet) {
      std::cout << "eigenvalues:";
      for (int j = 0; j < shell.eigenvalues.size(); ++j) {
        std::cout << " " << shell.eigenvalues(j);
      }
      std::cout << "\nwrote " << FLAGS_output << "/mean.ply and " << shell_modes
                << " mode pairs\n";
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
    "[--json] [--png strip.png]",
    shellspace::PcaFlags(), shellspace::RunPca);
