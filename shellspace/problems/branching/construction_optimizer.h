// Evaluating and optimising the KM (psi-junction), needle (T2) and lens
// constructions (docs/math.md, "Branching: the Kohn–Müller model"): energies
// from the generic cell evaluator (cell_pattern.h) plus the generation series
// (self_similar_series.h); optimisation of (h0, theta[, tau, a1, a2]) by
// Levenberg–Marquardt on KmEnergyCostFunction / LensEnergyCostFunction.
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_CONSTRUCTION_OPTIMIZER_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_CONSTRUCTION_OPTIMIZER_H_

#include <string>

#include "shellspace/models/branching/construction.h"
#include "shellspace/models/branching/lens_family.h"

namespace shellspace::branching {

struct ConstructionResult {
  std::string family;
  int r = 2;
  double h0 = 0.0, theta = 0.0;
  LensShape shape;  // lens only
  double A = 0.0, B = 0.0;
  // km only: u = 0 on the cell edges instead of the optimal shift
  // (EvaluateCellZeroAt at kKmAnchor) and its constant at the same theta
  // (with its own optimal h0).
  double A_zero_edge = 0.0, constant_zero_edge = 0.0;
  double elastic = 0.0, interfacial = 0.0;  // energy per unit height
  // (elastic + interfacial) / (eps^(2/3) L^(1/3)).
  double constant = 0.0;
  int iterations = 0;
  double seconds = 0.0;
  std::string termination;

  Construction ToConstruction(double length) const;
};

// Energy at given parameters via EvaluateCell (generic quadrature).
ConstructionResult EvaluateKm(double epsilon, double length, double h0,
                              double theta);
ConstructionResult EvaluateNeedle(double epsilon, double length, double h0,
                                  double theta);
ConstructionResult EvaluateLens(double epsilon, double length, double h0,
                                double theta, const LensShape& shape);

// Defaults (no optimisation): KM at the closed-form optimum; lens with a
// straight wedge (tau = a1 = a2 = 0) at the series-optimal theta and h0.
ConstructionResult DefaultKm(double epsilon, double length);
ConstructionResult DefaultNeedle(double epsilon, double length);
ConstructionResult DefaultLens(double epsilon, double length);

// LM from the given start (bounds: theta strictly inside (1/r^2, 1/r), lens
// shape bounds of lens_family.h). Reports the evaluator's energy at the
// optimum.
ConstructionResult OptimizeKm(double epsilon, double length, double h0,
                              double theta);
ConstructionResult OptimizeNeedle(double epsilon, double length, double h0,
                                  double theta);
ConstructionResult OptimizeLens(double epsilon, double length, double h0,
                                double theta, const LensShape& start);

// The construction `family` ("km", "needle" or "lens") at its default, or,
// with `optimize`, optimised from a start derived from it: KM and needle
// from half the default h0 and theta 0.3, the lens from the default h0 and
// theta with the shape (tau, a1, a2) = (0.2, 0, 0). Throws InputError for
// any other family.
ConstructionResult ConstructFamily(const std::string& family, double epsilon,
                                   double length, bool optimize);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_CONSTRUCTION_OPTIMIZER_H_
