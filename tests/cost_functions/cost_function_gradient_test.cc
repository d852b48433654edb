// Analytic Jacobians of the membrane and bending cost functions against
// ceres::GradientChecker (central differences), on random and on real meshes,
// for every combination of variable reference / deformed arguments.
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <random>

#include "shellspace/cost_functions/bending_cost_function.h"
#include "shellspace/cost_functions/membrane_cost_function.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

enum class Mode { kBothVariable, kReferenceFixed, kDeformedFixed };

// Builds the cost function of one element and the parameter pointers.
template <class Cost, int kVertices, class Element>
std::unique_ptr<ceres::CostFunction> MakeCost(const Element& element,
                                              std::vector<double>& ref,
                                              std::vector<double>& def,
                                              Mode mode,
                                              std::vector<double*>* params) {
  params->clear();
  const double* fixed_ref =
      mode == Mode::kReferenceFixed ? ref.data() : nullptr;
  const double* fixed_def = mode == Mode::kDeformedFixed ? def.data() : nullptr;
  for (int v = 0; v < kVertices && !fixed_ref; ++v) {
    params->push_back(ref.data() + 3 * v);
  }
  for (int v = 0; v < kVertices && !fixed_def; ++v) {
    params->push_back(def.data() + 3 * v);
  }
  return std::make_unique<Cost>(element, fixed_ref, fixed_def, 1.7);
}

// The normwise relative Jacobian error of the element
// (testing::CostFunctionJacobianError), EXPECTed below `tolerance`.
double Check(const ceres::CostFunction& cost,
             const std::vector<double*>& params, double tolerance) {
  const double relative = testing::CostFunctionJacobianError(cost, params);
  EXPECT_LT(relative, tolerance);
  return relative;
}

// Check of the element's cost function at (ref, def) with every side
// variable, the reference fixed and the deformed fixed.
template <class Cost, int kVertices, class Element>
void CheckEveryMode(const Element& element, std::vector<double>& ref,
                    std::vector<double>& def, double tolerance) {
  for (Mode mode :
       {Mode::kBothVariable, Mode::kReferenceFixed, Mode::kDeformedFixed}) {
    std::vector<double*> params;
    auto cost = MakeCost<Cost, kVertices>(element, ref, def, mode, &params);
    Check(*cost, params, tolerance);
  }
}

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

// Check of the element's cost function on the vertices `vs` of the pair
// (ref, def), gathered by Gather, both sides variable.
template <class Cost, int kVertices, class Element>
double CheckOnVertices(const Element& element, const Mesh& ref,
                       const Mesh& def, const std::vector<int>& vs,
                       double tolerance) {
  std::vector<double> r = Gather(ref.positions, vs);
  std::vector<double> d = Gather(def.positions, vs);
  std::vector<double*> params;
  auto cost = MakeCost<Cost, kVertices>(element, r, d, Mode::kBothVariable,
                                        &params);
  return Check(*cost, params, tolerance);
}

TEST(CostFunctionGradientTest, RandomTriangles) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  MembraneElement membrane;
  membrane.law.mu = 1.3;
  membrane.law.lambda = 0.7;
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> ref(9), def(9);
    for (double& x : ref) x = u(rng);
    for (int i = 0; i < 9; ++i) def[i] = ref[i] + 0.3 * u(rng);
    // Include near-rest configurations (series branch of psi).
    if (trial % 5 == 0) {
      for (int i = 0; i < 9; ++i) def[i] = ref[i] + 1e-3 * u(rng);
    }
    CheckEveryMode<MembraneCostFunction, 3>(membrane, ref, def, 1e-8);
  }
}

TEST(CostFunctionGradientTest, RandomEdgeFlaps) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  BendingElement bending;
  bending.eta = 0.3;
  for (int trial = 0; trial < 50; ++trial) {
    // A reasonable flap: edge along x, opposite vertices on either side.
    std::vector<double> ref = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0};
    std::vector<double> def(12);
    for (double& x : ref) x += 0.3 * u(rng);
    for (int i = 0; i < 12; ++i) def[i] = ref[i] + 0.4 * u(rng);
    CheckEveryMode<BendingCostFunction, 4>(bending, ref, def, 1e-8);
  }
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

// The negative twin of the checks above: a Jacobian wrong in one entry,
// through the same helper and tolerance, must fail -- for both elements and
// every argument mode.
TEST(CostFunctionGradientTest, CheckerDetectsWrongJacobian) {
  std::vector<double> ref = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0};
  std::vector<double> def = {0, 0, 0.1, 1.1, 0, 0, 0.5, 1, 0.3, 0.4, -1, 0};
  for (int which = 0; which < 2; ++which) {
    for (Mode mode :
         {Mode::kBothVariable, Mode::kReferenceFixed, Mode::kDeformedFixed}) {
      std::vector<double*> params;
      std::unique_ptr<ceres::CostFunction> inner =
          which == 0 ? MakeCost<MembraneCostFunction, 3>(MembraneElement(), ref,
                                                         def, mode, &params)
                     : MakeCost<BendingCostFunction, 4>(BendingElement(), ref,
                                                        def, mode, &params);
      // The correct one passes the helper ...
      EXPECT_LT(testing::CostFunctionJacobianError(*inner, params), 1e-8);
      // ... and one entry off by 1e-4 of the Jacobian's scale does not.
      testing::CostFunctionWithWrongJacobian wrong(std::move(inner), 1, 2,
                                                   1e-4);
      EXPECT_GT(testing::CostFunctionJacobianError(wrong, params), 1e-8)
          << which << int(mode);
    }
  }
}

}  // namespace
}  // namespace shellspace
