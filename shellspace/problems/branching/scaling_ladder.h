// The scaling law from the relaxed simulation (docs/math.md, "Branching: the
// Kohn–Müller model"): minimal energy per unit height over eps, and the fit
//   log E = p log eps + log(C L^(1/3))      (expect p = 2/3).
//
// Grid / width rule (documented choice): L and H fixed for the whole ladder;
// the interface width follows the natural length of the pattern,
//   delta = c_delta eps^(1/3) L^(2/3),
// so every rung has the same relative resolution of the interfaces and the
// same delta-bias of the relaxed constant (the relaxed minimum
// underestimates the sharp constant by an amount depending only on
// delta / eps^(1/3)); dy = delta / 3 (ny = ceil(3 H / delta), even), i.e.
// dy <= delta / 2.5; the x-grid is graded, x_i = L (i/nx)^2, with nx fixed.
// Each rung takes the minimum over needle (T2; formerly called "km")
// initialisations with the two period counts floor / ceil of H / h0*(eps) (the
// integer number of periods in H is the one thing that breaks the exact scaling
// invariance).
#ifndef SHELLSPACE_PROBLEMS_BRANCHING_SCALING_LADDER_H_
#define SHELLSPACE_PROBLEMS_BRANCHING_SCALING_LADDER_H_

#include <functional>
#include <vector>

namespace shellspace::branching {

struct LadderSettings {
  std::vector<double> epsilons;
  double length = 1.0;
  double height = 0.5;
  int nx = 32;
  double grading = 2.0;
  double delta_over_lambda = 0.1;  // c_delta
  int continuation = 3;
  int max_iterations = 200;
};

struct LadderRung {
  double epsilon = 0.0;
  double delta = 0.0;
  int ny = 0;
  int periods = 0;
  double energy = 0.0;  // minimal energy per unit height
  double elastic = 0.0, interfacial = 0.0;
  double seconds = 0.0;
  int iterations = 0;
};

struct LadderResult {
  std::vector<LadderRung> rungs;
  double exponent = 0.0;  // p
  double constant = 0.0;  // C (E ~ C eps^p L^(1/3))
};

// Least-squares line through (log eps, log E).
void FitPowerLaw(const std::vector<double>& epsilons,
                 const std::vector<double>& energies, double length,
                 double* exponent, double* constant);

LadderResult RunLadder(const LadderSettings& settings,
                       const std::function<void(const LadderRung&)>& progress =
                           nullptr);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_PROBLEMS_BRANCHING_SCALING_LADDER_H_
