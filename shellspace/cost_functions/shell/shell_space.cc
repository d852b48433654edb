#include "shellspace/cost_functions/shell/shell_space.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "shellspace/cost_functions/shell/element_set.h"
#include "shellspace/geometry/named_values.h"

namespace shellspace {

void ShellMaterial::Validate() const {
  const auto fail = [](const std::string& what, double value) {
    std::ostringstream message;
    message << "shell material: " << what << ", got " << value;
    throw InputError(message.str());
  };
  switch (membrane_law) {
#define SHELLSPACE_MEMBRANE_LAW_CASE(type, value, name) case MembraneLaw::value:
    SHELLSPACE_MEMBRANE_LAWS(SHELLSPACE_MEMBRANE_LAW_CASE)
#undef SHELLSPACE_MEMBRANE_LAW_CASE
    break;
    default:
      throw InputError("material: unknown membrane law");
  }
  if (!(mu > 0) || !std::isfinite(mu)) {
    fail("the membrane weight mu must be a positive number", mu);
  }
  if (!(lambda > 0) || !std::isfinite(lambda)) {
    fail("the membrane weight lambda must be a positive number", lambda);
  }
  if (!(eta >= 0) || !std::isfinite(eta)) {
    fail("the bending weight eta must be a non-negative number", eta);
  }
  switch (bending_model) {
    case BendingModel::kDiscreteShells:
    case BendingModel::kShapeOperator:
      break;
    default:
      throw InputError("material: unknown bending model");
  }
  if (!(shape_operator_beta >= 0) || !std::isfinite(shape_operator_beta)) {
    fail("the shape-operator weight beta must be a non-negative number",
         shape_operator_beta);
  }
  if (!(shape_operator_alpha + shape_operator_beta / 2 >= 0) ||
      !std::isfinite(shape_operator_alpha)) {
    fail("the shape-operator weight alpha must be a number with alpha + "
         "beta / 2 >= 0",
         shape_operator_alpha);
  }
}

namespace {

constexpr NamedValue<BendingModel> kBendingModelNames[] = {
    {BendingModel::kDiscreteShells, "discrete-shells"},
    {BendingModel::kShapeOperator, "shape-operator"}};

}  // namespace

const char* BendingModelName(BendingModel model) {
  return NameOf(kBendingModelNames, model);
}

bool ParseBendingModel(const std::string& name, BendingModel* model) {
  const std::optional<BendingModel> named =
      ValueNamed(kBendingModelNames, name);
  if (named) *model = *named;
  return named.has_value();
}

ShellSpace::ShellSpace(const Mesh& mesh, const Topology& topo,
                       const ShellMaterial& mat)
    : faces(mesh.faces),
      topology(topo),
      material(mat),
      num_vertices(mesh.num_vertices()),
      elements_(std::make_shared<const ElementSet>(faces, topology, material)) {}

ShellSpace::ShellSpace(const Mesh& mesh, const Topology& topo,
                       const ShellMaterial& mat, const ElementLabels& labels)
    : faces(mesh.faces),
      topology(topo),
      material(mat),
      num_vertices(mesh.num_vertices()),
      elements_(std::make_shared<const ElementSet>(faces, topology, material,
                                                   labels)) {}

const ElementSet& ShellSpace::elements() const {
  if (!elements_) {
    throw std::logic_error("ShellSpace: default-constructed space has no elements");
  }
  const ShellMaterial& m = elements_->material();
  if (m.mu != material.mu || m.lambda != material.lambda ||
      m.eta != material.eta || m.bending_model != material.bending_model ||
      m.membrane_law != material.membrane_law ||
      m.shape_operator_alpha != material.shape_operator_alpha ||
      m.shape_operator_beta != material.shape_operator_beta ||
      elements_->num_faces() != faces.rows() ||
      elements_->num_interior_edges() !=
          static_cast<int>(topology.interior_edges.size())) {
    throw std::logic_error(
        "ShellSpace: material or mesh changed after construction; build a new "
        "ShellSpace");
  }
  return *elements_;
}

}  // namespace shellspace
