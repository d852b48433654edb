// The membrane energy of one triangle as a function of the two first
// fundamental forms, with its analytic gradient and Hessian (the second
// derivatives of MembraneElementOf<Law>, membrane_element.h), for any
// isotropic membrane law (membrane_law.h).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_FORM_DERIVATIVES_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_FORM_DERIVATIVES_H_

#include <Eigen/Core>

#include <cmath>

namespace shellspace {

// With p = (gbar11, gbar12, gbar22) the reference and q = (g11, g12, g22) the
// deformed first fundamental form (geometry/element_geometry.h),
//   B = det gbar = 1/2 p^T M p,  D = det g = 1/2 q^T M q,
//   A = p^T M q = B tr(gbar^-1 g),   M = [[0, 0, 1], [0, -2, 0], [1, 0, 0]].
// An isotropic law's term abar W(gbar^-1 g) depends on the forms through the
// invariants tr G = A / B, det G = D / B and abar = sqrt(B) / 2 only, so it
// is a function F(A, B, D). A law gives F and its partials in A, B, D
// (MembraneInvariantPartials); with P = M p = dB/dp = dA/dq and
// Q = M q = dD/dq = dA/dp the chain rule gives
//   dF/dq = F_A P + F_D Q,       dF/dp = F_A Q + F_B P
//   d2F/dq2   = F_AA P P^T + F_AD (P Q^T + Q P^T) + F_DD Q Q^T + F_D M
//   d2F/dp2   = F_AA Q Q^T + F_AB (P Q^T + Q P^T) + F_BB P P^T + F_B M
//   d2F/dp dq = F_AA Q P^T + F_AB P P^T + F_AD Q Q^T + F_BD P Q^T + F_A M
// (rows p, columns q). The terms of a partial that is exactly 0 are skipped.
struct MembraneInvariantPartials {
  double f = 0;
  double f_a = 0, f_b = 0, f_d = 0;
  double f_aa = 0, f_ab = 0, f_ad = 0, f_bb = 0, f_bd = 0, f_dd = 0;
};

// F, its gradients and Hessian blocks over the form entries.
struct MembraneFormDerivatives {
  double energy = 0;
  Eigen::Vector3d grad_p, grad_q;
  Eigen::Matrix3d h_pp, h_qq, h_pq;  // h_pq(m, n) = d2F / dp_m dq_n

  // False (nothing else set) if det gbar or det g is not positive and finite
  // or the law rejects the invariants. `want_pp`, `want_qq`, `want_pq`
  // select the Hessian blocks. Law::Partials(A, B, D, &partials) fills
  // MembraneInvariantPartials (membrane_law.h).
  template <class Law>
  bool Compute(const Law& law, const double p[3], const double q[3],
               bool want_pp, bool want_qq, bool want_pq) {
    const double dbar = p[0] * p[2] - p[1] * p[1];
    const double d = q[0] * q[2] - q[1] * q[1];
    if (!(dbar > 0) || !(d > 0) || !std::isfinite(dbar) || !std::isfinite(d))
      return false;
    const double a = p[2] * q[0] - 2 * p[1] * q[1] + p[0] * q[2];
    MembraneInvariantPartials f;
    if (!law.Partials(a, dbar, d, &f)) return false;
    Assemble(f, p, q, want_pp, want_qq, want_pq);
    return true;
  }

 private:
  void Assemble(const MembraneInvariantPartials& f, const double p[3],
                const double q[3], bool want_pp, bool want_qq, bool want_pq) {
    const Eigen::Vector3d pm(p[2], -2 * p[1], p[0]);  // P = M p
    const Eigen::Vector3d qm(q[2], -2 * q[1], q[0]);  // Q = M q
    energy = f.f;
    grad_q = f.f_a * pm + f.f_d * qm;
    grad_p = f.f_a * qm + f.f_b * pm;
    Eigen::Matrix3d m;
    m << 0, 0, 1, 0, -2, 0, 1, 0, 0;
    const bool nonlinear_in_a = f.f_aa != 0 || f.f_ad != 0;
    if (want_qq) {
      h_qq = f.f_dd * qm * qm.transpose() + f.f_d * m;
      if (nonlinear_in_a) {
        const Eigen::Matrix3d pq = pm * qm.transpose();
        h_qq += f.f_aa * pm * pm.transpose() + f.f_ad * (pq + pq.transpose());
      }
    }
    if (want_pp) {
      const Eigen::Matrix3d pq = pm * qm.transpose();
      h_pp = f.f_ab * (pq + pq.transpose()) + f.f_bb * pm * pm.transpose() +
             f.f_b * m;
      if (f.f_aa != 0) h_pp += f.f_aa * qm * qm.transpose();
    }
    if (want_pq) {
      h_pq = f.f_ab * pm * pm.transpose() + f.f_bd * pm * qm.transpose() +
             f.f_a * m;
      if (nonlinear_in_a) {
        h_pq += f.f_aa * qm * pm.transpose() + f.f_ad * qm * qm.transpose();
      }
    }
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_FORM_DERIVATIVES_H_
