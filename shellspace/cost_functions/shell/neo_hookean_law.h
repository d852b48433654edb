// The neo-Hookean membrane law (docs/math.md, "Membrane energy"): its four
// smooth residuals, closed-form energy and invariant partials.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_NEO_HOOKEAN_LAW_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_NEO_HOOKEAN_LAW_H_

#include <cmath>

#include "shellspace/cost_functions/shell/membrane_form_derivatives.h"
#include "shellspace/cost_functions/shell/signed_sqrt_divergence.h"
#include "shellspace/geometry/scalar_traits.h"

namespace shellspace {

// The neo-Hookean membrane law of docs/math.md, "Membrane energy" (the
// default, MembraneLaw::kNeoHookean):
// W_m(G) = mu/2 tr G + lambda/4 det G - (mu/2 + lambda/4) log
// det G - mu - lambda/4 per unit reference area, written (docs/math.md,
// "Membrane energy") with t = a + c, d = a c - b^2 = det G as
//   abar W_m = 1/2 (r0^2 + r1^2 + r2^2 + r3^2),
//   r0 = w (a - c),  r1 = 2 w b,  w = sqrt(mu abar / (t + 2 sqrt d)),
//   r2 = sqrt(2 mu abar) psi(sqrt d),  r3 = sqrt(lambda abar / 2) psi(d).
// Inputs are the distortion (a, b, c) of geometry/triangle_distortion.h and
// the reference area abar. The law knows nothing about how (a, b, c) were
// discretised.
struct NeoHookeanLaw {
  double mu = 1.0;
  double lambda = 1.0;

  // residuals[4]; if `jacobian` is non-null, jacobian[m][q] = d r_m / d q for
  // q = (a, b, c, abar). Returns false if det G <= 0 or is not finite.
  template <typename T>
  bool Evaluate(const T& a, const T& b, const T& c, const T& area, T* residuals,
                T (*jacobian)[4]) const {
    const T t = a + c;
    const T d = a * c - b * b;
    const double d_value = ScalarValue(d);
    if (!(d_value > 0.0) || !std::isfinite(d_value)) return false;
    const T sd = sqrt(d);
    const T denom = t + T(2) * sd;
    const T w = sqrt(T(mu) * area / denom);
    T psi_sd, dpsi_sd, psi_d, dpsi_d;
    SignedSqrtDivergence(sd, &psi_sd, &dpsi_sd);
    SignedSqrtDivergence(d, &psi_d, &dpsi_d);
    const T k2 = sqrt(T(2.0 * mu) * area);
    const T k3 = sqrt(T(0.5 * lambda) * area);
    residuals[0] = w * (a - c);
    residuals[1] = T(2) * w * b;
    residuals[2] = k2 * psi_sd;
    residuals[3] = k3 * psi_d;
    if (jacobian == nullptr) return true;
    // Partial derivatives of the intermediates w.r.t. q = (a, b, c, abar).
    const T dd[4] = {c, T(-2) * b, a, T(0)};
    const T dt[4] = {T(1), T(0), T(1), T(0)};
    const T darea[4] = {T(0), T(0), T(0), T(1)};
    for (int q = 0; q < 4; ++q) {
      const T dsd = dd[q] / (T(2) * sd);
      const T ddenom = dt[q] + T(2) * dsd;
      const T dw = T(0.5) * w * (darea[q] / area - ddenom / denom);
      const T da = (q == 0) ? T(1) : T(0);
      const T db = (q == 1) ? T(1) : T(0);
      const T dc = (q == 2) ? T(1) : T(0);
      jacobian[0][q] = dw * (a - c) + w * (da - dc);
      jacobian[1][q] = T(2) * (dw * b + w * db);
      jacobian[2][q] = k2 * (dpsi_sd * dsd + psi_sd * darea[q] / (T(2) * area));
      jacobian[3][q] = k3 * (dpsi_d * dd[q] + psi_d * darea[q] / (T(2) * area));
    }
    return true;
  }

  // abar W_m(G) in closed form from the invariants tr G, det G (for direct
  // energy evaluation and tests); false if det G is not positive.
  bool Energy(double tr, double det, double area, double* energy) const {
    if (!(det > 0)) return false;
    *energy = area * (mu / 2 * tr + lambda / 4 * det -
                      (mu / 2 + lambda / 4) * std::log(det) - mu - lambda / 4);
    return true;
  }

  // F(A, B, D) = abar W_m (membrane_form_derivatives.h) and its partials:
  // with s = sqrt(B) (abar = s / 2), L = log(D / B), c1 = mu/2 + lambda/4,
  // c0 = mu + lambda/4,
  //   F = mu A / (4 s) + lambda D / (8 s) - c1 s L / 2 - c0 s / 2,
  // linear in A (F_AA = F_AD = 0):
  //   F_A  = mu / (4 s),              F_AB = -mu / (8 s^3),
  //   F_D  = lambda / (8 s) - c1 s / (2 D),   F_DD = c1 s / (2 D^2),
  //   F_BD = -lambda / (16 s^3) - c1 / (4 s D),
  //   F_B  = -(mu A / 4 + lambda D / 8) / (2 s^3) + (2 c1 - c0 - c1 L) / (4 s),
  //   F_BB = 3 (mu A / 4 + lambda D / 8) / (4 s^5) + (c0 + c1 L) / (8 s^3).
  // B, D > 0 (checked by the caller).
  bool Partials(double a, double dbar, double d,
                MembraneInvariantPartials* f) const {
    const double s = std::sqrt(dbar);
    const double s3 = s * dbar;
    const double log_det = std::log(d / dbar);
    const double c1 = mu / 2 + lambda / 4, c0 = mu + lambda / 4;
    const double lin = mu * a / 4 + lambda * d / 8;
    f->f = lin / s - c1 * s * log_det / 2 - c0 * s / 2;
    f->f_a = mu / (4 * s);
    f->f_d = lambda / (8 * s) - c1 * s / (2 * d);
    f->f_b = -lin / (2 * s3) + (2 * c1 - c0 - c1 * log_det) / (4 * s);
    f->f_ab = -mu / (8 * s3);
    f->f_dd = c1 * s / (2 * d * d);
    f->f_bb = 3 * lin / (4 * s3 * dbar) + (c0 + c1 * log_det) / (8 * s3);
    f->f_bd = -lambda / (16 * s3) - c1 / (4 * s * d);
    return true;
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_NEO_HOOKEAN_LAW_H_
