// The space of shells of one connectivity and the material of W[Sbar, S] =
// W_mem + eta W_bend (shells.md): ShellMaterial (membrane law weights, bending
// weight, bending model) and ShellSpace (faces, topology, material and the
// element set of W built from them).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_SHELL_SPACE_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_SHELL_SPACE_H_

#include <memory>

#include "shellspace/cost_functions/shell/bending_element.h"
#include "shellspace/cost_functions/shell/membrane_element.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"

namespace shellspace {

// The discretisation of W_bend, an axis independent of the membrane law:
//   kDiscreteShells: sum over interior edges of (theta - thetabar)^2 |Ebar|^2
//     / dbar_E (BendingElement; shells.md).
// (The discrete shape operator of shape_operator.md is the next value; see
// the recipe in element_set.h.)
enum class BendingModel { kDiscreteShells };

// Material parameters: membrane Lame-type weights mu, lambda > 0, bending
// weight eta >= 0 (the squared thickness) and the bending model.
struct ShellMaterial {
  double mu = 1.0;
  double lambda = 1.0;
  double eta = 0.01;
  BendingModel bending_model = BendingModel::kDiscreteShells;

  // The membrane element of this law (MembraneElement: mu, lambda).
  MembraneElement membrane() const {
    MembraneElement element;
    element.law.mu = mu;
    element.law.lambda = lambda;
    return element;
  }
  // The Discrete-Shells bending element with weight eta.
  BendingElement bending() const {
    BendingElement element;
    element.eta = eta;
    return element;
  }
  // Throws InputError unless mu > 0, lambda > 0, eta >= 0 (all finite) and
  // bending_model is a BendingModel value.
  void Validate() const;
};

class ElementSet;

// The space of shells with one connectivity: faces, their topology, the
// material of W and the element set of W (element_set.h: which terms make W,
// built once here). Every problem of the calculus is posed on one ShellSpace.
// The members are not to be changed after construction: build a new
// ShellSpace instead (elements() checks that the material and mesh sizes are
// still those the set was built for).
struct ShellSpace {
  Faces faces;        // #F x 3
  Topology topology;
  ShellMaterial material;
  int num_vertices = 0;

  ShellSpace() = default;
  ShellSpace(const Mesh& mesh, const Topology& topo, const ShellMaterial& mat);

  // The element set of W on this space. Throws std::logic_error for a
  // default-constructed space or one whose members were changed after
  // construction.
  const ElementSet& elements() const;

 private:
  std::shared_ptr<const ElementSet> elements_;  // shared by copies
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_SHELL_SPACE_H_
