// The St. Venant-Kirchhoff membrane law (docs/math.md, "Membrane energy:
// other laws"): its four residuals, closed-form energy and invariant
// partials.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_ST_VENANT_KIRCHHOFF_LAW_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_ST_VENANT_KIRCHHOFF_LAW_H_

#include <cmath>

#include "shellspace/cost_functions/shell/membrane_form_derivatives.h"
#include "shellspace/geometry/scalar_traits.h"

namespace shellspace {

// W_svk(G) = mu tr(E^2) + lambda/2 (tr E)^2 per unit reference area, with the
// Green-Lagrange strain E = (G - I) / 2. In the distortion G = [[a, b],
// [b, c]] of an orthonormal frame of the reference triangle
// (geometry/triangle_distortion.h), abar W_svk = 1/2 (r0^2 + .. + r3^2) with
// residuals linear in (a, b, c):
//   r0 = sqrt(mu abar / 2) (a - 1),   r1 = sqrt(mu abar) b,
//   r2 = sqrt(mu abar / 2) (c - 1),   r3 = sqrt(lambda abar) (a + c - 2) / 2,
// so Gauss-Newton is exact in G. Unlike the neo-Hookean law the energy stays
// finite as a triangle degenerates (no barrier against crushing or
// inversion); a degenerate deformed triangle (det G <= 0) is still rejected,
// as by every law, so that the verdicts of the whole library do not depend on
// the law.
struct StVenantKirchhoffLaw {
  double mu = 1.0;
  double lambda = 1.0;

  // residuals[4]; if `jacobian` is non-null, jacobian[m][q] = d r_m / d q for
  // q = (a, b, c, abar). Returns false if det G <= 0 or is not finite.
  template <typename T>
  bool Evaluate(const T& a, const T& b, const T& c, const T& area, T* residuals,
                T (*jacobian)[4]) const {
    const double d_value = ScalarValue(a * c - b * b);
    if (!(d_value > 0.0) || !std::isfinite(d_value)) return false;
    const T k0 = sqrt(T(0.5 * mu) * area);
    const T k1 = sqrt(T(mu) * area);
    const T k3 = T(0.5) * sqrt(T(lambda) * area);
    residuals[0] = k0 * (a - T(1));
    residuals[1] = k1 * b;
    residuals[2] = k0 * (c - T(1));
    residuals[3] = k3 * (a + c - T(2));
    if (jacobian == nullptr) return true;
    // Each residual is sqrt(abar) times a function of (a, b, c):
    // d r / d abar = r / (2 abar).
    const T half_over_area = T(0.5) / area;
    const T zero(0);
    const T rows[4][3] = {
        {k0, zero, zero}, {zero, k1, zero}, {zero, zero, k0}, {k3, zero, k3}};
    for (int m = 0; m < 4; ++m) {
      for (int q = 0; q < 3; ++q) jacobian[m][q] = rows[m][q];
      jacobian[m][3] = residuals[m] * half_over_area;
    }
    return true;
  }

  // abar W_svk(G) in closed form from the invariants tr G, det G:
  // tr(E^2) = (tr G^2 - 2 tr G + 2) / 4 with tr G^2 = (tr G)^2 - 2 det G,
  // tr E = (tr G - 2) / 2. False if det G is not positive.
  bool Energy(double tr, double det, double area, double* energy) const {
    if (!(det > 0)) return false;
    *energy = area * (mu / 4 * (tr * tr - 2 * det - 2 * tr + 2) +
                      lambda / 8 * (tr - 2) * (tr - 2));
    return true;
  }

  // F(A, B, D) = abar W_svk (membrane_form_derivatives.h): with tr G = A / B,
  // det G = D / B, abar = sqrt(B) / 2, k = mu/8 + lambda/16 and
  // c = (mu + lambda) / 4,
  //   F = k A^2 B^-3/2 - (mu / 4) D B^-1/2 - c A B^-1/2 + c B^1/2,
  // linear in D (F_DD = F_AD = 0):
  //   F_A  = 2 k A B^-3/2 - c B^-1/2,     F_AA = 2 k B^-3/2,
  //   F_D  = -(mu / 4) B^-1/2,            F_BD = (mu / 8) B^-3/2,
  //   F_B  = -3/2 k A^2 B^-5/2 + (mu / 8) D B^-3/2 + c/2 A B^-3/2
  //          + c/2 B^-1/2,
  //   F_AB = -3 k A B^-5/2 + c/2 B^-3/2,
  //   F_BB = 15/4 k A^2 B^-7/2 - 3/16 mu D B^-5/2 - 3/4 c A B^-5/2
  //          - c/4 B^-3/2.
  // B, D > 0 (checked by the caller).
  bool Partials(double a, double dbar, double d,
                MembraneInvariantPartials* f) const {
    const double k = mu / 8 + lambda / 16, c = (mu + lambda) / 4;
    const double s = std::sqrt(dbar);  // B^1/2
    const double b1 = 1 / s;           // B^-1/2
    const double b3 = b1 / dbar;       // B^-3/2
    const double b5 = b3 / dbar;       // B^-5/2
    const double b7 = b5 / dbar;       // B^-7/2
    f->f = k * a * a * b3 - mu / 4 * d * b1 - c * a * b1 + c * s;
    f->f_a = 2 * k * a * b3 - c * b1;
    f->f_d = -mu / 4 * b1;
    f->f_b = -1.5 * k * a * a * b5 + mu / 8 * d * b3 + c / 2 * a * b3 +
             c / 2 * b1;
    f->f_aa = 2 * k * b3;
    f->f_ab = -3 * k * a * b5 + c / 2 * b3;
    f->f_bd = mu / 8 * b3;
    f->f_bb = 3.75 * k * a * a * b7 - 0.1875 * mu * d * b5 -
              0.75 * c * a * b5 - c / 4 * b3;
    return true;
  }
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_ST_VENANT_KIRCHHOFF_LAW_H_
