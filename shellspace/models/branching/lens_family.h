// The lens cell (docs/math.md, "Branching: the Kohn–Müller model"): in the
// middle of EACH existing lamella a lamella of the other variant nucleates as a
// needle whose tip sits inside the cell; each lamella becomes three, so r = 3.
//
// Cell (units: period h; coordinates s, eta of cell_pattern.h). Coarse end:
// -1 on [0, 1/4), +1 on [1/4, 3/4), -1 on [3/4, 1); the two old interfaces
// eta = 1/4 (jump +2) and 3/4 (jump -2) stay straight. For s >= tau (the tip)
// two needles of full width W(s) open:
//   a -1 needle in the +1 lamella: 1/2 - W/2 (jump -2), 1/2 + W/2 (jump +2),
//   a +1 needle in the -1 lamella: -W/2 (jump +2), W/2 (jump -2)  (mod 1),
//   W(s) = phi(t) / 6,  t = (s - tau) / (1 - tau),
//   phi(t) = t + a1 t (1 - t) + a2 t^2 (1 - t)   (phi(0) = 0, phi(1) = 1).
// At s = 1 all six pieces have width 1/6: the laminate of period 1/3 with the
// variants swapped, so the next generation starts at eta = 1/2 * (1/3)
// (next_offset = 1/2). The +1 fraction is 1/2 in every column without moving
// the old interfaces (the two needles trade equal areas).
// Shape parameters: tau in [0, 1) (tip position), a1, a2 (curvature of the
// needle flanks; a1 = a2 = 0: straight wedge). The sides are curved and meet
// at the tip: a lens-shaped needle.
//
// Reduced energy. With W' = dW/ds, F = -sum jump_i g_i' is 0 on the outer
// parts of the -1 lamella (width 1/2 - W), -W' on both needles (width 2W) and
// -2W' on the outer parts of the +1 lamella (width 1/2 - W); its variance is
//   Var F = W'^2 (1 - 2W),
// so (Gauss–Legendre, exact: the integrand is a polynomial of degree 7)
//   A = \int_tau^1 (1 - 2W) W'^2 ds = J(a1, a2) / (1 - tau),
//   J = \int_0^1 (1 - phi/3) (phi_t / 6)^2 dt,
//   B = 2 (2 + 4 (1 - tau)) = 12 - 8 tau.
// The metric (1 - 2W) dW^2 is not flat: its geodesic (1 - 2W)^(3/2) linear in
// s is a curved (lens) profile, which a1, a2 approximate.
#ifndef SHELLSPACE_MODELS_BRANCHING_LENS_FAMILY_H_
#define SHELLSPACE_MODELS_BRANCHING_LENS_FAMILY_H_

#include "shellspace/models/branching/cell_pattern.h"

namespace shellspace::branching {

struct LensShape {
  double tau = 0.0;
  double a1 = 0.0;
  double a2 = 0.0;
};

// Bounds keeping the geometry valid (0 <= W <= 1/4, needles inside their
// lamellae): tau in [0, kLensTauMax], |a1|, |a2| <= kLensCurvatureMax.
constexpr double kLensTauMax = 0.95;
constexpr double kLensCurvatureMax = 0.9;
constexpr int kLensRatio = 3;

// Throws InputError outside the bounds.
void CheckLensShape(const LensShape& shape);

// The cell as curves (for EvaluateCell and rendering).
CellPattern LensCellPattern(const LensShape& shape);

// phi, phi_t and their derivatives with respect to (a1, a2).
struct LensProfile {
  double phi, phi_t;
  double dphi_da1, dphi_da2, dphit_da1, dphit_da2;
};
LensProfile EvaluateLensProfile(const LensShape& shape, double t);

// Reduced coefficients (formulas above); `dA` (if not null) receives
// dA/d(tau, a1, a2), `dB` (if not null) dB/dtau.
double LensReducedA(const LensShape& shape, double dA[3] = nullptr);
double LensReducedB(const LensShape& shape, double* dB = nullptr);

}  // namespace shellspace::branching

#endif  // SHELLSPACE_MODELS_BRANCHING_LENS_FAMILY_H_
