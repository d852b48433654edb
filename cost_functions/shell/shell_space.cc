#include "shellspace/cost_functions/shell/shell_space.h"

#include <cmath>
#include <stdexcept>

#include "shellspace/cost_functions/shell/element_set.h"

namespace shellspace {

void ShellMaterial::Validate() const {
  if (!(mu > 0) || !std::isfinite(mu)) {
    throw InputError("--mu must be a positive number");
  }
  if (!(lambda > 0) || !std::isfinite(lambda)) {
    throw InputError("--lambda must be a positive number");
  }
  if (!(eta >= 0) || !std::isfinite(eta)) {
    throw InputError("--eta must be a non-negative number");
  }
  switch (bending_model) {
    case BendingModel::kDiscreteShells:
      break;
    default:
      throw InputError("material: unknown bending model");
  }
}

ShellSpace::ShellSpace(const Mesh& mesh, const Topology& topo,
                       const ShellMaterial& mat)
    : faces(mesh.faces),
      topology(topo),
      material(mat),
      num_vertices(mesh.num_vertices()),
      elements_(std::make_shared<const ElementSet>(faces, topology, material)) {}

const ElementSet& ShellSpace::elements() const {
  if (!elements_) {
    throw std::logic_error("ShellSpace: default-constructed space has no elements");
  }
  const ShellMaterial& m = elements_->material();
  if (m.mu != material.mu || m.lambda != material.lambda ||
      m.eta != material.eta || m.bending_model != material.bending_model ||
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
