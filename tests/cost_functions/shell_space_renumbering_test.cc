// RenumberForLocality on procedural meshes whose vertices and faces are
// numbered at random (as a mesh file may number them): the renumbered space
// gives every energy and gradient of the caller's to round-off (the twin: the
// caller's shapes without the renumbering, measured by the same helper, are
// far off); its faces' vertices lie close together (the twin: the random
// numbering, measured by the same helper, spreads them over the mesh); its
// element descriptions name the caller's faces, interior edges and vertices;
// the renumbering is a function of the connectivity alone.
#include "shellspace/cost_functions/shell/shell_space_renumbering.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/element_set.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

// A finger (closed at its tip, open at its base) and a bent copy of it.
struct Pair {
  Mesh a;
  Positions b;
};
Pair ShuffledFinger(unsigned seed) {
  const Mesh finger = MakeFinger(0.5, 4.0, 16, 20, 4);
  Pair pair;
  pair.a = testing::ShuffledNumbering(finger, seed);
  Mesh bent = finger;
  bent.positions = BendAlongY(finger.positions, 4.0, 1.2);
  pair.b = testing::ShuffledNumbering(bent, seed).positions;
  return pair;
}

// The largest relative difference between W[a, b] and both its gradients in
// the caller's space and W[a', b'] in `renumbered`, its gradients mapped
// back, where a' = map(a), b' = map(b).
template <class Map>
double LargestDifference(const ShellSpace& space,
                         const RenumberedShellSpace& renumbered,
                         const Positions& a, const Positions& b, Map map) {
  const Positions ra = map(a), rb = map(b);
  const double energy = EvaluateDeformationEnergy(space, a, b).total;
  DeformationEnergy renumbered_energy;
  if (!TryEvaluateDeformationEnergy(renumbered.space, ra, rb,
                                    &renumbered_energy)) {
    return HUGE_VAL;  // a degenerate element: nothing like the caller's W
  }
  double difference = std::abs(renumbered_energy.total - energy) / energy;
  for (const ShellSide side : {ShellSide::kReference, ShellSide::kDeformed}) {
    const Eigen::VectorXd g = EnergyGradient(space, a, b, side);
    Eigen::VectorXd rg;
    if (!TryEnergyGradient(renumbered.space, ra, rb, side, &rg)) {
      return HUGE_VAL;
    }
    const double scale = g.cwiseAbs().maxCoeff();
    for (int v = 0; v < space.num_vertices; ++v) {
      const int w = renumbered.new_vertex[v];
      difference = std::max(
          difference,
          (g.segment<3>(3 * v) - rg.segment<3>(3 * w)).cwiseAbs().maxCoeff() /
              scale);
    }
  }
  return difference;
}

TEST(ShellSpaceRenumberingTest, EnergiesAndGradientsAreTheCallersToRoundOff) {
  const Pair pair = ShuffledFinger(3);
  for (const BendingModel model :
       {BendingModel::kDiscreteShells, BendingModel::kShapeOperator}) {
    ShellMaterial material;
    material.bending_model = model;
    const ShellSpace space = testing::MakeSpace(pair.a, material);
    const RenumberedShellSpace renumbered = RenumberForLocality(space);
    const auto to_renumbered = [&](const Positions& x) {
      return renumbered.ToRenumbered(x);
    };
    EXPECT_LT(LargestDifference(space, renumbered, pair.a.positions, pair.b,
                                to_renumbered),
              1e-12)
        << BendingModelName(model);
    // Twin: the caller's shapes as they are, by the same helper.
    const auto unmapped = [](const Positions& x) { return x; };
    EXPECT_GT(LargestDifference(space, renumbered, pair.a.positions, pair.b,
                                unmapped),
              1e-2)
        << BendingModelName(model);
    // ToOriginal inverts ToRenumbered.
    EXPECT_EQ(renumbered.ToOriginal(to_renumbered(pair.b)), pair.b);
  }
}

// The median over faces of (largest - smallest vertex index).
int MedianFaceSpan(const Faces& faces) {
  std::vector<int> span;
  for (int f = 0; f < faces.rows(); ++f) {
    span.push_back(faces.row(f).maxCoeff() - faces.row(f).minCoeff());
  }
  std::nth_element(span.begin(), span.begin() + span.size() / 2, span.end());
  return span[span.size() / 2];
}

