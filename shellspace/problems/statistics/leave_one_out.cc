#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/problems/statistics/leave_one_out.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <string>

#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/statistics/procrustes_pca.h"

namespace shellspace {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since)
      .count();
}

// W[truth, reconstruction], or NaN if the reconstruction has a degenerate
// triangle.
double EnergyToTruth(const ShellSpace& space, const Positions& truth,
                     const Positions& reconstruction) {
  DeformationEnergy w;
  return TryEvaluateDeformationEnergy(space, truth, reconstruction, &w)
             ? w.total
             : std::numeric_limits<double>::quiet_NaN();
}

// Passes `line` to options.log, if set.
void LogLine(const LeaveOneOutOptions& options, const std::string& line) {
  if (options.log) options.log(line);
}

// The folds to run: options.held_out, or every shape if it is empty. Throws
// InputError on fewer than 3 shapes, negative modes or an index out of range.
std::vector<int> CheckedFolds(int n, const LeaveOneOutOptions& options) {
  if (n < 3) throw InputError("leave-one-out needs at least 3 shapes");
  if (options.max_modes < 0) throw InputError("leave-one-out: modes < 0");
  std::vector<int> folds = options.held_out;
  if (folds.empty()) {
    for (int h = 0; h < n; ++h) folds.push_back(h);
  }
  for (int h : folds) {
    if (h < 0 || h >= n) {
      throw InputError("leave-one-out: held-out index " + std::to_string(h) +
                       " out of range");
    }
  }
  return folds;
}

// The LOG_K geodesics from options.initial_mean to every shape S_i,
// i = 0..n-1 (logs how long they took).
std::vector<ShellPath> WarmLogPaths(const ShellSpace& space,
                                    const std::vector<Positions>& shapes,
                                    const LeaveOneOutOptions& options,
                                    const SolverSettings& settings) {
  std::vector<ShellPath> warm_paths;
  const auto warm_clock = std::chrono::steady_clock::now();
  for (const Positions& shape : shapes) {
    GeodesicResult geodesic;
    ShellDisplacement(space, options.initial_mean, shape, options.pca, settings,
                      nullptr, &geodesic);
    warm_paths.push_back(std::move(geodesic.path));
  }
  char line[96];
  std::snprintf(line, sizeof(line), "LOG paths from the initial mean (%.1f s)",
                SecondsSince(warm_clock));
  LogLine(options, line);
  return warm_paths;
}

// Appends to `fold` the errors of the shell and Procrustes reconstructions of
// `truth` from their first m modes (fewer if a model has fewer); c holds the
// truth's shell mode coefficients.
void AddReconstructionErrors(
    const ShellSpace& space, const ShellPcaModel& shell,
    const Eigen::VectorXd& c, const ProcrustesPcaModel& procrustes,
    const Positions& truth, int m, const LeaveOneOutOptions& options,
    const SolverSettings& settings, LeaveOneOutFold* fold) {
  const int ms = std::min<int>(m, static_cast<int>(shell.modes.size()));
  ExpShotReport shot;
  Positions shell_reconstruction;
  if (TryShellFromCoefficients(space, shell, c.head(ms), options.pca, settings,
                               &shell_reconstruction, &shot)) {
    fold->shell_vertex_error.push_back(
        MeanVertexErrorUpToRigidMotion(shell_reconstruction, truth));
    fold->shell_energy.push_back(
        EnergyToTruth(space, truth, shell_reconstruction));
  } else {
    shot.ok = false;
    fold->shell_vertex_error.push_back(
        std::numeric_limits<double>::quiet_NaN());
    fold->shell_energy.push_back(std::numeric_limits<double>::quiet_NaN());
  }
  fold->shell_shots.push_back(shot);

  const int mp = std::min<int>(m, static_cast<int>(procrustes.modes.size()));
  const Positions procrustes_reconstruction =
      ProcrustesReconstruct(procrustes, truth, mp);
  fold->procrustes_vertex_error.push_back(
      MeanVertexErrorUpToRigidMotion(procrustes_reconstruction, truth));
  fold->procrustes_energy.push_back(
      EnergyToTruth(space, truth, procrustes_reconstruction));
}

// One fold: both models from every shape but shapes[h] (the elastic mean
// started from initial_mean if not null, the LOGs from warm_paths if not
// empty), and the errors of their reconstructions of shapes[h] from
// m = 0 .. num_m - 1 modes.
LeaveOneOutFold EvaluateFold(const ShellSpace& space,
                             const std::vector<Positions>& shapes, int h,
                             const Positions* initial_mean,
                             const std::vector<ShellPath>& warm_paths,
                             int num_m, const LeaveOneOutOptions& options,
                             const SolverSettings& settings) {
  const auto fold_clock = std::chrono::steady_clock::now();
  const int n = static_cast<int>(shapes.size());
  std::vector<Positions> others;
  std::vector<ShellPath> others_warm;
  for (int i = 0; i < n; ++i) {
    if (i == h) continue;
    others.push_back(shapes[i]);
    if (!warm_paths.empty()) others_warm.push_back(warm_paths[i]);
  }
  const bool warm_log = !warm_paths.empty();
  const Positions& truth = shapes[h];
  LeaveOneOutFold fold;
  fold.held_out = h;

  const ElasticMeanResult mean =
      ComputeElasticMean(space, others, settings, initial_mean);
  fold.mean_energy = mean.energy;
  fold.mean_iterations = mean.lm_iterations;
  fold.mean_newton_iterations = mean.newton_iterations;
  fold.mean_converged = mean.converged;
  const ShellPcaModel shell =
      ComputeShellPca(space, mean.mean, others, options.pca, settings,
                      warm_log ? &others_warm : nullptr);
  fold.shell_eigenvalues = shell.eigenvalues;
  GeodesicResult truth_log;
  const Positions v =
      ShellDisplacement(space, shell.mean, truth, options.pca, settings,
                        warm_log ? &warm_paths[h] : nullptr, &truth_log);
  fold.log_iterations = shell.log_iterations + truth_log.iterations;
  const Eigen::VectorXd c =
      ShellModeCoefficients(shell, v, static_cast<int>(shell.modes.size()));

  const ProcrustesPcaModel procrustes = ComputeProcrustesPca(others);
  fold.procrustes_eigenvalues = procrustes.eigenvalues;

  for (int m = 0; m < num_m; ++m) {
    AddReconstructionErrors(space, shell, c, procrustes, truth, m, options,
                            settings, &fold);
  }
  fold.seconds = SecondsSince(fold_clock);
  return fold;
}

