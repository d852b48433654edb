// Analytic Jacobians of the membrane and bending cost functions against
// ceres::GradientChecker (central differences) on the elements of real mesh
// pairs (every element of the small meshes, a strided subset of the big
// ones), both arguments variable.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <utility>

#include "shellspace/cost_functions/bending_cost_function.h"
#include "shellspace/cost_functions/membrane_cost_function.h"
#include "tests/testing/element_cost_check.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

using testing::MakeCost;
using testing::Mode;

// Coordinates of `vs`, translated so that the element's centroid sits at
// (d, d, d), d its diameter. W is translation invariant, and Ceres' finite
// differences step relative to |x|: this makes the steps relative to the
// element size whatever the mesh's distance from the origin.
std::vector<double> Gather(const Positions& p, const std::vector<int>& vs) {
  Eigen::RowVector3d centroid = Eigen::RowVector3d::Zero();
  for (int v : vs) centroid += p.row(v) / vs.size();
  double diameter = 0;
  for (int a : vs) {
    for (int b : vs)
      diameter = std::max(diameter, (p.row(a) - p.row(b)).norm());
  }
  std::vector<double> out;
  for (int v : vs) {
    for (int c = 0; c < 3; ++c) out.push_back(p(v, c) - centroid(c) + diameter);
  }
  return out;
}

// testing::CheckJacobian of the element's cost function on the vertices
// `vs` of the pair (ref, def), gathered by Gather, both sides variable.
template <class Cost, int kVertices, class Element>
double CheckOnVertices(const Element& element, const Mesh& ref,
                       const Mesh& def, const std::vector<int>& vs,
                       double tolerance) {
  std::vector<double> r = Gather(ref.positions, vs);
  std::vector<double> d = Gather(def.positions, vs);
  std::vector<double*> params;
  auto cost = MakeCost<Cost, kVertices>(element, r, d, Mode::kBothVariable,
                                        &params);
  return testing::CheckJacobian(*cost, params, tolerance);
}

// Every element of real mesh pairs; prints the largest relative error.
TEST(CostFunctionGradientTest, RealMeshes) {
  const std::pair<const char*, const char*> pairs[] = {
      {"simple/square4.ply", "simple/square4_bent.ply"},
      {"sphere/unitSphere1.ply", "sphere/unitSphere1_defX.ply"},
      {"finger/finger0.ply", "finger/finger1.ply"},
      {"cactus/cactus0.ply", "cactus/cactus1.ply"}};
  double worst = 0;
  for (const auto& [ref_name, def_name] : pairs) {
    const Mesh ref = testing::LoadData(ref_name);
    const Mesh def = testing::LoadData(def_name);
    const ShellSpace space = testing::MakeSpace(ref);
    // Every element on the small meshes, a strided subset on the big ones.
    const int stride = ref.num_faces() > 1000 ? 37 : 1;
    for (int f = 0; f < ref.num_faces(); f += stride) {
      const std::vector<int> vs = {ref.faces(f, 0), ref.faces(f, 1),
                                   ref.faces(f, 2)};
      worst = std::max(worst, CheckOnVertices<MembraneCostFunction, 3>(
                                  space.material.membrane(), ref, def, vs,
                                  1e-8));
    }
    const auto& flaps = space.topology.interior_edges;
    for (size_t e = 0; e < flaps.size(); e += stride) {
      const auto& flap = flaps[e];
      const std::vector<int> vs = {flap.i, flap.j, flap.k, flap.l};
      worst = std::max(worst, CheckOnVertices<BendingCostFunction, 4>(
                                  space.material.bending(), ref, def, vs,
                                  1e-8));
    }
  }
  std::cout << "largest relative Jacobian error on real meshes: " << worst
            << "\n";
}

}  // namespace
}  // namespace shellspace
