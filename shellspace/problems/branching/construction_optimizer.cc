#include "shellspace/problems/branching/construction_optimizer.h"

#include <ceres/ceres.h>

#include <chrono>
#include <cmath>

#include "shellspace/cost_functions/branching/km_energy_cost_function.h"
#include "shellspace/cost_functions/branching/lens_energy_cost_function.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/problems/branching/km_family.h"
#include "shellspace/problems/branching/self_similar_series.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace::branching {

namespace {

void CheckScales(double epsilon, double length) {
  if (!(epsilon > 0) || !(length > 0)) {
    throw InputError("branching construction: epsilon and length must be > 0");
  }
}

// The fields every family sets before its cell is evaluated.
ConstructionResult Begin(const char* family, int r, double epsilon,
                         double length, double h0, double theta) {
  CheckScales(epsilon, length);
  ConstructionResult result;
  result.family = family;
  result.r = r;
  result.h0 = h0;
  result.theta = theta;
  return result;
}

ConstructionResult Finish(ConstructionResult result, const CellPattern& cell,
                          double epsilon, double length) {
  const CellCoefficients c = EvaluateCell(cell);
  result.A = c.A;
  result.B = c.B;
  const SeriesEnergy e = SeriesEnergyAt(c.A, c.B, result.r, epsilon, length,
                                        result.h0, result.theta);
  result.elastic = e.elastic;
  result.interfacial = e.interfacial;
  result.constant =
      e.total() / (std::pow(epsilon, 2.0 / 3.0) * std::cbrt(length));
  return result;
}

// Dense LM on the few cell parameters; absolute gradient tolerance.
ceres::Solver::Options LmOptions() {
  SolverSettings settings;
  settings.linear_solver = SolverSettings::LinearSolver::kDenseQr;
  settings.max_iterations = 500;
  settings.function_tolerance = 1e-15;
  settings.gradient_tolerance = 1e-14;
  settings.parameter_tolerance = 1e-14;
  settings.num_threads = 1;
  return MakeSolverOptions(settings, /*initial_gradient_norm=*/0);
}

// The LM solve that optimised `result`'s parameters: its iterations
// (Ceres' iteration 0 not counted), termination and the seconds since
// `start`.
void RecordSolve(const ceres::Solver::Summary& summary,
                 std::chrono::steady_clock::time_point start,
                 ConstructionResult* result) {
  result->iterations = static_cast<int>(summary.iterations.size()) - 1;
  result->termination =
      ceres::TerminationTypeToString(summary.termination_type);
  result->seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
}

}  // namespace

Construction ConstructionResult::ToConstruction(double length) const {
  Construction c;
  c.pattern = family == "km"       ? KmCellPattern()
              : family == "needle" ? NeedleCellPattern()
                                   : LensCellPattern(shape);
  c.length = length;
  c.h0 = h0;
  c.theta = theta;
  return c;
}

ConstructionResult EvaluateKm(double epsilon, double length, double h0,
                              double theta) {
  ConstructionResult result = Finish(Begin("km", 2, epsilon, length, h0, theta),
                                     KmCellPattern(), epsilon, length);
  result.A_zero_edge = EvaluateCellZeroAt(KmCellPattern(), kKmAnchor).A;
  // Its own optimal h0 at the same theta.
  result.constant_zero_edge =
      SeriesConstant(result.A_zero_edge, result.B, 2, theta);
  return result;
}

ConstructionResult EvaluateNeedle(double epsilon, double length, double h0,
                                  double theta) {
  return Finish(Begin("needle", 2, epsilon, length, h0, theta),
                NeedleCellPattern(), epsilon, length);
}

ConstructionResult EvaluateLens(double epsilon, double length, double h0,
                                double theta, const LensShape& shape) {
  ConstructionResult result =
      Begin("lens", kLensRatio, epsilon, length, h0, theta);
  result.shape = shape;
  return Finish(result, LensCellPattern(shape), epsilon, length);
}

ConstructionResult DefaultKm(double epsilon, double length) {
  const double theta = KmOptimalTheta();
  return EvaluateKm(epsilon, length,
                    OptimalFirstPeriod(kKmA, kKmB, 2, epsilon, length, theta),
                    theta);
}

