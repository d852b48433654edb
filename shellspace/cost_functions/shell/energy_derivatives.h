// First and second derivatives of W[Sbar, S] (docs/math.md, "Derivatives and
// the rigid-motion gauge"): D_1 W, D_2 W, D_1^2 W, D_2^2 W and D_1 D_2 W as
// Eigen vectors and sparse matrices over the 3 n coordinates (vertex-major:
// index 3 v + c), assembled over the element set of the space (element_set.h).
// Each function throws InputError naming the element if one is degenerate;
// its Try twin returns false instead (*failure, if given, names the first
// degenerate element of the enumeration; the output is unspecified): the
// status for line searches, which must not use exceptions as control flow.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_ENERGY_DERIVATIVES_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_ENERGY_DERIVATIVES_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <utility>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/cost_functions/shell/element_set.h"
#include "shellspace/cost_functions/shell/shell_space.h"

namespace shellspace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// D_1 W[reference, deformed] (side kReference) or D_2 W (side kDeformed),
// 3n (reference and deformed #V x 3).
Eigen::VectorXd EnergyGradient(const ShellSpace& space,
                               const Positions& reference,
                               const Positions& deformed, ShellSide side);
bool TryEnergyGradient(const ShellSpace& space, const Positions& reference,
                       const Positions& deformed, ShellSide side,
                       Eigen::VectorXd* gradient,
                       ElementFailure* failure = nullptr);
// Both gradients in one pass over the elements, each element evaluated once
// with both Jacobians (for a path, whose inner shapes are the deformed shell
// of one term and the reference of the next): *of_reference = D_1 W,
// *of_deformed = D_2 W (either may be null), the same digits as
// TryEnergyGradient for each side.
bool TryEnergyGradients(const ShellSpace& space, const Positions& reference,
                        const Positions& deformed,
                        Eigen::VectorXd* of_reference,
                        Eigen::VectorXd* of_deformed,
                        ElementFailure* failure = nullptr);

// d/de D W[reference + e p, deformed] (moved kReference) or
// d/de D W[reference, deformed + e p] (moved kDeformed) at e = 0, with D =
// D_1 (gradient kReference) or D_2 (kDeformed): the product of the block
// EnergyHessian(gradient, moved) with p, without assembling it (per element
// its analytic second-derivative block times p; for an element without them,
// dual numbers with one derivative over the element gradient). Throws
// InputError if an element is degenerate.
Eigen::VectorXd EnergyGradientDerivative(const ShellSpace& space,
                                         const Positions& reference,
                                         const Positions& deformed,
                                         ShellSide gradient, ShellSide moved,
                                         const Eigen::VectorXd& p);
bool TryEnergyGradientDerivative(const ShellSpace& space,
                                 const Positions& reference,
                                 const Positions& deformed, ShellSide gradient,
                                 ShellSide moved, const Eigen::VectorXd& p,
                                 Eigen::VectorXd* derivative,
                                 ElementFailure* failure = nullptr);

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
bool TryEnergyHessianColumns(const ShellSpace& space,
                             const Positions& reference,
                             const Positions& deformed, ShellSide cols,
                             std::pair<SparseMatrix, SparseMatrix>* blocks,
                             ElementFailure* failure = nullptr);

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_ENERGY_DERIVATIVES_H_
