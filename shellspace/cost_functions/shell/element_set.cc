#include "shellspace/cost_functions/shell/element_set.h"

#include <stdexcept>
#include <unordered_map>

namespace shellspace {

ElementSet::ElementSet(const Faces& faces, const Topology& topology,
                       const ShellMaterial& material,
                       const ElementLabels& labels)
    : material_(material),
      num_faces_(static_cast<int>(faces.rows())),
      num_interior_edges_(static_cast<int>(topology.interior_edges.size())) {
  // 1. Membrane: one element per face, of the material's law.
  switch (material.membrane_law) {
#define SHELLSPACE_MEMBRANE_LAW_CASE(type, value, name)        \
  case MembraneLaw::value:                                    \
    AddMembraneGroup(material.membrane<type>(), faces, labels.faces); \
    break;
    SHELLSPACE_MEMBRANE_LAWS(SHELLSPACE_MEMBRANE_LAW_CASE)
#undef SHELLSPACE_MEMBRANE_LAW_CASE
    default:
      throw InputError("material: unknown membrane law " +
                       std::to_string(static_cast<int>(material.membrane_law)));
  }

  // 2. Bending, weight eta, by the material's bending model.
  switch (material.bending_model) {
    case BendingModel::kDiscreteShells: {
      ElementGroup<BendingElement> bending;
      bending.term = "bending (Discrete Shells)";
      bending.stencil_kind = "interior edge";
      bending.part = EnergyPart::kBending;
      bending.weight = material.eta;
      bending.element = material.bending();
      bending.stencils.reserve(topology.interior_edges.size());
      for (const EdgeFlap& flap : topology.interior_edges) {
        bending.stencils.push_back({flap.i, flap.j, flap.k, flap.l});
      }
      bending.labels = labels.interior_edges;
      Add(std::move(bending));
      break;
    }
    case BendingModel::kShapeOperator:
      AddShapeOperatorGroups(faces, topology, material, labels.faces);
      break;
    default:
      throw InputError("material: unknown bending model " +
                       std::to_string(static_cast<int>(material.bending_model)));
  }
  if (!labels.vertices.empty()) {
    const auto vertex_labels =
        std::make_shared<const std::vector<int>>(labels.vertices);
    for (AnyElementGroup& any : groups_) {
      std::visit([&](auto& group) { group.vertex_labels = vertex_labels; },
                 any);
    }
  }
}

namespace {

template <int kInterior>
ElementGroup<ShapeOperatorElement<kInterior>> ShapeOperatorGroup(
    const ShellMaterial& material) {
  ElementGroup<ShapeOperatorElement<kInterior>> group;
  static const std::string kinds[4] = {
      "face with 0 interior edges", "face with 1 interior edge",
      "face with 2 interior edges", "face with 3 interior edges"};
  group.term = "bending (shape operator)";
  group.stencil_kind = kinds[kInterior].c_str();
  group.part = EnergyPart::kBending;
  group.weight = material.eta;
  group.element =
      material.shape_operator<ShapeOperatorElement<kInterior>>();
  return group;
}

}  // namespace

template <class Law>
void ElementSet::AddMembraneGroup(const MembraneElementOf<Law>& element,
                                  const Faces& faces,
                                  const std::vector<int>& face_labels) {
  ElementGroup<MembraneElementOf<Law>> membrane;
  membrane.term = "membrane";
  membrane.stencil_kind = "triangle";
  membrane.part = EnergyPart::kMembrane;
  membrane.weight = 1;
  membrane.element = element;
  membrane.stencils.resize(faces.rows());
  for (int f = 0; f < faces.rows(); ++f) {
    membrane.stencils[f] = {faces(f, 0), faces(f, 1), faces(f, 2)};
  }
  membrane.labels = face_labels;
  Add(std::move(membrane));
}

void ElementSet::AddShapeOperatorGroups(const Faces& faces,
                                        const Topology& topology,
                                        const ShellMaterial& material,
                                        const std::vector<int>& face_labels) {
  // Directed edge (u, w) of a face -> the vertex across it.
  std::unordered_map<long long, int> across;
  const long long n = static_cast<long long>(topology.vertex_faces.size()) + 1;
  for (const EdgeFlap& flap : topology.interior_edges) {
    across[flap.i * n + flap.j] = flap.l;  // face_0 holds i -> j
    across[flap.j * n + flap.i] = flap.k;  // face_1 holds j -> i
  }
  auto g3 = ShapeOperatorGroup<3>(material);
  auto g2 = ShapeOperatorGroup<2>(material);
  auto g1 = ShapeOperatorGroup<1>(material);
  auto g0 = ShapeOperatorGroup<0>(material);
  for (int f = 0; f < faces.rows(); ++f) {
    const int label = face_labels.empty() ? f : face_labels[f];
    const int x[3] = {faces(f, 0), faces(f, 1), faces(f, 2)};
    int opposite[3];  // vertex across the edge opposite x[i], or -1
    int count = 0;
    for (int i = 0; i < 3; ++i) {
      const auto it = across.find(x[(i + 1) % 3] * n + x[(i + 2) % 3]);
      opposite[i] = it == across.end() ? -1 : it->second;
      count += opposite[i] >= 0;
    }
    // Rotation start r: corners r, r+1, r+2 with the interior edges first.
    int r = 0;
    if (count == 1) {
      while (opposite[r] < 0) ++r;
    } else if (count == 2) {
      int z = 0;
      while (opposite[z] >= 0) ++z;
      r = (z + 1) % 3;
    }
    const int a = x[r], b = x[(r + 1) % 3], c = x[(r + 2) % 3];
    const int pa = opposite[r], pb = opposite[(r + 1) % 3];
    switch (count) {
      case 3:
        g3.stencils.push_back({a, b, c, pa, pb, opposite[(r + 2) % 3]});
        g3.labels.push_back(label);
        break;
      case 2:
        g2.stencils.push_back({a, b, c, pa, pb});
        g2.labels.push_back(label);
        break;
      case 1:
        g1.stencils.push_back({a, b, c, pa});
        g1.labels.push_back(label);
        break;
      default:
        g0.stencils.push_back({a, b, c});
        g0.labels.push_back(label);
    }
  }
  Add(std::move(g3));
  Add(std::move(g2));
  Add(std::move(g1));
  Add(std::move(g0));
}

template <class E>
void ElementSet::Add(ElementGroup<E> group) {
  // A term of weight 0 (eta = 0) is not part of W: no elements, no residuals
  // (as eta <= 0 skipped the bending loops before the set existed).
  if (group.weight > 0) {
    group.first_element = num_elements_;
    num_elements_ += group.size();
  } else {
    group.first_element = -1;
  }
  groups_.emplace_back(std::move(group));
}

std::string ElementSet::Describe(int element) const {
  std::string out;
  ForEachGroup([&](const auto& group) {
    const int i = element - group.first_element;
    if (i >= 0 && i < group.size()) out = group.Describe(i);
  });
  if (out.empty()) {
    throw std::out_of_range("ElementSet::Describe: no element " +
                            std::to_string(element));
  }
  return out;
}

void ElementSet::Fail(int element, ElementFailure* failure) const {
  if (failure == nullptr) return;
  failure->element = element;
  failure->description = Describe(element);
}

}  // namespace shellspace