// The progress line of a finished fold, the `number`-th one.
std::string FoldLogLine(const LeaveOneOutFold& fold, size_t number, int num_m) {
  std::string text = "fold " + std::to_string(number) + " (held out " +
                     std::to_string(fold.held_out) + "):";
  for (int m = 0; m < num_m; ++m) {
    char item[200];
    std::snprintf(item, sizeof(item),
                  " m=%d shell %.4g/%.4g (K=%d%s) procrustes %.4g/%.4g;", m,
                  fold.shell_vertex_error[m], fold.shell_energy[m],
                  fold.shell_shots[m].steps,
                  fold.shell_shots[m].ok ? "" : " FAILED",
                  fold.procrustes_vertex_error[m], fold.procrustes_energy[m]);
    text += item;
  }
  char tail[128];
  std::snprintf(tail, sizeof(tail),
                " mean %d LM + %d Newton%s, LOGs %d iterations (%.1f s)",
                fold.mean_iterations, fold.mean_newton_iterations,
                fold.mean_converged ? "" : " NOT CONVERGED",
                fold.log_iterations, fold.seconds);
  return text + tail;
}

// Row m of the table: the folds' errors for m modes, averaged (the shell's
// over the folds whose shot succeeded).
LeaveOneOutRow AverageRow(const std::vector<LeaveOneOutFold>& folds, int m) {
  LeaveOneOutRow row;
  row.modes = m;
  int shell_count = 0;
  for (const LeaveOneOutFold& fold : folds) {
    row.procrustes_vertex_error += fold.procrustes_vertex_error[m];
    row.procrustes_energy += fold.procrustes_energy[m];
    if (!fold.shell_shots[m].ok) {
      ++row.shell_failed;
      continue;
    }
    ++shell_count;
    row.shell_vertex_error += fold.shell_vertex_error[m];
    row.shell_energy += fold.shell_energy[m];
    row.procrustes_vertex_error_shell_folds += fold.procrustes_vertex_error[m];
    row.procrustes_energy_shell_folds += fold.procrustes_energy[m];
  }
  const double count = static_cast<double>(folds.size());
  row.procrustes_vertex_error /= count;
  row.procrustes_energy /= count;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double shell = shell_count > 0 ? 1.0 / shell_count : nan;
  row.shell_vertex_error *= shell;
  row.shell_energy *= shell;
  row.procrustes_vertex_error_shell_folds *= shell;
  row.procrustes_energy_shell_folds *= shell;
  return row;
}

}  // namespace

double MeanVertexErrorUpToRigidMotion(const Positions& reconstruction,
                                      const Positions& truth) {
  if (reconstruction.rows() != truth.rows() || truth.rows() == 0) {
    throw InputError("vertex error: shapes of different sizes");
  }
  const Positions aligned = AlignRigidly(reconstruction, truth);
  return (aligned - truth).rowwise().norm().mean();
}

LeaveOneOutTable EvaluateLeaveOneOut(const ShellSpace& space,
                                     const std::vector<Positions>& shapes,
                                     const LeaveOneOutOptions& options,
                                     const SolverSettings& settings) {
  const auto clock = std::chrono::steady_clock::now();
  CheckShapeSet(space, shapes, "leave-one-out");
  const std::vector<int> folds =
      CheckedFolds(static_cast<int>(shapes.size()), options);

  const bool warm = options.initial_mean.size() > 0;
  if (warm) CheckShapeSet(space, {options.initial_mean}, "leave-one-out start");

  std::vector<ShellPath> warm_paths;  // initial_mean -> S_i, i = 0..n-1
  if (warm && options.warm_logs &&
      options.pca.displacement == DisplacementKind::kLog) {
    warm_paths = WarmLogPaths(space, shapes, options, settings);
  }

  const int num_m = options.max_modes + 1;
  LeaveOneOutTable table;
  for (int h : folds) {
    LeaveOneOutFold fold =
        EvaluateFold(space, shapes, h, warm ? &options.initial_mean : nullptr,
                     warm_paths, num_m, options, settings);
    LogLine(options, FoldLogLine(fold, table.folds.size() + 1, num_m));
    table.folds.push_back(std::move(fold));
  }

  for (int m = 0; m < num_m; ++m) {
    table.rows.push_back(AverageRow(table.folds, m));
  }
  table.seconds = SecondsSince(clock);
  return table;
}

}  // namespace shellspace
