// Assembled first and second derivatives of W[Sbar, S] (shells.md,
// calculus.md): D_1 W, D_2 W, D_1^2 W, D_2^2 W and the mixed D_1 D_2 W, as
// Eigen vectors and sparse matrices over the 3 n coordinates (vertex-major:
// index 3 v + c).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_ENERGY_DERIVATIVES_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_ENERGY_DERIVATIVES_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <utility>

#include "shellspace/cost_functions/deformation_energy.h"
#include "shellspace/cost_functions/shell/element_hessian.h"

namespace shellspace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// D_1 W[reference, deformed] (side kReference) or D_2 W (side kDeformed).
Eigen::VectorXd EnergyGradient(const ShellSpace& space,
                               const Positions& reference,
                               const Positions& deformed, ShellSide side);

// d/de D W[reference + e p, deformed] (moved kReference) or
// d/de D W[reference, deformed + e p] (moved kDeformed) at e = 0, with D =
// D_1 (gradient kReference) or D_2 (kDeformed): the product of the block
// EnergyHessian(gradient, moved) with p, without assembling it (dual numbers
// with one derivative over the element gradients). Throws InputError if an
// element is degenerate.
Eigen::VectorXd EnergyGradientDerivative(const ShellSpace& space,
                                         const Positions& reference,
                                         const Positions& deformed,
                                         ShellSide gradient, ShellSide moved,
                                         const Eigen::VectorXd& p);

// The block d_rows d_cols W[reference, deformed] (3n x 3n): (kDeformed,
// kDeformed) = D_2^2 W, (kReference, kReference) = D_1^2 W, (kReference,
// kDeformed) = the mixed D_1 D_2 W (rows reference, columns deformed), and
// (kDeformed, kReference) its transpose. Throws InputError if an element is
// degenerate.
SparseMatrix EnergyHessian(const ShellSpace& space, const Positions& reference,
                           const Positions& deformed, ShellSide rows,
                           ShellSide cols);

// Both second-derivative blocks with columns on the side `cols`, from one
// dual-number pass: first = d_cols D_1 W (rows reference), second = d_cols
// D_2 W (rows deformed). E.g. cols = kDeformed gives (mixed D_1 D_2 W,
// D_2^2 W).
std::pair<SparseMatrix, SparseMatrix> EnergyHessianColumns(
    const ShellSpace& space, const Positions& reference,
    const Positions& deformed, ShellSide cols);

// Calls visit(vertices, count, reference_coords, deformed_coords, element)
// for each membrane (count 3) and bending (count 4) element of `space`.
// Used by the assembly routines and the EXP residual cache.
template <class Visitor>
void ForEachElement(const ShellSpace& space, const Positions& reference,
                    const Positions& deformed, Visitor&& visit) {
  const MembraneElement membrane = space.material.membrane();
  const BendingElement bending = space.material.bending();
  double ref[12], def[12];
  for (int f = 0; f < space.faces.rows(); ++f) {
    const int vs[3] = {space.faces(f, 0), space.faces(f, 1), space.faces(f, 2)};
    for (int a = 0; a < 3; ++a) {
      for (int c = 0; c < 3; ++c) {
        ref[3 * a + c] = reference(vs[a], c);
        def[3 * a + c] = deformed(vs[a], c);
      }
    }
    visit(vs, 3, ref, def, membrane);
  }
  if (space.material.eta <= 0) return;
  for (const EdgeFlap& flap : space.topology.interior_edges) {
    const int vs[4] = {flap.i, flap.j, flap.k, flap.l};
    for (int a = 0; a < 4; ++a) {
      for (int c = 0; c < 3; ++c) {
        ref[3 * a + c] = reference(vs[a], c);
        def[3 * a + c] = deformed(vs[a], c);
      }
    }
    visit(vs, 4, ref, def, bending);
  }
}

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_ENERGY_DERIVATIVES_H_
