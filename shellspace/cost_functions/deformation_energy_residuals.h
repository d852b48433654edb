// The Ceres adapter of W[Sbar, S] = W_mem + eta W_bend (docs/math.md,
// "Deformation energy"): adds the residual blocks of every element of the
// element set (shell/element_set.h) to a ceres::Problem.
#ifndef SHELLSPACE_COST_FUNCTIONS_DEFORMATION_ENERGY_RESIDUALS_H_
#define SHELLSPACE_COST_FUNCTIONS_DEFORMATION_ENERGY_RESIDUALS_H_

#include <ceres/problem.h>

#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"

namespace shellspace {

// One argument of W inside a problem: the shell's positions (#V x 3,
// row-major: 3 doubles per vertex) and whether its vertices are Ceres
// parameter blocks (`variable`, one block of size 3 per vertex at positions +
// 3 i) or fixed data (copied into the cost functions).
struct ShellArgument {
  double* positions = nullptr;
  bool variable = false;

  static ShellArgument Variable(Positions* p) { return {p->data(), true}; }
  static ShellArgument Fixed(const Positions& p) {
    return {const_cast<double*>(p.data()), false};
  }
};

// Adds the residuals of weight * W[reference, deformed] to `problem`, one
// residual block per element of space.elements(), in its enumeration order:
// ElementCostFunction<E> of each element type E (today four membrane
// residuals per face, MembraneCostFunction, then one bending residual per
// interior edge, BendingCostFunction, none if eta = 0), parameter blocks the
// stencil's reference vertices (if variable) then its deformed vertices (if
// variable). At least one argument must be variable. Appends the residual
// block ids to `ids` if given.
void AddDeformationEnergy(const ShellSpace& space, ShellArgument reference,
                          ShellArgument deformed, double weight,
                          ceres::Problem* problem,
                          std::vector<ceres::ResidualBlockId>* ids = nullptr);

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_DEFORMATION_ENERGY_RESIDUALS_H_
