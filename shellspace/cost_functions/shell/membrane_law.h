// The membrane law of W_mem (docs/math.md, "Membrane energy"), an axis
// independent of the bending model (shell_space.h): the choice MembraneLaw
// and the registry of the law types.
//
// A law type (NeoHookeanLaw, StVenantKirchhoffLaw are examples) is an
// isotropic energy density W(G) of the distortion G of a triangle, with
// parameters mu, lambda, providing
//   template <typename T> bool Evaluate(const T& a, const T& b, const T& c,
//       const T& abar, T* residuals, T (*jacobian)[4]) const;
//       // 4 residuals with 1/2 |r|^2 = abar W(G), G = [[a, b], [b, c]] in an
//       // orthonormal frame of the reference triangle, and their derivatives
//       // in (a, b, c, abar); false if det G <= 0 or not finite
//   bool Energy(double tr, double det, double abar, double* e) const;
//       // abar W in closed form from tr G, det G (independent of the
//       // residuals); false if det G <= 0
//   bool Partials(double A, double B, double D,
//                 MembraneInvariantPartials* f) const;
//       // abar W as F(A, B, D) of the first fundamental forms and its first
//       // and second partials (membrane_form_derivatives.h)
// MembraneElementOf<Law> (membrane_element.h) composes it with the triangle's
// geometry; every evaluator, the Ceres adapter and the path Hessian take it
// from there.
//
// Adding a law: write <law>_law.h with the type above (and its closed-form
// test), include it below and add one line to SHELLSPACE_MEMBRANE_LAWS. The
// derivative tests of the element set run on every registered law.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_LAW_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_LAW_H_

#include <string>

#include "shellspace/cost_functions/shell/neo_hookean_law.h"
#include "shellspace/cost_functions/shell/st_venant_kirchhoff_law.h"

namespace shellspace {

// The registered laws: X(type, MembraneLaw value, name).
#define SHELLSPACE_MEMBRANE_LAWS(X)                          \
  X(NeoHookeanLaw, kNeoHookean, "neo-hookean")               \
  X(StVenantKirchhoffLaw, kStVenantKirchhoff, "st-venant-kirchhoff")

// Which law W_mem uses (ShellMaterial::membrane_law); kNeoHookean is the
// law of the specification and the default.
#define SHELLSPACE_MEMBRANE_LAW_VALUE(type, value, name) value,
enum class MembraneLaw { SHELLSPACE_MEMBRANE_LAWS(SHELLSPACE_MEMBRANE_LAW_VALUE) };
#undef SHELLSPACE_MEMBRANE_LAW_VALUE

// "neo-hookean" / "st-venant-kirchhoff".
const char* MembraneLawName(MembraneLaw law);
// The law called `name` (MembraneLawName); false if there is none.
bool ParseMembraneLaw(const std::string& name, MembraneLaw* law);
// The registered names, "neo-hookean or st-venant-kirchhoff" (for messages
// and help texts).
std::string MembraneLawNames();

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_MEMBRANE_LAW_H_
