// The element set of W[Sbar, S] (docs/math.md, "Deformation energy"): the
// explicit list of the energy terms of W on one connectivity -- per term its
// element type, stencils (the vertex lists of its elements) and weight -- in
// ONE enumeration order, built once per ShellSpace (ShellSpace::elements()).
// Every evaluation over a mesh iterates it: the energy value and its
// derivatives (shell/deformation_energy.h, shell/energy_derivatives.h), the
// Ceres residuals (deformation_energy_residuals.h), the EXP residual cache
// (gradient_field_residual.h) and the path Hessian assembler
// (problems/calculus/path_hessian.h).
//
// Today's terms, in this order:
//   1. membrane, one element per face f (stencil (i, j, k) = faces(f, .)),
//      MembraneElementOf<the material's law> (membrane_law.h), weight 1;
//   2. bending, weight eta, not a term of W when eta = 0 (ForEachGroup skips
//      it), by the material's BendingModel:
//      kDiscreteShells: one element per interior edge e (stencil (i, j, k,
//        l) = topology.interior_edges[e]), BendingElement;
//      kShapeOperator: one element per face, ShapeOperatorElement<m>, in four
//        groups by the face's number m = 3, 2, 1, 0 of interior edges (in
//        this order, faces in increasing index within a group); stencil the
//        face rotated cyclically so its interior edges are edges 0 .. m-1,
//        then the vertices across them (shape_operator_element.h).
// Element e of the enumeration is element e - group.first_element of the
// group that holds it; groups come in the order above.
//
// An element type E provides (MembraneElement, BendingElement are examples):
//   static constexpr int kNumVertices;   // stencil size
//   static constexpr int kNumResiduals;
//   template <typename T> using Jacobian =
//       Eigen::Matrix<T, kNumResiduals, 3 kNumVertices>;   // row-major
//   template <typename T> bool Evaluate(const Vec3<T>* ref, const Vec3<T>* def,
//       T* residuals, Jacobian<T>* jac_ref, Jacobian<T>* jac_def) const;
//       // 1/2 |r|^2 = weight * e (the group's weight is folded into the
//       // element's parameters, as BendingElement::eta); false if degenerate
//   bool Energy(const Vec3<double>* ref, const Vec3<double>* def,
//       double* e) const;   // the unweighted term e in closed form,
//                           // independent of the residuals; false if
//                           // degenerate
// and optionally
//   bool SecondDerivatives(const double* ref, const double* def,
//       ShellSide active, double weight, Rows rows,
//       ElementSecondDerivatives<kNumVertices>* out) const;
//       // hand-derived second derivatives (element_hessian.h); without it
//       // they are taken by dual numbers over Evaluate's J^T r
// and the evaluators are templates over it (ElementSecondDerivatives,
// ElementCostFunction, ...): no evaluator names an element type.
//
// Recipe: adding a bending model (e.g. the shape operator of docs/math.md,
// "Bending energy: two models", 3 residuals per face, stencil = the face and
// the opposite vertices of its interior edges: up to 6 vertices)
//   1. write its element class (cost_functions/shell/<model>_element.h) with
//      the interface above, with its own FD Jacobian test and negative twin,
//      and SHELLSPACE_ELEMENT_HESSIAN_TEMPLATES(extern template, E) after it,
//      (template, E) in <model>_element.cc: its second derivatives compiled
//      once (element_hessian.h);
//   2. add a BendingModel value (shell_space.h);
//   3. one entry in the set: its ElementGroup<E> in AnyElementGroup below and
//      the case of its BendingModel in ElementSet's constructor
//      (element_set.cc) that fills the group's stencils and weight eta.
// A model whose stencil size varies (faces with 3, 2, 1, 0 interior edges)
// adds one group per size, e.g. an element templated on the number of
// interior edges with the face rotated so that boundary edges come last.
// Nothing else changes: every evaluator, the Ceres adapter, the EXP cache and
// the path Hessian pick the new groups up through ForEachGroup.
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_SET_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_SET_H_

#include <array>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "shellspace/cost_functions/shell/bending_element.h"
#include "shellspace/cost_functions/shell/membrane_element.h"
#include "shellspace/cost_functions/shell/shape_operator_element.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/scalar_traits.h"
#include "shellspace/geometry/topology.h"

namespace shellspace {

// Which part of DeformationEnergy (shell/deformation_energy.h) a term adds to.
enum class EnergyPart { kMembrane, kBending };

// One term of W: `stencils.size()` elements of type E.
template <class E>
struct ElementGroup {
  using Element = E;
  static constexpr int kVertices = E::kNumVertices;
  using Stencil = std::array<int, kVertices>;

