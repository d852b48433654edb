// Energy of the self-similar Kohn–Müller construction over (h0, theta) as two
// squared residuals (docs/math.md, "Branching: the Kohn–Müller model").
#ifndef SHELLSPACE_COST_FUNCTIONS_BRANCHING_KM_ENERGY_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_BRANCHING_KM_ENERGY_COST_FUNCTION_H_

#include <cmath>

#include <ceres/ceres.h>

namespace shellspace::branching {

// For a cell with coefficients A, B and period ratio r (KM: A = 1/32, B = 8,
// r = 2, see problems/branching/km_family.h), the energy per unit height of
// the construction on (0, L) is E = r_el^2 + r_if^2 with
//
//   r_el = h0 sqrt(A S1(theta) / (L (1 - theta))),
//   r_if = sqrt(B eps L (1 - theta) S2(theta) / h0),
//   S1 = r^2 theta / (r^2 theta - 1),  S2 = 1 / (1 - r theta).
//
// Parameter block (size 2): p = (h0, theta), h0 > 0, 1/r^2 < theta < 1/r
// (outside: Evaluate returns false). Jacobian (2 x 2, row-major):
//   d r_el / d h0    = r_el / h0,
//   d r_el / d theta = r_el / 2 (1/theta - r^2/(r^2 theta - 1) + 1/(1 - theta)),
//   d r_if / d h0    = -r_if / (2 h0),
//   d r_if / d theta = r_if / 2 (r / (1 - r theta) - 1 / (1 - theta)).
class KmEnergyCostFunction : public ceres::SizedCostFunction<2, 2> {
 public:
  KmEnergyCostFunction(double A, double B, int r, double epsilon, double length)
      : A_(A), B_(B), r_(r), epsilon_(epsilon), length_(length) {}

  // `A`, `B`: cell coefficients (e.g. from EvaluateCell(KmCellPattern())).
  static ceres::CostFunction* Create(double A, double B, int r, double epsilon,
                                     double length) {
    return new KmEnergyCostFunction(A, B, r, epsilon, length);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double h0 = parameters[0][0];
    const double theta = parameters[0][1];
    const double r = r_;
    if (!(h0 > 0.0) || !(theta > 1.0 / (r * r)) || !(theta < 1.0 / r)) {
      return false;
    }
    const double S1 = r * r * theta / (r * r * theta - 1.0);
    const double S2 = 1.0 / (1.0 - r * theta);
    residuals[0] = h0 * std::sqrt(A_ * S1 / (length_ * (1.0 - theta)));
    residuals[1] =
        std::sqrt(B_ * epsilon_ * length_ * (1.0 - theta) * S2 / h0);
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      double* J = jacobians[0];
      J[0] = residuals[0] / h0;
      J[1] = 0.5 * residuals[0] *
             (1.0 / theta - r * r / (r * r * theta - 1.0) + 1.0 / (1.0 - theta));
      J[2] = -0.5 * residuals[1] / h0;
      J[3] = 0.5 * residuals[1] * (r / (1.0 - r * theta) - 1.0 / (1.0 - theta));
    }
    return true;
  }

 private:
  double A_, B_;
  int r_;
  double epsilon_, length_;
};

}  // namespace shellspace::branching

#endif  // SHELLSPACE_COST_FUNCTIONS_BRANCHING_KM_ENERGY_COST_FUNCTION_H_
