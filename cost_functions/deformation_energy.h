// The deformation energy W[Sbar, S] = W_mem + eta W_bend (shells.md): adding
// its residuals to a ceres::Problem, and evaluating it directly.
#ifndef SHELLSPACE_COST_FUNCTIONS_DEFORMATION_ENERGY_H_
#define SHELLSPACE_COST_FUNCTIONS_DEFORMATION_ENERGY_H_

#include <ceres/problem.h>

#include <vector>

#include "shellspace/cost_functions/shell/bending_element.h"
#include "shellspace/cost_functions/shell/membrane_element.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"

namespace shellspace {

// Material parameters: membrane Lame-type weights mu, lambda > 0 and bending
// weight eta >= 0 (the squared thickness).
struct ShellMaterial {
  double mu = 1.0;
  double lambda = 1.0;
  double eta = 0.01;

  MembraneElement membrane() const {
    MembraneElement element;
    element.law.mu = mu;
    element.law.lambda = lambda;
    return element;
  }
  BendingElement bending() const {
    BendingElement element;
    element.eta = eta;
    return element;
  }
  // Throws InputError unless mu > 0, lambda > 0, eta >= 0 (all finite).
  void Validate() const;
};

// The space of shells with one connectivity: faces, their topology and the
// material of W. Every problem of the calculus is posed on one ShellSpace.
struct ShellSpace {
  Faces faces;
  Topology topology;
  ShellMaterial material;
  int num_vertices = 0;

  ShellSpace() = default;
  ShellSpace(const Mesh& mesh, const Topology& topo, const ShellMaterial& mat)
      : faces(mesh.faces),
        topology(topo),
        material(mat),
        num_vertices(mesh.num_vertices()) {}
};

// One argument of W inside a problem: the shell's positions (3 doubles per
// vertex, row-major) and whether its vertices are Ceres parameter blocks
// (`variable`, one block of size 3 per vertex at positions + 3 i) or fixed
// data (copied into the cost functions).
struct ShellArgument {
  double* positions = nullptr;
  bool variable = false;

  static ShellArgument Variable(Positions* p) { return {p->data(), true}; }
  static ShellArgument Fixed(const Positions& p) {
    return {const_cast<double*>(p.data()), false};
  }
};

// Adds the residuals of weight * W[reference, deformed] to `problem`: four
// membrane residuals per face (MembraneCostFunction) and one bending residual
// per interior edge (BendingCostFunction, skipped if eta = 0). At least one
// argument must be variable. Appends the residual block ids to `ids` if given.
void AddDeformationEnergy(const ShellSpace& space, ShellArgument reference,
                          ShellArgument deformed, double weight,
                          ceres::Problem* problem,
                          std::vector<ceres::ResidualBlockId>* ids = nullptr);

// The parts of W.
struct DeformationEnergy {
  double membrane = 0;  // W_mem
  double bending = 0;   // W_bend (without the factor eta)
  double total = 0;     // W_mem + eta W_bend
};

// Evaluates W[reference, deformed] directly from the closed-form membrane
// density (tr and det of gbar^-1 g) and the bending sum, independently of the
// residual form. Throws InputError if a triangle is degenerate.
DeformationEnergy EvaluateDeformationEnergy(const ShellSpace& space,
                                            const Positions& reference,
                                            const Positions& deformed);

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_DEFORMATION_ENERGY_H_
