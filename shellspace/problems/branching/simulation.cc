#include "shellspace/problems/branching/simulation.h"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "shellspace/geometry/mesh.h"
#include "shellspace/problems/branching/construction_optimizer.h"
#include "shellspace/problems/branching/field_transfer.h"
#include "shellspace/problems/branching/initial_guess.h"
#include "shellspace/problems/branching/km_family.h"
#include "shellspace/problems/branching/self_similar_series.h"

namespace shellspace::branching {

double SimulationSettings::Delta() const {
  return delta > 0.0 ? delta : 3.0 * height / ny;
}

void CheckSimulationSettings(const SimulationSettings& s) {
  if (!(s.epsilon > 0) || !std::isfinite(s.epsilon)) {
    throw InputError("branching simulation: the twin-boundary energy epsilon must be a positive number");
  }
  if (!(s.length > 0) || !std::isfinite(s.length)) {
    throw InputError("branching simulation: the domain length L must be a positive number");
  }
  if (!(s.height > 0) || !std::isfinite(s.height)) {
    throw InputError("branching simulation: the domain height H must be a positive number");
  }
  if (s.nx < 2 || s.nx > 4096) throw InputError("branching simulation: the number of x-cells nx must lie in [2, 4096]");
  if (s.ny < 8 || s.ny > 8192) throw InputError("branching simulation: the number of y-nodes ny must lie in [8, 8192]");
  if (!(s.grading >= 1.0 && s.grading <= 4.0)) {
    throw InputError("branching simulation: the x-grading exponent must lie in [1, 4]");
  }
  if (s.delta < 0 || !std::isfinite(s.delta)) {
    throw InputError("branching simulation: the interface width delta must be >= 0 (0: 3 dy)");
  }
  if (s.delta > 0 && s.height / s.ny > s.delta / 2.0) {
    throw InputError("branching simulation: the interface width delta is not resolved: need H/ny <= delta/2");
  }
  if (s.continuation < 1 || s.continuation > 8) {
    throw InputError("branching simulation: the number of continuation stages must lie in [1, 8]");
  }
  try {
    CheckInitialGuessName(s.init);
  } catch (const InputError& e) {
    throw InputError(std::string("branching simulation: the initial guess ") +
                     e.what());
  }
  if (s.periods < 0) throw InputError("branching simulation: the number of periods must be >= 0");
  if (s.max_iterations < 0) throw InputError("branching simulation: the LM iterations per stage must be >= 0");
}

void CheckInitialGuessName(const std::string& init) {
  if (init != "laminate" && init != "random" && init != "km" &&
      init != "needle" && init != "lens") {
    throw InputError("must be laminate, random, km, needle or lens, got '" +
                     init + "'");
  }
}

std::string SimulationBreakdown(const SimulationResult& result) {
  if (!result.stages.empty() &&
      result.stages.back().termination == "COLLAPSED") {
    return "the pattern collapsed to u = 0 at delta " +
           std::to_string(result.stages.back().delta) +
           " (max |u_y| < 0.5): the grid cannot hold it; use more y-nodes "
           "or a smaller delta";
  }
  if (!std::isfinite(result.energy.total())) {
    return "the energy is not finite (" +
           std::to_string(result.energy.total()) +
           "): epsilon, length and height this far apart leave the grid no "
           "resolution";
  }
  return "";
}

SimulationResult InitialSimulation(const SimulationSettings& s) {
  CheckSimulationSettings(s);
  SimulationResult result(
      RelaxedGrid(s.length, s.height, s.nx, s.ny, s.grading));
  result.delta = s.Delta();
  const int periods =
      s.periods > 0 ? s.periods : KmPeriodsFor(s.epsilon, s.length, s.height);
  result.periods = periods;
  const double h0 = s.height / periods;
  if (s.init == "laminate") {
    InitLaminate(&result.field, periods, result.delta);
  } else if (s.init == "random") {
    InitRandom(&result.field, s.seed, result.delta);
  } else if (s.init == "km" || s.init == "needle") {
    ConstructionResult c =
        s.init == "km" ? EvaluateKm(s.epsilon, s.length, h0, KmOptimalTheta())
                       : EvaluateNeedle(s.epsilon, s.length, h0,
                                        KmOptimalTheta());
    InitConstruction(&result.field, c.ToConstruction(s.length), result.delta);
  } else {
    ConstructionResult lens = DefaultLens(s.epsilon, s.length);
    lens.shape = LensShape{0.5, 0.0, 0.0};
    // The lens period in H: the nearest integer count to its optimal h0.
    const int n = s.periods > 0
                      ? s.periods
                      : std::max(1, static_cast<int>(
                                        std::lround(s.height / lens.h0)));
    result.periods = n;
    lens.h0 = s.height / n;
    InitConstruction(&result.field, lens.ToConstruction(s.length),
                     result.delta);
  }
  return result;
}

namespace {

// Solves result->field at the widths `deltas` (the settings' limits) and
// fills the stages, energy, iterations, interfaces and seconds since
// `start`.
void SolveSimulation(const SimulationSettings& s, std::vector<double> deltas,
                     std::chrono::steady_clock::time_point start,
                     SimulationResult* result) {
  RelaxedSolveOptions options;
  options.deltas = std::move(deltas);
  options.max_iterations = s.max_iterations;
  options.num_threads = s.num_threads;
  options.progress = s.progress;
  options.stop = s.stop;
  result->stages = SolveRelaxed(&result->field, s.epsilon, options);
  result->energy = result->stages.back().energy;
  for (const RelaxedStage& stage : result->stages) {
    result->iterations += stage.iterations;
  }
  result->interfaces = CountInterfaces(result->field);
  result->seconds = std::chrono::duration<double>(
                        std::chrono::steady_clock::now() - start)
                        .count();
}

}  // namespace

SimulationResult RunSimulation(const SimulationSettings& s) {
  const auto start = std::chrono::steady_clock::now();
  SimulationResult result = InitialSimulation(s);
  SolveSimulation(s, ContinuationDeltas(result.delta, s.continuation), start,
                  &result);
  return result;
}

SimulationResult ContinueSimulation(const SimulationSettings& s,
                                    const RelaxedField& start, int periods) {
  CheckSimulationSettings(s);
  const auto begin = std::chrono::steady_clock::now();
  SimulationResult result(RelaxedGrid(s.length, s.height, s.nx, s.ny, s.grading));
  result.field = TransferField(start, result.field.grid);
  result.delta = s.Delta();
  result.periods = periods;
  SolveSimulation(s, {result.delta}, begin, &result);
  return result;
}

std::vector<double> PolynomialFit(const std::vector<double>& x,
                                  const std::vector<double>& y, int degree,
                                  double* rms) {
  const int n = static_cast<int>(x.size());
  const int m = degree + 1;
  if (n < m || static_cast<int>(y.size()) != n) {
    throw InputError("polynomial fit: need at least degree + 1 points");
  }
  // Normal equations M c = b, solved by Gaussian elimination with pivoting.
  std::vector<std::vector<double>> M(m, std::vector<double>(m + 1, 0.0));
  for (int k = 0; k < n; ++k) {
    std::vector<double> pw(2 * m, 1.0);
    for (int e = 1; e < 2 * m; ++e) pw[e] = pw[e - 1] * x[k];
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < m; ++j) M[i][j] += pw[i + j];
      M[i][m] += pw[i] * y[k];
    }
  }
  for (int col = 0; col < m; ++col) {
    int piv = col;
    for (int r = col + 1; r < m; ++r) {
      if (std::fabs(M[r][col]) > std::fabs(M[piv][col])) piv = r;
    }
    std::swap(M[col], M[piv]);
    if (M[col][col] == 0.0) throw InputError("polynomial fit: singular data");
    for (int r = 0; r < m; ++r) {
      if (r == col) continue;
      const double f = M[r][col] / M[col][col];
      for (int j = col; j <= m; ++j) M[r][j] -= f * M[col][j];
    }
  }
  std::vector<double> c(m);
  for (int i = 0; i < m; ++i) c[i] = M[i][m] / M[i][i];
  if (rms != nullptr) {
    double s = 0.0;
    for (int k = 0; k < n; ++k) {
      double v = 0.0, pw = 1.0;
      for (int i = 0; i < m; ++i, pw *= x[k]) v += c[i] * pw;
      s += (v - y[k]) * (v - y[k]);
    }
    *rms = std::sqrt(s / n);
  }
  return c;
}

