// Energy of the self-similar lens construction as a function of its parameters
// (h0, theta, tau, a1, a2), as squared residuals (docs/math.md, "Branching: the
// Kohn–Müller model"; cell geometry in models/branching/lens_family.h).
#ifndef SHELLSPACE_COST_FUNCTIONS_BRANCHING_LENS_ENERGY_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_BRANCHING_LENS_ENERGY_COST_FUNCTION_H_

#include <ceres/ceres.h>

namespace shellspace::branching {

// With r = 3, S1 = 9 theta / (9 theta - 1), S2 = 1 / (1 - 3 theta),
// P = h0^2 S1 / (L (1 - theta) (1 - tau)), Gauss–Legendre nodes t_q and
// weights w_q on [0, 1] (q < kLensEnergyPoints; exact for the degree-7
// integrand), phi_q = phi(t_q), phi'_q = phi_t(t_q) (lens_family.h):
//
//   r_q    = sqrt(P w_q (1 - phi_q / 3)) phi'_q / 6      (elastic; sum r_q^2
//            = A h0^2 S1 / l0 with A = J / (1 - tau))
//   r_last = sqrt(eps L (12 - 8 tau) (1 - theta) S2 / h0)  (interfacial)
//
// E = sum r^2 is the energy per unit height. Parameter block (size 5):
// p = (h0, theta, tau, a1, a2). Jacobian (rows: residuals, columns: p):
//   d r_q / d h0    = r_q / h0
//   d r_q / d theta = r_q / 2 (1/theta - 9/(9 theta - 1) + 1/(1 - theta))
//   d r_q / d tau   = r_q / (2 (1 - tau))
//   d r_q / d a_k   = sqrt(P w_q) [ -(d phi_q/d a_k) / (6 sqrt(1 - phi_q/3))
//                      phi'_q / 6 + sqrt(1 - phi_q/3) (d phi'_q / d a_k) / 6 ]
//   d r_last / d h0    = -r_last / (2 h0)
//   d r_last / d theta = r_last / 2 (3 / (1 - 3 theta) - 1 / (1 - theta))
//   d r_last / d tau   = -4 r_last / (12 - 8 tau),   d r_last / d a_k = 0.
// Outside the valid domain (h0 <= 0, theta not in (1/9, 1/3), tau not in
// [0, 1), 1 - phi/3 <= 0) Evaluate returns false.
constexpr int kLensEnergyPoints = 8;

class LensEnergyCostFunction
    : public ceres::SizedCostFunction<kLensEnergyPoints + 1, 5> {
 public:
  LensEnergyCostFunction(double epsilon, double length);

  static ceres::CostFunction* Create(double epsilon, double length) {
    return new LensEnergyCostFunction(epsilon, length);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  double epsilon_, length_;
  double nodes_[kLensEnergyPoints];
  double weights_[kLensEnergyPoints];
};

}  // namespace shellspace::branching

#endif  // SHELLSPACE_COST_FUNCTIONS_BRANCHING_LENS_ENERGY_COST_FUNCTION_H_
