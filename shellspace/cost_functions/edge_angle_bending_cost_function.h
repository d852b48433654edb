// Ceres cost function of one face's shape-operator bending energy in the
// edge-angle variant, as a function of the angles of the face's edges.
#ifndef SHELLSPACE_COST_FUNCTIONS_EDGE_ANGLE_BENDING_COST_FUNCTION_H_
#define SHELLSPACE_COST_FUNCTIONS_EDGE_ANGLE_BENDING_COST_FUNCTION_H_

#include <ceres/sized_cost_function.h>

#include "shellspace/geometry/edge_angle_second_form.h"

namespace shellspace {

// The reference side of one face: its metric and its (already rotated)
// second form. Gbar = L L^T (Cholesky of the reference face's first
// fundamental form in the basis E_1, E_2), L^-1 = [[p, 0], [q, s]].
struct EdgeAngleReferenceFace {
  double area = 0;          // abar
  double p = 0, q = 0, s = 0;
  SecondForm2 second_form;  // Hbar (h11, h12, h22)
};

// Three residuals r with
//   1/2 |r|^2 = abar (alpha (tr M)^2 + beta tr(M^2)),
//   M = Gbar^-1 (H(phi) - Hbar),
// H(phi) the rotated mid-edge form of the deformed face
// (geometry/edge_angle_second_form.h), Hbar and Gbar = L L^T of the
// reference face (both fixed data): with K = L^-1 (H(phi) - Hbar) L^-T,
//   r = ( sqrt(2 abar (alpha + beta/2)) (k11 + k22),
//         sqrt(abar beta) (k11 - k22),  2 sqrt(abar beta) k12 ).
// Parameter blocks: phi_0, phi_1, phi_2 (one double each), the angles of the
// face's edge slots 0, 1, 2 (slot i opposite X_i). A boundary slot's block
// is any block the caller holds constant; its Jacobian column is 0.
// Jacobian: H is linear in c = (c_0, c_1, c_2) (dH/dc_0 = (1, 1, 1),
// dH/dc_1 = (1, 0, 0), dH/dc_2 = (0, 0, 1) in (h11, h12, h22)), K is linear
// in H, and dc_i/dphi_i = 2 h_i s_i cos(alpha_i).
class EdgeAngleBendingCostFunction : public ceres::SizedCostFunction<3, 1, 1, 1> {
 public:
  EdgeAngleBendingCostFunction(const EdgeAngleFace& deformed,
                               const EdgeAngleReferenceFace& reference,
                               double alpha, double beta);

  static EdgeAngleBendingCostFunction* Create(
      const EdgeAngleFace& deformed, const EdgeAngleReferenceFace& reference,
      double alpha = 0, double beta = 1) {
    return new EdgeAngleBendingCostFunction(deformed, reference, alpha, beta);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  // The residuals at the slot angles phi[3] (no Jacobian).
  void Residuals(const double* phi, double* residuals) const;

 private:
  // r of a symmetric matrix A = (a11, a12, a22) in place of H - Hbar.
  void Map(double a11, double a12, double a22, double* r) const;

  EdgeAngleFace deformed_;
  EdgeAngleReferenceFace reference_;
  double scale_trace_, scale_deviator_;
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_EDGE_ANGLE_BENDING_COST_FUNCTION_H_
