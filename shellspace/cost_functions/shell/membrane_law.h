// The membrane law of docs/math.md, "Membrane energy", as 4 smooth residuals.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_LAW_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_LAW_H_

#include <cmath>

#include "shellspace/geometry/scalar_traits.h"

namespace shellspace {

// psi(x) = sign(x - 1) sqrt(f(x)), f(x) = x - 1 - log x, and psi'(x).
// With u = x - 1: f = u^2 h(u), h(u) = sum_{n>=0} (-u)^n / (n + 2), so
// psi = u sqrt(h(u)) is smooth through x = 1 (psi ~ (x - 1)/sqrt 2). For
// |u| < 0.1 h and h' are summed as series (error < 1e-17), avoiding the
// cancellation in x - 1 - log x.
template <typename T>
void SignedSqrtDivergence(const T& x, T* psi, T* dpsi) {
  const T u = x - T(1);
  const double u_value = ScalarValue(u);
  T h, dh;
  if (std::abs(u_value) < 0.1) {
    // Horner on h(u) = sum c_n u^n, c_n = (-1)^n / (n + 2), n = 0..17.
    h = T(0);
    dh = T(0);
    for (int n = 17; n >= 0; --n) {
      const double c = ((n % 2) ? -1.0 : 1.0) / (n + 2);
      dh = dh * u + h;
      h = h * u + T(c);
    }
  } else {
    h = (u - log(x)) / (u * u);
    dh = T(1) / (u * x) - T(2) * h / u;
  }
  const T sqrt_h = sqrt(h);
  *psi = u * sqrt_h;
  *dpsi = sqrt_h + u * dh / (T(2) * sqrt_h);
}

// Membrane law W_m(G) = mu/2 tr G + lambda/4 det G - (mu/2 + lambda/4) log
// det G - mu - lambda/4 per unit reference area, written (docs/math.md,
// "Membrane energy") with t = a + c, d = a c - b^2 = det G as
//   abar W_m = 1/2 (r0^2 + r1^2 + r2^2 + r3^2),
//   r0 = w (a - c),  r1 = 2 w b,  w = sqrt(mu abar / (t + 2 sqrt d)),
//   r2 = sqrt(2 mu abar) psi(sqrt d),  r3 = sqrt(lambda abar / 2) psi(d).
// Inputs are the distortion (a, b, c) of geometry/triangle_distortion.h and
// the reference area abar. The law knows nothing about how (a, b, c) were
// discretised.
struct MembraneLaw {
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

  // Closed form of abar W_m(G) (for tests and direct energy evaluation).
  double Energy(double a, double b, double c, double area) const {
    const double t = a + c, d = a * c - b * b;
    return area * (mu / 2 * t + lambda / 4 * d -
                   (mu / 2 + lambda / 4) * std::log(d) - mu - lambda / 4);
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_LAW_H_