ConstructionResult DefaultNeedle(double epsilon, double length) {
  const double theta = KmOptimalTheta();
  return EvaluateNeedle(
      epsilon, length,
      OptimalFirstPeriod(kNeedleA, kNeedleB, 2, epsilon, length, theta), theta);
}

ConstructionResult DefaultLens(double epsilon, double length) {
  const LensShape shape;
  const double theta = OptimalTheta(kLensRatio);
  const double A = LensReducedA(shape), B = LensReducedB(shape);
  return EvaluateLens(
      epsilon, length,
      OptimalFirstPeriod(A, B, kLensRatio, epsilon, length, theta), theta,
      shape);
}

namespace {
ConstructionResult OptimizeR2(bool km, double epsilon, double length, double h0,
                              double theta) {
  CheckScales(epsilon, length);
  const auto start = std::chrono::steady_clock::now();
  const CellCoefficients c =
      EvaluateCell(km ? KmCellPattern() : NeedleCellPattern());
  double p[2] = {h0, theta};
  ceres::Problem problem;
  problem.AddResidualBlock(
      KmEnergyCostFunction::Create(c.A, c.B, 2, epsilon, length), nullptr, p);
  const double margin = 1e-6;
  problem.SetParameterLowerBound(p, 0, 1e-12 * length);
  problem.SetParameterLowerBound(p, 1, 0.25 + margin);
  problem.SetParameterUpperBound(p, 1, 0.5 - margin);
  ceres::Solver::Summary summary;
  ceres::Solve(LmOptions(), &problem, &summary);
  ConstructionResult result = km ? EvaluateKm(epsilon, length, p[0], p[1])
                                 : EvaluateNeedle(epsilon, length, p[0], p[1]);
  RecordSolve(summary, start, &result);
  return result;
}

}  // namespace

ConstructionResult OptimizeKm(double epsilon, double length, double h0,
                              double theta) {
  return OptimizeR2(true, epsilon, length, h0, theta);
}

ConstructionResult OptimizeNeedle(double epsilon, double length, double h0,
                                  double theta) {
  return OptimizeR2(false, epsilon, length, h0, theta);
}

ConstructionResult OptimizeLens(double epsilon, double length, double h0,
                                double theta, const LensShape& start_shape) {
  CheckScales(epsilon, length);
  CheckLensShape(start_shape);
  const auto start = std::chrono::steady_clock::now();
  double p[5] = {h0, theta, start_shape.tau, start_shape.a1, start_shape.a2};
  ceres::Problem problem;
  problem.AddResidualBlock(LensEnergyCostFunction::Create(epsilon, length),
                           nullptr, p);
  const double margin = 1e-6;
  problem.SetParameterLowerBound(p, 0, 1e-12 * length);
  problem.SetParameterLowerBound(p, 1, 1.0 / 9.0 + margin);
  problem.SetParameterUpperBound(p, 1, 1.0 / 3.0 - margin);
  problem.SetParameterLowerBound(p, 2, 0.0);
  problem.SetParameterUpperBound(p, 2, kLensTauMax);
  for (int k = 3; k < 5; ++k) {
    problem.SetParameterLowerBound(p, k, -kLensCurvatureMax);
    problem.SetParameterUpperBound(p, k, kLensCurvatureMax);
  }
  ceres::Solver::Summary summary;
  ceres::Solve(LmOptions(), &problem, &summary);
  ConstructionResult result =
      EvaluateLens(epsilon, length, p[0], p[1], LensShape{p[2], p[3], p[4]});
  RecordSolve(summary, start, &result);
  return result;
}

ConstructionResult ConstructFamily(const std::string& family, double epsilon,
                                   double length, bool optimize) {
  if (family == "km" || family == "needle") {
    const bool km = family == "km";
    const ConstructionResult result =
        km ? DefaultKm(epsilon, length) : DefaultNeedle(epsilon, length);
    if (!optimize) return result;
    return km ? OptimizeKm(epsilon, length, 0.5 * result.h0, 0.3)
              : OptimizeNeedle(epsilon, length, 0.5 * result.h0, 0.3);
  }
  if (family == "lens") {
    const ConstructionResult result = DefaultLens(epsilon, length);
    if (!optimize) return result;
    return OptimizeLens(epsilon, length, result.h0, result.theta,
                        LensShape{0.2, 0.0, 0.0});
  }
  throw InputError("branching construct: unknown family '" + family +
                   "' (km, needle or lens)");
}

}  // namespace shellspace::branching
