// The space of shells of one connectivity and the material of W[Sbar, S] =
// W_mem + eta W_bend (docs/math.md, "Deformation energy"): ShellMaterial
// (membrane law and its weights, bending model and its weight) and ShellSpace
// (faces, topology, material and the element set of W built from them).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_SHELL_SPACE_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_SHELL_SPACE_H_

#include <memory>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/bending_element.h"
#include "shellspace/cost_functions/shell/membrane_element.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/topology.h"

namespace shellspace {

// The discretisation of W_bend (docs/math.md, "Bending energy: two models"),
// an axis independent of the membrane law:
//   kDiscreteShells: sum over interior edges of (theta - thetabar)^2 |Ebar|^2
//     / dbar_E (BendingElement).
//   kShapeOperator: sum over faces of abar (alpha (tr M)^2 + beta tr(M^2)),
//     M = Gbar^-1 (H - Hbar) from mid-edge normals (ShapeOperatorElement).
enum class BendingModel { kDiscreteShells, kShapeOperator };

// "discrete-shells" / "shape-operator".
const char* BendingModelName(BendingModel model);
// The model called `name` (BendingModelName); false if there is none.
bool ParseBendingModel(const std::string& name, BendingModel* model);

// Material parameters, on two independent axes: the membrane law
// (membrane_law.h) with its Lame-type weights mu, lambda > 0, and the
// bending model with its weight eta >= 0 (the squared thickness) and, for
// kShapeOperator, its weights alpha (of (tr M)^2) and beta (of tr(M^2)),
// beta >= 0 and alpha + beta / 2 >= 0 (so the energy is >= 0).
struct ShellMaterial {
  double mu = 1.0;
  double lambda = 1.0;
  double eta = 0.01;
  BendingModel bending_model = BendingModel::kDiscreteShells;
  double shape_operator_alpha = 0.0;
  double shape_operator_beta = 1.0;
  // Last, so that ShellMaterial{mu, lambda, eta} keeps its meaning.
  MembraneLaw membrane_law = MembraneLaw::kNeoHookean;

  // The membrane element of the law type `Law` with this material's mu,
  // lambda (the caller picks Law by membrane_law).
  template <class Law = NeoHookeanLaw>
  MembraneElementOf<Law> membrane() const {
    MembraneElementOf<Law> element;
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
  // The shape-operator bending element (any number of interior edges) with
  // weight eta and this material's alpha, beta.
  template <class Element>
  Element shape_operator() const {
    Element element;
    element.eta = eta;
    element.alpha = shape_operator_alpha;
    element.beta = shape_operator_beta;
    return element;
  }
  // Throws InputError unless membrane_law is a MembraneLaw value, mu > 0,
  // lambda > 0, eta >= 0 (all finite), bending_model is a BendingModel value and the shape-operator weights
  // are finite with beta >= 0, alpha + beta / 2 >= 0.
  void Validate() const;
};

// The ids an element set's descriptions name, for a space whose numbering is
// not the caller's (shell_space_renumbering.h): vertices[v], faces[f] and
// interior_edges[e] are the caller's ids of the space's vertex v, face f and
// interior edge e. An empty list names the space's own ids.
struct ElementLabels {
  std::vector<int> vertices, faces, interior_edges;
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
  // The same with the ids its element descriptions name (ElementLabels).
  ShellSpace(const Mesh& mesh, const Topology& topo, const ShellMaterial& mat,
             const ElementLabels& labels);

  // The element set of W on this space. Throws std::logic_error for a
  // default-constructed space or one whose members were changed after
  // construction.
  const ElementSet& elements() const;

 private:
  std::shared_ptr<const ElementSet> elements_;  // shared by copies
};

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_SHELL_SPACE_H_
