// Elements sampled from real mesh pairs, shared by the tests of the element
// second derivatives (tests/cost_functions/element_hessian*_test.cc): an
// element's coordinates on both sides, ElementSecondDerivatives::Compute
// at them, every sampled element of both terms of W on a pair, and the
// parameterised fixture ElementHessianTest with its mesh pairs.
#ifndef SHELLSPACE_TESTS_TESTING_ELEMENT_SAMPLES_H_
#define SHELLSPACE_TESTS_TESTING_ELEMENT_SAMPLES_H_

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/cost_functions/shell/element_set.h"
#include "tests/testing/test_support.h"

namespace shellspace::testing {

// A reference and a deformed mesh of ../shared/data of one connectivity.
struct MeshPairNames {
  const char* reference;
  const char* deformed;
};

// The pairs of the RealMeshes instantiations of ElementHessianTest: the
// cactus, the finger and the faces.
std::vector<MeshPairNames> ElementHessianMeshPairs();

class ElementHessianTest : public ::testing::TestWithParam<MeshPairNames> {};

template <int kV>
using Derivatives = ElementSecondDerivatives<kV>;

inline constexpr ShellSide kSides[] = {ShellSide::kReference,
                                       ShellSide::kDeformed};

// One element of a real mesh pair: its coordinates on both sides (vertex-
// major, 3 kV each).
template <int kV>
struct ElementSample {
  Eigen::Matrix<double, 3 * kV, 1> ref, def;
  double edge = 0;  // the longest reference edge of the stencil (length scale)

  // This sample with the coordinates of the `active` side replaced by x.
  ElementSample With(ShellSide active, const Eigen::VectorXd& x) const {
    ElementSample moved = *this;
    (active == ShellSide::kReference ? moved.ref : moved.def) = x;
    return moved;
  }

  // d->Compute of `element` at this sample (false if it is degenerate).
  template <class Element>
  bool Compute(const Element& element, ShellSide active, double weight,
               ElementSecondDerivatives<kV>* d,
               typename ElementSecondDerivatives<kV>::Rows rows =
                   ElementSecondDerivatives<kV>::Rows::kBoth) const {
    return d->Compute(element, ref.data(), def.data(), active, weight, rows);
  }
};

// Every stride-th element of `group`, up to `count` of them.
template <class Group>
std::vector<ElementSample<Group::kVertices>> SampleElements(
    const Group& group, const Positions& ref, const Positions& def,
    int count) {
  constexpr int kV = Group::kVertices;
  std::vector<ElementSample<kV>> out;
  const int stride = std::max(1, group.size() / count);
  for (int e = 0; e < group.size() && static_cast<int>(out.size()) < count;
       e += stride) {
    ElementSample<kV> s;
    GatherCoordinates(ref, group.stencils[e], s.ref.data());
    GatherCoordinates(def, group.stencils[e], s.def.data());
    for (int a = 0; a < kV; ++a) {
      for (int b = 0; b < a; ++b) {
        s.edge = std::max(s.edge, (s.ref.template segment<3>(3 * a) -
                                   s.ref.template segment<3>(3 * b))
                                      .norm());
      }
    }
    out.push_back(s);
  }
  return out;
}

// Calls check(element, sample) for sampled elements of every term of W on
// the pair (each mesh pair, membrane and bending, eta of the default
// material), and of the membrane term of every other registered membrane law
// (membrane_law.h).
template <class Check>
void ForSampledElements(const MeshPairNames& pair, int count, Check&& check) {
  const Mesh ref = LoadData(pair.reference);
  const Mesh def = LoadData(pair.deformed);
  const ShellSpace space = MakeSpace(ref);
  int groups = 0;
  const auto sample = [&](const auto& group) {
    ++groups;
    for (const auto& s :
         SampleElements(group, ref.positions, def.positions, count)) {
      check(group.element, s);
    }
  };
  space.elements().ForEachGroup(sample);
  ASSERT_EQ(groups, 2);  // membrane and bending
  int laws = 0;
#define SHELLSPACE_OTHER_LAW(type, value, name)                        \
  if (MembraneLaw::value != space.material.membrane_law) {             \
    ShellMaterial material = space.material;                          \
    material.membrane_law = MembraneLaw::value;                       \
    MakeSpace(ref, material).elements().ForEachGroup([&](const auto& g) { \
      if (g.part == EnergyPart::kMembrane) sample(g);                 \
    });                                                               \
    ++laws;                                                           \
  }
  SHELLSPACE_MEMBRANE_LAWS(SHELLSPACE_OTHER_LAW)
#undef SHELLSPACE_OTHER_LAW
  ASSERT_EQ(groups, 2 + laws);
  ASSERT_GE(laws, 1);  // the St. Venant-Kirchhoff law
}

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_ELEMENT_SAMPLES_H_
