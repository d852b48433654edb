#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/problems/statistics/shell_pca.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/calculus/exponential_map.h"

namespace shellspace {
namespace {

Eigen::Map<const Eigen::VectorXd> Flat(const Positions& p) {
  return Eigen::Map<const Eigen::VectorXd>(p.data(), p.size());
}

void CheckOptions(const ShellPcaOptions& options) {
  if (options.steps < 1)
    throw InputError("shell PCA: steps must be at least 1");
  if (options.exp_steps < 0) {
    throw InputError("shell PCA: EXP steps must be non-negative");
  }
  if (options.max_exp_steps < std::max(options.exp_steps, 1)) {
    throw InputError("shell PCA: max EXP steps below the EXP steps");
  }
  if (!(options.max_energy_drift > 0)) {
    throw InputError("shell PCA: the energy drift bound must be positive");
  }
  if (!(options.relative_cutoff >= 0)) {
    throw InputError("shell PCA: relative cutoff must be non-negative");
  }
}

// A healthy EXP step converges by Newton (exp_step_newton.h); the LM
// fallback of ExpStep gets this many iterations in a shot before the step
// counts as failed (a step that needs more is failing and would otherwise
// run to settings.max_iterations before the safeguard can react).
constexpr int kMaxExpStepIterations = 25;

// How one EXP_K shot went.
struct ShotOutcome {
  bool ok = false;          // every step solved, drift within the bound
  int unsolved_step = 0;    // k of the first step without a solution, or 0
  double unsolved_residual = 0;  // its max |F| / max |D_2 W[s_{k-1}, s_k]|
  std::string degenerate;   // the degenerate element met at unsolved_step
  double drift = 0;         // largest relative step-energy drift so far
  bool stopped = false;     // settings.stop was set: the shot ended early
};

// One EXP_K shot from (s0, s0 + v/K), step by step. A step is solved if its
// solve is usable and either converged or left a residual |F|_inf <= 1e-6
// |D_2 W[s_{k-1}, s_k]|_inf (then hitting the iteration cap is harmless);
// the shot is ok if every step is solved and within max_drift of the first
// step's energy. The shot stops at the first unsolved step (what follows
// would be shot from a non-solution), and at the first drift violation if
// `abort_on_drift`; *end is set only if it ran to the end.
ShotOutcome ShootOnce(const ShellSpace& space, const Positions& s0,
                      const Positions& variation, int steps, double max_drift,
                      bool abort_on_drift, const SolverSettings& settings,
                      Positions* end) {
  SolverSettings step_settings = settings;
  step_settings.max_iterations =
      std::min(settings.max_iterations, kMaxExpStepIterations);
  ShotOutcome outcome;
  // A degenerate element in W[previous, current] ends the shot at step k (a
  // numerical status: the caller tries more steps).
  const auto degenerate = [&](int k, const ElementFailure& failure) {
    outcome.ok = false;
    outcome.unsolved_step = k;
    outcome.unsolved_residual = std::numeric_limits<double>::infinity();
    outcome.degenerate = failure.description;
    outcome.drift = std::numeric_limits<double>::infinity();
    return outcome;
  };
  Positions previous = s0;
  Positions current = s0 + variation / steps;
  DeformationEnergy energy;
  ElementFailure failure;
  if (!TryEvaluateDeformationEnergy(space, s0, current, &energy, &failure)) {
    return degenerate(1, failure);
  }
  const double first = energy.total;
  outcome.ok = true;
  for (int k = 2; k <= steps; ++k) {
    if (settings.stop.stop_requested()) {  // no further step: the caller stops
      outcome.ok = false;
      outcome.stopped = true;
      return outcome;
    }
    ExpStepResult step = ExpStep(space, previous, current,
                                 StepDirection::kForward, {}, step_settings);
    Eigen::VectorXd gradient;
    if (!TryEnergyGradient(space, previous, current, ShellSide::kDeformed,
                           &gradient, &failure)) {
      return degenerate(k, failure);
    }
    const double scale = gradient.cwiseAbs().maxCoeff();
    const bool solved = step.summary.IsSolutionUsable() &&
                        (step.summary.termination_type == ceres::CONVERGENCE ||
                         step.residual_norm <= 1e-6 * scale);
    if (!solved) {
      outcome.ok = false;
      outcome.unsolved_step = k;
      outcome.unsolved_residual = step.residual_norm / scale;
      outcome.drift = std::numeric_limits<double>::infinity();
      return outcome;
    }
    if (!TryEvaluateDeformationEnergy(space, current, step.shape, &energy,
                                      &failure)) {
      return degenerate(k, failure);
    }
    outcome.drift =
        std::max(outcome.drift, std::abs(energy.total - first) / first);
    if (!(outcome.drift <= max_drift)) {
      outcome.ok = false;
      if (abort_on_drift) return outcome;
    }
    previous = std::move(current);
    current = std::move(step.shape);
  }
  *end = std::move(current);
  return outcome;
}

}  // namespace

DisplacementKind ParseDisplacementKind(const std::string& value,
                                       const std::string& name) {
  if (value == "log") return DisplacementKind::kLog;
  if (value == "difference") return DisplacementKind::kAlignedDifference;
  throw InputError(name + " must be 'log' or 'difference', got '" + value +
                   "'");
}

const char* DisplacementKindName(DisplacementKind kind) {
  return kind == DisplacementKind::kLog ? "log" : "difference";
}

ShellPcaOptions MakeShellPcaOptions(int log_steps, int exp_steps,
                                    int max_exp_steps,
                                    DisplacementKind displacement) {
  ShellPcaOptions options;
  options.steps = log_steps;
  options.exp_steps = exp_steps;
  options.max_exp_steps = max_exp_steps;
  options.displacement = displacement;
  return options;
}

void CheckPcaModeCount(int modes, int inputs, bool leave_one_out,
                       const std::string& modes_name,
                       const std::string& leave_one_out_name) {
  if (modes > inputs - 1) {
    throw InputError(modes_name + " " + std::to_string(modes) + " exceeds " +
                     std::to_string(inputs - 1) + " (number of inputs - 1)");
  }
  if (leave_one_out && modes > inputs - 2) {
    throw InputError(leave_one_out_name + " with " + modes_name + " " +
                     std::to_string(modes) + " needs at least " +
                     std::to_string(modes + 2) + " inputs");
  }
}

bool TryShootFromMean(const ShellSpace& space, const Positions& mean,
                      const Positions& variation,
                      const ShellPcaOptions& options,
                      const SolverSettings& settings, Positions* shot,
                      ExpShotReport* report) {
  CheckOptions(options);
  ExpShotReport local;
  ExpShotReport& r = report ? *report : local;
  r = ExpShotReport{};
  if (variation.cwiseAbs().maxCoeff() == 0) {
    r.ok = true;
    *shot = mean;
    return true;
  }
  int steps = options.exp_steps > 0 ? options.exp_steps : options.steps;
  steps = std::min(steps, options.max_exp_steps);
  for (;;) {
    const bool last = 2 * steps > options.max_exp_steps;
    ++r.attempts;
    r.steps = steps;
    Positions end;
    const ShotOutcome outcome =
        ShootOnce(space, mean, variation, steps, options.max_energy_drift,
                  !last, settings, &end);
    r.energy_drift = outcome.drift;
    if (outcome.stopped) {
      r.failure = "EXP shot: stopped on request at EXP_" +
                  std::to_string(steps) + " (attempt " +
                  std::to_string(r.attempts) + ")";
      return false;
    }
    if (last && outcome.unsolved_step > 0) {
      char text[300];
      if (outcome.degenerate.empty()) {
        std::snprintf(text, sizeof(text),
                      "EXP shot: step %d of EXP_%d has no solution (max |F| "
                      "= %.3g of |D_2 W|) after %d attempt(s) up to K = %d",
                      outcome.unsolved_step, steps, outcome.unsolved_residual,
                      r.attempts, steps);
      } else {
        std::snprintf(text, sizeof(text),
                      "EXP shot: step %d of EXP_%d meets a degenerate %s "
                      "after %d attempt(s) up to K = %d",
                      outcome.unsolved_step, steps, outcome.degenerate.c_str(),
                      r.attempts, steps);
      }
      r.failure = text;
      return false;
    }
    if (outcome.ok || last) {
      r.ok = outcome.ok;
      *shot = std::move(end);
      return true;
    }
    steps *= 2;
  }
}

Positions ShootFromMean(const ShellSpace& space, const Positions& mean,
                        const Positions& variation,
                        const ShellPcaOptions& options,
                        const SolverSettings& settings, ExpShotReport* report) {
  ExpShotReport local;
  ExpShotReport& r = report ? *report : local;
  Positions shot;
  if (!TryShootFromMean(space, mean, variation, options, settings, &shot, &r)) {
    throw InputError(r.failure);
  }
  return shot;
}

ShellMetric::ShellMetric(const ShellSpace& space, const Positions& at)
    : hessian_(EnergyHessian(space, at, at, ShellSide::kDeformed,
                             ShellSide::kDeformed)) {}

double ShellMetric::Inner(const Positions& u, const Positions& w) const {
  if (u.size() != hessian_.rows() || w.size() != hessian_.rows()) {
    throw InputError("shell metric: variation of the wrong size");
  }
  return 0.5 * Flat(u).dot(hessian_ * Flat(w));
}

double ShellMetric::Norm(const Positions& u) const {
  return std::sqrt(std::max(0.0, Inner(u, u)));
}

Eigen::MatrixXd ShellGram(const ShellMetric& metric,
                          const std::vector<Positions>& displacements) {
  const int n = static_cast<int>(displacements.size());
  const Eigen::Index size = metric.hessian().rows();
  Eigen::MatrixXd v(size, n);
  for (int i = 0; i < n; ++i) {
    if (displacements[i].size() != size) {
      throw InputError("shell metric: a displacement of the wrong size");
    }
    v.col(i) = Flat(displacements[i]);
  }
  const Eigen::MatrixXd hv = metric.hessian() * v;
  return 0.5 * v.transpose() * hv / std::max(n, 1);
}

GramModes ModesFromGram(const Eigen::MatrixXd& gram,
                        const std::vector<Positions>& displacements,
                        double relative_cutoff) {
  const int n = static_cast<int>(displacements.size());
  if (n == 0 || gram.rows() != n || gram.cols() != n) {
    throw InputError("PCA: Gram matrix does not match the displacements");
  }
  const Eigen::MatrixXd symmetric = 0.5 * (gram + gram.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(symmetric);
  // Eigen sorts ascending; reverse to lambda_1 >= lambda_2 >= ...
  GramModes result;
  result.eigenvalues = solver.eigenvalues().reverse();
  const Eigen::MatrixXd vectors = solver.eigenvectors().rowwise().reverse();
  const double largest = std::max(result.eigenvalues(0), 0.0);
  for (int j = 0; j < n; ++j) {
    const double lambda = result.eigenvalues(j);
    if (!(lambda > relative_cutoff * largest) || !(lambda > 0)) break;
    Positions mode = Positions::Zero(displacements[0].rows(), 3);
    for (int i = 0; i < n; ++i) mode += vectors(i, j) * displacements[i];
    mode /= std::sqrt(n * lambda);
    // Sign convention: the largest-magnitude coefficient positive.
    Eigen::Index k = 0;
    vectors.col(j).cwiseAbs().maxCoeff(&k);
    if (vectors(k, j) < 0) mode = -mode;
    result.modes.push_back(std::move(mode));
  }
  return result;
}

ShellPath WarmLogPath(const ShellPath& old, const Positions& mean,
                      const Positions& end) {
  const int steps = static_cast<int>(old.size()) - 1;
  if (steps < 1 || old[0].rows() != mean.rows() ||
      end.rows() != mean.rows()) {
    throw InputError("warm LOG path: wrong number of shapes or vertices");
  }
  const Positions start_shift = mean - AlignRigidly(old[0], mean);
  const Positions end_shift = end - AlignRigidly(old[steps], end);
  ShellPath path(steps + 1);
  for (int k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    const Positions linear = (1 - t) * mean + t * end;
    path[k] = AlignRigidly(old[k], linear) + (1 - t) * start_shift +
              t * end_shift;
  }
  path.front() = mean;
  path.back() = end;
  return path;
}

Positions ShellDisplacement(const ShellSpace& space, const Positions& mean,
                            const Positions& shape,
                            const ShellPcaOptions& options,
                            const SolverSettings& settings,
                            const ShellPath* warm, GeodesicResult* geodesic) {
  CheckOptions(options);
  const Positions aligned = AlignRigidly(shape, mean);
  if (options.displacement == DisplacementKind::kAlignedDifference) {
    return aligned - mean;
  }
  ShellPath initial;
  if (warm != nullptr) {
    if (static_cast<int>(warm->size()) != options.steps + 1) {
      throw InputError("shell PCA: a warm LOG path needs K + 1 shapes");
    }
    initial = WarmLogPath(*warm, mean, aligned);
  }
  return LogK(space, mean, aligned, options.steps, {}, settings, geodesic,
              warm != nullptr ? &initial : nullptr);
}

ShellPcaModel ComputeShellPca(const ShellSpace& space, const Positions& mean,
                              const std::vector<Positions>& shapes,
                              const ShellPcaOptions& options,
                              const SolverSettings& settings,
                              const std::vector<ShellPath>* warm) {
  CheckOptions(options);
  CheckShapeSet(space, shapes, "shell PCA");
  CheckShapeSet(space, {mean}, "shell PCA mean");
  if (warm != nullptr && warm->size() != shapes.size()) {
    throw InputError("shell PCA: one warm LOG path per shape needed");
  }
  ShellPcaModel model{mean, {}, {}, {}, {}, ShellMetric(space, mean), {}};
  const int n = static_cast<int>(shapes.size());
  const bool log = options.displacement == DisplacementKind::kLog;
  if (log) model.log_paths.resize(n);
  for (int i = 0; i < n; ++i) {
    GeodesicResult geodesic;
    model.displacements.push_back(
        ShellDisplacement(space, mean, shapes[i], options, settings,
                          warm != nullptr ? &(*warm)[i] : nullptr, &geodesic));
    if (log) {
      model.log_paths[i] = std::move(geodesic.path);
      model.log_iterations += geodesic.iterations;
    }
  }
  model.gram = ShellGram(model.metric, model.displacements);
  GramModes modes =
      ModesFromGram(model.gram, model.displacements, options.relative_cutoff);
  model.eigenvalues = std::move(modes.eigenvalues);
  model.modes = std::move(modes.modes);
  return model;
}

bool TryShellModeShape(const ShellSpace& space, const ShellPcaModel& model,
                       int j, double t, const ShellPcaOptions& options,
                       const SolverSettings& settings, Positions* shape,
                       ExpShotReport* report) {
  CheckOptions(options);
  if (j < 0 || j >= static_cast<int>(model.modes.size())) {
    throw InputError("shell PCA: mode " + std::to_string(j + 1) +
                     " does not exist (the model has " +
                     std::to_string(model.modes.size()) + ")");
  }
  const Positions variation =
      t * std::sqrt(model.eigenvalues(j)) * model.modes[j];
  if (!TryShootFromMean(space, model.mean, variation, options, settings,
                        shape, report)) {
    return false;
  }
  *shape = AlignRigidly(*shape, model.mean);
  return true;
}

Positions ShellModeShape(const ShellSpace& space, const ShellPcaModel& model,
                         int j, double t, const ShellPcaOptions& options,
                         const SolverSettings& settings) {
  ExpShotReport report;
  Positions shape;
  if (!TryShellModeShape(space, model, j, t, options, settings, &shape,
                         &report)) {
    throw InputError(report.failure);
  }
  return shape;
}

Eigen::VectorXd ShellModeCoefficients(const ShellPcaModel& model,
                                      const Positions& v, int m) {
  if (m < 0 || m > static_cast<int>(model.modes.size())) {
    throw InputError("shell PCA: " + std::to_string(m) +
                     " modes requested, the model has " +
                     std::to_string(model.modes.size()));
  }
  Eigen::VectorXd c(m);
  for (int j = 0; j < m; ++j) c(j) = model.metric.Inner(v, model.modes[j]);
  return c;
}

bool TryShellFromCoefficients(const ShellSpace& space,
                              const ShellPcaModel& model,
                              const Eigen::VectorXd& coefficients,
                              const ShellPcaOptions& options,
                              const SolverSettings& settings, Positions* shell,
                              ExpShotReport* report) {
  CheckOptions(options);
  const int m = static_cast<int>(coefficients.size());
  if (m > static_cast<int>(model.modes.size())) {
    throw InputError("shell PCA: more coefficients than modes");
  }
  Positions variation = Positions::Zero(model.mean.rows(), 3);
  for (int j = 0; j < m; ++j) variation += coefficients(j) * model.modes[j];
  if (!TryShootFromMean(space, model.mean, variation, options, settings,
                        shell, report)) {
    return false;
  }
  *shell = AlignRigidly(*shell, model.mean);
  return true;
}

Positions ShellFromCoefficients(const ShellSpace& space,
                                const ShellPcaModel& model,
                                const Eigen::VectorXd& coefficients,
                                const ShellPcaOptions& options,
                                const SolverSettings& settings,
                                ExpShotReport* report) {
  ExpShotReport local;
  ExpShotReport& r = report ? *report : local;
  Positions shell;
  if (!TryShellFromCoefficients(space, model, coefficients, options, settings,
                                &shell, &r)) {
    throw InputError(r.failure);
  }
  return shell;
}

}  // namespace shellspace
