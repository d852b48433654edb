// The membrane energy of one triangle as a function of the two first
// fundamental forms, with its analytic gradient and Hessian (the second
// derivatives of MembraneElement, membrane_element.h).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_FORM_DERIVATIVES_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_FORM_DERIVATIVES_H_

#include <Eigen/Core>

#include <cmath>

namespace shellspace {

// With p = (gbar11, gbar12, gbar22) the reference and q = (g11, g12, g22) the
// deformed first fundamental form (geometry/element_geometry.h),
//   Dbar = det gbar = 1/2 p^T M p,  D = det g = 1/2 q^T M q,
//   A = p^T M q = Dbar tr(gbar^-1 g),   M = [[0, 0, 1], [0, -2, 0], [1, 0, 0]],
// the membrane term abar W_m(gbar^-1 g) (docs/math.md, "Membrane energy") is,
// with s = sqrt(Dbar) (abar = s / 2), L = log(D / Dbar), c1 = mu/2 +
// lambda/4, c0 = mu + lambda/4:
//   F(p, q) = mu A / (4 s) + lambda D / (8 s) - c1 s L / 2 - c0 s / 2.
// F is linear in A, so with P = M p = dDbar/dp = dA/dq and Q = M q = dD/dq =
// dA/dp:
//   dF/dq = F_A P + F_D Q,       dF/dp = F_A Q + F_B P           (B = Dbar)
//   d2F/dq2   = F_DD Q Q^T + F_D M
//   d2F/dp2   = F_AB (P Q^T + Q P^T) + F_BB P P^T + F_B M
//   d2F/dp dq = F_AB P P^T + F_BD P Q^T + F_A M      (rows p, columns q)
// with the scalar partials
//   F_A  = mu / (4 s),              F_AB = -mu / (8 s^3),
//   F_D  = lambda / (8 s) - c1 s / (2 D),   F_DD = c1 s / (2 D^2),
//   F_BD = -lambda / (16 s^3) - c1 / (4 s D),
//   F_B  = -(mu A / 4 + lambda D / 8) / (2 s^3) + (2 c1 - c0 - c1 L) / (4 s),
//   F_BB = 3 (mu A / 4 + lambda D / 8) / (4 s^5) + (c0 + c1 L) / (8 s^3).
// Everything is a 3-vector or 3 x 3 matrix over the form entries; the chain
// to vertex coordinates is MembraneElement::SecondDerivatives.
struct MembraneFormDerivatives {
  double energy = 0;
  Eigen::Vector3d grad_p, grad_q;
  Eigen::Matrix3d h_pp, h_qq, h_pq;  // h_pq(m, n) = d2F / dp_m dq_n

  // False (nothing else set) if det gbar or det g is not positive and
  // finite. `want_pp`, `want_qq`, `want_pq` select the Hessian blocks.
  bool Compute(double mu, double lambda, const double p[3], const double q[3],
               bool want_pp, bool want_qq, bool want_pq) {
    const double dbar = p[0] * p[2] - p[1] * p[1];
    const double d = q[0] * q[2] - q[1] * q[1];
    if (!(dbar > 0) || !(d > 0) || !std::isfinite(dbar) || !std::isfinite(d))
      return false;
    const double a = p[2] * q[0] - 2 * p[1] * q[1] + p[0] * q[2];
    const Eigen::Vector3d pm(p[2], -2 * p[1], p[0]);  // P = M p
    const Eigen::Vector3d qm(q[2], -2 * q[1], q[0]);  // Q = M q
    const double s = std::sqrt(dbar);
    const double s3 = s * dbar;
    const double log_det = std::log(d / dbar);
    const double c1 = mu / 2 + lambda / 4, c0 = mu + lambda / 4;
    const double lin = mu * a / 4 + lambda * d / 8;
    energy = lin / s - c1 * s * log_det / 2 - c0 * s / 2;
    const double f_a = mu / (4 * s);
    const double f_d = lambda / (8 * s) - c1 * s / (2 * d);
    const double f_b = -lin / (2 * s3) + (2 * c1 - c0 - c1 * log_det) / (4 * s);
    grad_q = f_a * pm + f_d * qm;
    grad_p = f_a * qm + f_b * pm;
    Eigen::Matrix3d m;
    m << 0, 0, 1, 0, -2, 0, 1, 0, 0;
    const double f_ab = -mu / (8 * s3);
    if (want_qq) {
      const double f_dd = c1 * s / (2 * d * d);
      h_qq = f_dd * qm * qm.transpose() + f_d * m;
    }
    if (want_pp) {
      const double f_bb =
          3 * lin / (4 * s3 * dbar) + (c0 + c1 * log_det) / (8 * s3);
      const Eigen::Matrix3d pq = pm * qm.transpose();
      h_pp = f_ab * (pq + pq.transpose()) + f_bb * pm * pm.transpose() +
             f_b * m;
    }
    if (want_pq) {
      const double f_bd = -lambda / (16 * s3) - c1 / (4 * s * d);
      h_pq = f_ab * pm * pm.transpose() + f_bd * pm * qm.transpose() + f_a * m;
    }
    return true;
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_FORM_DERIVATIVES_H_
