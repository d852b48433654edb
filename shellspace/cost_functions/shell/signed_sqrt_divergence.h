// psi(x) = sign(x - 1) sqrt(x - 1 - log x), the smooth signed square root
// of the divergence x - 1 - log x that the neo-Hookean membrane law's
// residuals are made of (neo_hookean_law.h).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_SIGNED_SQRT_DIVERGENCE_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_SIGNED_SQRT_DIVERGENCE_H_

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

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_SIGNED_SQRT_DIVERGENCE_H_