  const char* term = "";          // e.g. "membrane"
  const char* stencil_kind = "";  // what stencil i is: e.g. "triangle"
  EnergyPart part = EnergyPart::kMembrane;
  double weight = 1;  // the factor of the term in W (folded into `element`)
  E element;          // the element with the material's parameters
  std::vector<Stencil> stencils;  // vertex lists (#elements x kVertices)
  // The id of element i that Describe names (e.g. its face), if not empty;
  // else i.
  std::vector<int> labels;
  // The id Describe names for vertex v of a stencil (ElementLabels::
  // vertices), if set and not empty; else v.
  std::shared_ptr<const std::vector<int>> vertex_labels;
  // Index of stencils[0] in the set's enumeration; -1 if the term has weight
  // 0 (not a term of W; only EvaluateDeformationEnergy reports its value).
  int first_element = -1;

  int size() const { return static_cast<int>(stencils.size()); }
  bool in_energy() const { return first_element >= 0; }
  // "membrane element of triangle 17 (vertices 3, 5, 9)".
  std::string Describe(int i) const {
    std::string out = std::string(term) + " element of " + stencil_kind + " " +
                      std::to_string(labels.empty() ? i : labels[i]) +
                      " (vertices";
    for (int a = 0; a < kVertices; ++a) {
      const int v = stencils[i][a];
      out += (a ? ", " : " ") +
             std::to_string(vertex_labels && !vertex_labels->empty()
                                ? (*vertex_labels)[v]
                                : v);
    }
    return out + ")";
  }
};

// The element types a set can hold, one alternative per type: the membrane
// element of every registered law (membrane_law.h), then the bending
// elements.
#define SHELLSPACE_MEMBRANE_GROUP(type, value, name) \
  ElementGroup<MembraneElementOf<type>>,
using AnyElementGroup =
    std::variant<SHELLSPACE_MEMBRANE_LAWS(SHELLSPACE_MEMBRANE_GROUP)
                     ElementGroup<BendingElement>,
                 ElementGroup<ShapeOperatorElement<3>>,
                 ElementGroup<ShapeOperatorElement<2>>,
                 ElementGroup<ShapeOperatorElement<1>>,
                 ElementGroup<ShapeOperatorElement<0>>>;
#undef SHELLSPACE_MEMBRANE_GROUP

// The first element at which an evaluation over the set stopped (the lowest
// enumeration index among the failing ones, whatever the threading).
struct ElementFailure {
  int element = -1;         // index in the enumeration (-1: weight-0 term)
  std::string description;  // ElementGroup::Describe
};

class ElementSet {
 public:
  // Throws InputError for an unknown material.membrane_law or
  // material.bending_model.
  ElementSet(const Faces& faces, const Topology& topology,
             const ShellMaterial& material, const ElementLabels& labels = {});

  // Calls visit(group) (a generic callable over ElementGroup<E>) for every
  // term of W, in the enumeration order.
  template <class Visitor>
  void ForEachGroup(Visitor&& visit) const {
    for (const AnyElementGroup& any : groups_) {
      std::visit(
          [&](const auto& group) {
            if (group.in_energy()) visit(group);
          },
          any);
    }
  }
  // Also the groups of weight 0 (eta = 0), whose unweighted values
  // DeformationEnergy still reports.
  template <class Visitor>
  void ForEachGroupWithZeroWeight(Visitor&& visit) const {
    for (const AnyElementGroup& any : groups_) {
      std::visit([&](const auto& group) { visit(group); }, any);
    }
  }

  // Elements of the terms of W (#F + #interior edges (Discrete Shells) or
  // #F + #F (shape operator) if eta > 0, else #F).
  int num_elements() const { return num_elements_; }
  // Describe(i) of the group holding enumeration index `element`.
  std::string Describe(int element) const;
  // Fills *failure (if non-null) for enumeration index `element`.
  void Fail(int element, ElementFailure* failure) const;

  // What the set was built for (ShellSpace::elements() checks it).
  const ShellMaterial& material() const { return material_; }
  int num_faces() const { return num_faces_; }
  int num_interior_edges() const { return num_interior_edges_; }

 private:
  template <class E>
  void Add(ElementGroup<E> group);
  // The membrane term: `element` on every face.
  template <class Law>
  void AddMembraneGroup(const MembraneElementOf<Law>& element,
                        const Faces& faces,
                        const std::vector<int>& face_labels);
  void AddShapeOperatorGroups(const Faces& faces, const Topology& topology,
                              const ShellMaterial& material,
                              const std::vector<int>& face_labels);

  std::vector<AnyElementGroup> groups_;
  int num_elements_ = 0;
  ShellMaterial material_;
  int num_faces_ = 0;
  int num_interior_edges_ = 0;
};

// Coordinates of a stencil's vertices: out[3 a + c] = p(stencil[a], c).
template <std::size_t kV>
void GatherCoordinates(const Positions& p, const std::array<int, kV>& stencil,
                       double* out) {
  for (std::size_t a = 0; a < kV; ++a) {
    for (int c = 0; c < 3; ++c) out[3 * a + c] = p(stencil[a], c);
  }
}
template <std::size_t kV>
void GatherVertices(const Positions& p, const std::array<int, kV>& stencil,
                    Vec3<double>* out) {
  for (std::size_t a = 0; a < kV; ++a) out[a] = p.row(stencil[a]).transpose();
}

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_ELEMENT_SET_H_
