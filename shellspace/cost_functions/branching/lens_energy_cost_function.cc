#include "shellspace/cost_functions/branching/lens_energy_cost_function.h"

#include <cmath>
#include <vector>

#include "shellspace/models/branching/cell_pattern.h"
#include "shellspace/models/branching/lens_family.h"

namespace shellspace::branching {

LensEnergyCostFunction::LensEnergyCostFunction(double epsilon, double length)
    : epsilon_(epsilon), length_(length) {
  std::vector<double> nodes, weights;
  GaussLegendre01(kLensEnergyPoints, &nodes, &weights);
  for (int q = 0; q < kLensEnergyPoints; ++q) {
    nodes_[q] = nodes[q];
    weights_[q] = weights[q];
  }
}

bool LensEnergyCostFunction::Evaluate(double const* const* parameters,
                                      double* residuals,
                                      double** jacobians) const {
  const double* p = parameters[0];
  const double h0 = p[0], theta = p[1];
  const LensShape shape{p[2], p[3], p[4]};
  if (!(h0 > 0.0) || !(theta > 1.0 / 9.0) || !(theta < 1.0 / 3.0) ||
      !(shape.tau >= 0.0) || !(shape.tau < 1.0)) {
    return false;
  }
  const double S1 = 9.0 * theta / (9.0 * theta - 1.0);
  const double S2 = 1.0 / (1.0 - 3.0 * theta);
  const double P = h0 * h0 * S1 / (length_ * (1.0 - theta) * (1.0 - shape.tau));
  const double dlog_theta_el =
      0.5 * (1.0 / theta - 9.0 / (9.0 * theta - 1.0) + 1.0 / (1.0 - theta));
  const double dlog_tau_el = 0.5 / (1.0 - shape.tau);
  double* J = (jacobians != nullptr) ? jacobians[0] : nullptr;
  for (int q = 0; q < kLensEnergyPoints; ++q) {
    const LensProfile f = EvaluateLensProfile(shape, nodes_[q]);
    const double well = 1.0 - f.phi / 3.0;
    if (!(well > 0.0)) return false;
    const double root = std::sqrt(P * weights_[q]);
    const double sw = std::sqrt(well);
    residuals[q] = root * sw * f.phi_t / 6.0;
    if (J != nullptr) {
      double* row = J + 5 * q;
      row[0] = residuals[q] / h0;
      row[1] = residuals[q] * dlog_theta_el;
      row[2] = residuals[q] * dlog_tau_el;
      row[3] = root * (-f.dphi_da1 / (6.0 * sw) * f.phi_t / 6.0 +
                       sw * f.dphit_da1 / 6.0);
      row[4] = root * (-f.dphi_da2 / (6.0 * sw) * f.phi_t / 6.0 +
                       sw * f.dphit_da2 / 6.0);
    }
  }
  const double B = 12.0 - 8.0 * shape.tau;
  const double last =
      std::sqrt(epsilon_ * length_ * B * (1.0 - theta) * S2 / h0);
  residuals[kLensEnergyPoints] = last;
  if (J != nullptr) {
    double* row = J + 5 * kLensEnergyPoints;
    row[0] = -0.5 * last / h0;
    row[1] = 0.5 * last * (3.0 / (1.0 - 3.0 * theta) - 1.0 / (1.0 - theta));
    row[2] = -4.0 * last / B;
    row[3] = 0.0;
    row[4] = 0.0;
  }
  return true;
}

}  // namespace shellspace::branching
