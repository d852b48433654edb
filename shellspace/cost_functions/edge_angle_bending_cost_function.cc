#include "shellspace/cost_functions/edge_angle_bending_cost_function.h"

#include <cmath>

namespace shellspace {

EdgeAngleBendingCostFunction::EdgeAngleBendingCostFunction(
    const EdgeAngleFace& deformed, const EdgeAngleReferenceFace& reference,
    double alpha, double beta)
    : deformed_(deformed),
      reference_(reference),
      scale_trace_(std::sqrt(2 * reference.area * (alpha + beta / 2))),
      scale_deviator_(std::sqrt(reference.area * beta)) {}

void EdgeAngleBendingCostFunction::Map(double a11, double a12, double a22,
                                       double* r) const {
  const double p = reference_.p, q = reference_.q, s = reference_.s;
  const double k11 = p * p * a11;
  const double k12 = p * (q * a11 + s * a12);
  const double k22 = q * q * a11 + 2 * q * s * a12 + s * s * a22;
  r[0] = scale_trace_ * (k11 + k22);
  r[1] = scale_deviator_ * (k11 - k22);
  r[2] = 2 * scale_deviator_ * k12;
}

void EdgeAngleBendingCostFunction::Residuals(const double* phi,
                                             double* residuals) const {
  const SecondForm2 h = EdgeAngleSecondForm(deformed_, phi);
  const SecondForm2& hbar = reference_.second_form;
  Map(h.h11 - hbar.h11, h.h12 - hbar.h12, h.h22 - hbar.h22, residuals);
}

bool EdgeAngleBendingCostFunction::Evaluate(double const* const* parameters,
                                            double* residuals,
                                            double** jacobians) const {
  const double phi[3] = {parameters[0][0], parameters[1][0], parameters[2][0]};
  Residuals(phi, residuals);
  if (jacobians == nullptr) return true;
  // d(h11, h12, h22)/dc_i, then the chain through dc_i/dphi_i.
  static constexpr double kSecondFormOfCoefficient[3][3] = {
      {1, 1, 1}, {1, 0, 0}, {0, 0, 1}};
  for (int i = 0; i < 3; ++i) {
    if (jacobians[i] == nullptr) continue;
    const double dc = deformed_.CoefficientDerivative(i, phi[i]);
    const double* dh = kSecondFormOfCoefficient[i];
    Map(dh[0] * dc, dh[1] * dc, dh[2] * dc, jacobians[i]);  // 3 x 1 column
  }
  return true;
}

}  // namespace shellspace