// The median over consecutive faces of |difference of smallest vertices|.
int MedianFaceStride(const Faces& faces) {
  std::vector<int> stride;
  for (int f = 1; f < faces.rows(); ++f) {
    stride.push_back(
        std::abs(faces.row(f).minCoeff() - faces.row(f - 1).minCoeff()));
  }
  std::nth_element(stride.begin(), stride.begin() + stride.size() / 2,
                   stride.end());
  return stride[stride.size() / 2];
}

TEST(ShellSpaceRenumberingTest, FacesOfAShuffledSheetBecomeLocal) {
  const int columns = 40, rows = 30;
  const Mesh sheet =
      testing::ShuffledNumbering(MakeEquilateralSheet(columns, rows, 0.1), 5);
  const ShellSpace space = testing::MakeSpace(sheet);
  const RenumberedShellSpace renumbered = RenumberForLocality(space);
  // A band of about one row: a face's vertices lie in two adjacent
  // breadth-first levels, consecutive faces next to each other.
  EXPECT_LE(MedianFaceSpan(renumbered.space.faces), 2 * columns);
  EXPECT_LE(MedianFaceStride(renumbered.space.faces), 1);
  // Twin: the shuffled numbering itself, by the same helpers.
  EXPECT_GT(MedianFaceSpan(space.faces), 5 * columns);
  EXPECT_GT(MedianFaceStride(space.faces), 2 * columns);
  // The faces are the caller's, renamed, in their cyclic order.
  for (int f = 0; f < space.faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(
          renumbered.space.faces(f, c),
          renumbered.new_vertex[space.faces(renumbered.original_face[f], c)]);
    }
  }
  // A function of the connectivity: the same again.
  const RenumberedShellSpace again = RenumberForLocality(space);
  EXPECT_EQ(again.new_vertex, renumbered.new_vertex);
  EXPECT_EQ(again.original_face, renumbered.original_face);
}

// The element descriptions of the renumbered space name the caller's ids:
// the membrane element of each face word for word, each bending element its
// interior edge and the same four vertices (a flap may be oriented from its
// other face).
TEST(ShellSpaceRenumberingTest, DescriptionsNameTheCallersIds) {
  const Pair pair = ShuffledFinger(9);
  const ShellSpace space = testing::MakeSpace(pair.a);
  const RenumberedShellSpace renumbered = RenumberForLocality(space);
  const ElementSet& set = space.elements();
  const ElementSet& renumbered_set = renumbered.space.elements();
  const int faces = static_cast<int>(space.faces.rows());
  ASSERT_EQ(renumbered_set.num_elements(), set.num_elements());
  int differing_faces = 0;
  for (int f = 0; f < faces; ++f) {
    const int original = renumbered.original_face[f];
    differing_faces += original != f;
    ASSERT_EQ(renumbered_set.Describe(f), set.Describe(original));
  }
  EXPECT_GT(differing_faces, faces / 2);  // the order did change
  const auto vertex_set = [](const std::string& description) {
    const std::string list = description.substr(description.find("(vertices"));
    std::set<int> vertices;
    for (size_t i = 9; i < list.size();) {
      size_t used = 0;
      vertices.insert(std::stoi(list.substr(i), &used));
      i += used + 1;
    }
    return vertices;
  };
  const int edges = static_cast<int>(space.topology.interior_edges.size());
  for (int e = 0; e < edges; ++e) {
    const EdgeFlap& flap = renumbered.space.topology.interior_edges[e];
    const std::string text = renumbered_set.Describe(faces + e);
    const int label = std::stoi(text.substr(text.find("interior edge ") + 14));
    const EdgeFlap& original = space.topology.interior_edges[label];
    EXPECT_EQ((std::set<int>{renumbered.original_vertex[flap.i],
                             renumbered.original_vertex[flap.j]}),
              (std::set<int>{original.i, original.j}))
        << text;
    ASSERT_EQ(vertex_set(text), vertex_set(set.Describe(faces + label)))
        << text;
  }
}

}  // namespace
}  // namespace shellspace