void CheckExtrapolationCount(int count) {
  if (count != 0 && (count < 2 || count > kMaxExtrapolationWidths)) {
    throw InputError(
        "delta extrapolation: the number of widths must be 0 or in [2, " +
        std::to_string(kMaxExtrapolationWidths) + "], got " +
        std::to_string(count));
  }
}

std::vector<double> ExtrapolationWidths(double delta, int count) {
  CheckExtrapolationCount(count);
  std::vector<double> deltas;
  for (int k = 0; k < count; ++k) {
    deltas.push_back(delta * std::pow(std::sqrt(0.5), k));
  }
  return deltas;
}

DeltaExtrapolation ExtrapolateDelta(
    const SimulationSettings& base, const std::vector<double>& deltas,
    const std::function<void(const DeltaWidth&)>& progress) {
  if (deltas.size() < 2) throw InputError("delta extrapolation needs at least 2 widths");
  for (size_t k = 0; k < deltas.size(); ++k) {
    if (!(deltas[k] > 0) || (k > 0 && !(deltas[k] < deltas[k - 1]))) {
      throw InputError("delta extrapolation: the widths must be positive and decreasing");
    }
  }
  DeltaExtrapolation out;
  const double lambda = std::cbrt(base.epsilon) * std::pow(base.length, 2.0 / 3.0);
  const double scale = std::pow(base.epsilon, 2.0 / 3.0) * std::cbrt(base.length);
  std::vector<double> d, constants;
  std::optional<SimulationResult> previous;
  out.all_converged = true;
  for (size_t k = 0; k < deltas.size(); ++k) {
    SimulationSettings s = base;
    s.delta = deltas[k];
    int ny = static_cast<int>(std::ceil(3.0 * s.height / deltas[k] - 1e-9));
    ny += ny % 2;
    s.ny = ny;
    s.nx = std::max(2, static_cast<int>(std::lround(base.nx * deltas[0] / deltas[k])));
    s.progress = nullptr;
    SimulationResult r = k == 0 ? RunSimulation(s)
                                : ContinueSimulation(s, previous->field,
                                                     previous->periods);
    DeltaWidth w;
    w.delta = deltas[k];
    w.nx = s.nx;
    w.ny = s.ny;
    w.constant = r.energy.total() / scale;
    w.elastic = r.energy.elastic / scale;
    w.interfacial = r.energy.interfacial() / scale;
    w.iterations = r.iterations;
    w.termination = r.stages.back().termination;
    w.converged = w.termination == "CONVERGENCE";
    w.interfaces_far = r.interfaces.back();
    w.interfaces_max = *std::max_element(r.interfaces.begin(), r.interfaces.end());
    w.seconds = r.seconds;
    out.all_converged = out.all_converged && w.converged;
    out.widths.push_back(w);
    d.push_back(deltas[k] / lambda);
    constants.push_back(w.constant);
    if (progress) progress(w);
    const bool collapsed = w.termination == "COLLAPSED";
    previous.emplace(std::move(r));
    if (collapsed || base.stop.stop_requested()) break;
  }
  out.monotone = constants.size() >= 2;
  for (size_t k = 1; k < constants.size(); ++k) {
    out.monotone = out.monotone && constants[k] > constants[k - 1];
  }
  const RelaxedField& last = previous->field;
  out.interfaces = previous->interfaces;
  for (int i = 1; i <= last.grid.nx; ++i) out.x.push_back(last.grid.x(i));
  out.steps = CountSteps(last, out.interfaces);
  if (d.size() < 2) return out;  // stopped or collapsed after one width
  const std::vector<double> lin = PolynomialFit(d, constants, 1, &out.linear_rms);
  out.c0 = lin[0];
  out.c1 = lin[1];
  out.extrapolated = out.c0;
  if (d.size() >= 4) {
    const std::vector<double> q = PolynomialFit(d, constants, 2, &out.quadratic_rms);
    out.q0 = q[0];
    out.q1 = q[1];
    out.q2 = q[2];
    std::vector<double> root;
    for (double v : d) root.push_back(std::sqrt(v));
    const std::vector<double> s = PolynomialFit(root, constants, 2, &out.root_rms);
    out.s0 = s[0];
    out.s1 = s[1];
    out.s2 = s[2];
    out.has_quadratic = true;
    out.extrapolated = out.s0;
    out.error = std::max(std::fabs(out.s0 - out.q0), std::fabs(out.s0 - out.c0));
  }
  return out;
}

std::vector<CountStep> CountSteps(const RelaxedField& field,
                                  const std::vector<int>& counts) {
  const RelaxedGrid& g = field.grid;
  if (static_cast<int>(counts.size()) != g.nx) {
    throw InputError("branching count steps: one count per node row i = 1..nx");
  }
  std::vector<CountStep> steps;
  for (int i = g.nx - 1; i >= 1; --i) {  // rows i (inner) and i + 1 (outer)
    if (counts[i - 1] != counts[i]) {
      steps.push_back({0.5 * (g.x(i) + g.x(i + 1)), counts[i], counts[i - 1]});
    }
  }
  return steps;
}

std::vector<int> CountInterfaces(const RelaxedField& field) {
  const RelaxedGrid& g = field.grid;
  std::vector<int> counts;
  for (int i = 1; i <= g.nx; ++i) {
    int count = 0;
    for (int j = 0; j < g.ny; ++j) {
      const bool a = field.uy(i, j) > 0.0;
      const bool b = field.uy(i, (j + 1) % g.ny) > 0.0;
      count += a != b;
    }
    counts.push_back(count);
  }
  return counts;
}

}  // namespace shellspace::branching
