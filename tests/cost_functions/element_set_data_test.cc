// The element set of W (cost_functions/shell/element_set.h): what it
// enumerates on a real mesh and in which order; every evaluator that iterates
// it against the values the code gave before the set existed; and the
// non-throwing status of degenerate elements.
#include "shellspace/cost_functions/shell/element_set.h"

#include <ceres/problem.h>
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <utility>

#include "shellspace/cost_functions/deformation_energy_residuals.h"
#include "shellspace/cost_functions/gradient_field_residual.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/path_hessian.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

// The interior edges of a mesh counted from its faces alone (an undirected
// edge shared by two faces), independently of Topology.
int CountInteriorEdges(const Faces& faces) {
  std::map<std::pair<int, int>, int> count;
  for (int f = 0; f < faces.rows(); ++f) {
    for (int a = 0; a < 3; ++a) {
      const int u = faces(f, a), v = faces(f, (a + 1) % 3);
      ++count[{std::min(u, v), std::max(u, v)}];
    }
  }
  int interior = 0;
  for (const auto& [edge, n] : count) interior += n == 2;
  return interior;
}

struct GroupSummary {
  std::string term;
  int vertices, size, first_element;
  double weight;
};

std::vector<GroupSummary> Groups(const ElementSet& set, bool zero_weight) {
  std::vector<GroupSummary> out;
  auto add = [&](const auto& group) {
    out.push_back({group.term, group.kVertices, group.size(),
                   group.first_element, group.weight});
  };
  if (zero_weight) {
    set.ForEachGroupWithZeroWeight(add);
  } else {
    set.ForEachGroup(add);
  }
  return out;
}

TEST(ElementSetTest, FacesThenInteriorEdgesOnTheFinger) {
  const Mesh mesh = testing::LoadData("finger/finger0.ply");
  ASSERT_EQ(mesh.num_faces(), 4088);  // data/README.md
  const int interior = CountInteriorEdges(mesh.faces);
  const ShellSpace space = testing::MakeSpace(mesh);  // eta = 0.01
  const ElementSet& set = space.elements();
  EXPECT_EQ(set.num_elements(), 4088 + interior);
  const std::vector<GroupSummary> groups = Groups(set, false);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].term, "membrane");
  EXPECT_EQ(groups[0].vertices, 3);
  EXPECT_EQ(groups[0].size, 4088);
  EXPECT_EQ(groups[0].first_element, 0);
  EXPECT_EQ(groups[0].weight, 1.0);
  EXPECT_EQ(groups[1].term, "bending (Discrete Shells)");
  EXPECT_EQ(groups[1].vertices, 4);
  EXPECT_EQ(groups[1].size, interior);
  EXPECT_EQ(groups[1].first_element, 4088);
  EXPECT_EQ(groups[1].weight, 0.01);
  // The fixed order: stencil f of the membrane is face f; stencil e of the
  // bending term is the flap (i, j, k, l) of interior edge e.
  int checked = 0;
  set.ForEachGroup([&](const auto& group) {
    for (int e = 0; e < group.size(); ++e) {
      const auto& s = group.stencils[e];
      if constexpr (std::decay_t<decltype(group)>::kVertices == 3) {
        EXPECT_EQ(s[0], mesh.faces(e, 0));
        EXPECT_EQ(s[1], mesh.faces(e, 1));
        EXPECT_EQ(s[2], mesh.faces(e, 2));
      } else {
        const EdgeFlap& flap = space.topology.interior_edges[e];
        EXPECT_EQ(s[0], flap.i);
        EXPECT_EQ(s[1], flap.j);
        EXPECT_EQ(s[2], flap.k);
        EXPECT_EQ(s[3], flap.l);
      }
      ++checked;
    }
  });
  EXPECT_EQ(checked, set.num_elements());
  EXPECT_EQ(set.Describe(17), "membrane element of triangle 17 (vertices " +
                                  std::to_string(mesh.faces(17, 0)) + ", " +
                                  std::to_string(mesh.faces(17, 1)) + ", " +
                                  std::to_string(mesh.faces(17, 2)) + ")");
  EXPECT_EQ(set.Describe(4088 + 5).rfind("bending (Discrete Shells) element "
                                         "of interior edge 5 (vertices",
                                         0),
            0u);
}

TEST(ElementSetTest, ZeroEtaHasNoBendingElements) {
  const Mesh mesh = testing::LoadData("finger/finger0.ply");
  ShellMaterial material;
  material.eta = 0;
  const ShellSpace space = testing::MakeSpace(mesh, material);
  EXPECT_EQ(space.elements().num_elements(), 4088);
  EXPECT_EQ(Groups(space.elements(), false).size(), 1u);
  const std::vector<GroupSummary> all = Groups(space.elements(), true);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].first_element, -1);
  // No bending residual blocks either.
  Positions x = mesh.positions;
  ceres::Problem problem;
  AddDeformationEnergy(space, ShellArgument::Fixed(mesh.positions),
                       ShellArgument::Variable(&x), 1.0, &problem);
  EXPECT_EQ(problem.NumResidualBlocks(), 4088);
  EXPECT_EQ(problem.NumResiduals(), 4 * 4088);
}

TEST(ElementSetTest, ChangedMaterialAfterConstructionIsCaught) {
  const Mesh mesh = testing::LoadData("simple/square4.ply");
  ShellSpace space = testing::MakeSpace(mesh);
  space.material.eta = 0.5;
  EXPECT_THROW(space.elements(), std::logic_error);
  EXPECT_THROW(ShellSpace().elements(), std::logic_error);
}

// Largest normwise relative error max |J - N| / max |N| of an element's
// analytic Jacobians (both sides) against central differences of its
// residuals, at the coordinates ref, def (3 kNumVertices each), step h times
// the element's diameter.
template <class E>
double JacobianError(const E& element, const double* ref, const double* def) {
  constexpr int kV = E::kNumVertices, m = E::kNumResiduals;
  Vec3<double> x_ref[kV], x_def[kV];
  for (int a = 0; a < kV; ++a) {
    x_ref[a] = Vec3<double>(ref + 3 * a);
    x_def[a] = Vec3<double>(def + 3 * a);
  }
  double diameter = 0;
  for (int a = 0; a < kV; ++a) {
    for (int b = 0; b < kV; ++b)
      diameter = std::max(diameter, (x_ref[a] - x_ref[b]).norm());
  }
  const double h = 1e-6 * diameter;
  using Jacobian = typename E::template Jacobian<double>;
  Jacobian jac[2];
  Jacobian* none = nullptr;
  double r[m];
  EXPECT_TRUE(element.Evaluate(x_ref, x_def, r, &jac[0], &jac[1]));
  double error = 0, scale = 0;
  for (int side = 0; side < 2; ++side) {
    Vec3<double>* x = side == 0 ? x_ref : x_def;
    for (int col = 0; col < 3 * kV; ++col) {
      double plus[m] = {}, minus[m] = {};
      const double saved = x[col / 3](col % 3);
      x[col / 3](col % 3) = saved + h;
      EXPECT_TRUE(element.Evaluate(x_ref, x_def, plus, none, none));
      x[col / 3](col % 3) = saved - h;
      EXPECT_TRUE(element.Evaluate(x_ref, x_def, minus, none, none));
      x[col / 3](col % 3) = saved;
      for (int i = 0; i < m; ++i) {
        const double numeric = (plus[i] - minus[i]) / (2 * h);
        error = std::max(error, std::abs(jac[side](i, col) - numeric));
        scale = std::max(scale, std::abs(numeric));
      }
    }
  }
  return error / scale;
}

// An element type with one wrong Jacobian entry (d r_0 / d X_0,x of the
// deformed side off by 1e-3 of the Jacobian's scale): the negative twin.
template <class E>
struct WrongJacobianElement : E {
  template <typename T>
  bool Evaluate(const Vec3<T>* ref, const Vec3<T>* def, T* residuals,
                typename E::template Jacobian<T>* jac_ref,
                typename E::template Jacobian<T>* jac_def) const {
    if (!E::Evaluate(ref, def, residuals, jac_ref, jac_def)) return false;
    if (jac_def) {
      (*jac_def)(0, 0) += 1e-3 * jac_def->cwiseAbs().maxCoeff();
    }
    return true;
  }
};

// Every element type of the set, through the interface the evaluators use
// (Element::Evaluate on a group's stencils), on the finger: the Jacobians
// match central differences; the same check fails for a wrong Jacobian.
TEST(ElementSetTest, EveryGroupsJacobiansMatchCentralDifferences) {
  const auto [ref, def, space] =
      testing::LoadPair("finger/finger0.ply", "finger/finger1.ply");
  int groups = 0;
  space.elements().ForEachGroup([&](const auto& group) {
    using Group = std::decay_t<decltype(group)>;
    constexpr int kV = Group::kVertices;
    WrongJacobianElement<typename Group::Element> wrong;
    static_cast<typename Group::Element&>(wrong) = group.element;
    double worst = 0, best_wrong = HUGE_VAL;
    for (int e = 0; e < group.size(); e += 97) {
      double r[3 * kV], d[3 * kV];
      GatherCoordinates(ref.positions, group.stencils[e], r);
      GatherCoordinates(def.positions, group.stencils[e], d);
      worst = std::max(worst, JacobianError(group.element, r, d));
      best_wrong = std::min(best_wrong, JacobianError(wrong, r, d));
    }
    EXPECT_LT(worst, 1e-6) << group.term;
    EXPECT_GT(best_wrong, 1e-5) << group.term;
    std::cout << group.term << ": largest relative Jacobian error " << worst
              << ", smallest of the wrong twin " << best_wrong << "\n";
    ++groups;
  });
  EXPECT_EQ(groups, 2);
}

double AbsSum(const SparseMatrix& m) {
  double s = 0;
  for (int k = 0; k < m.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(m, k); it; ++it)
      s += std::abs(it.value());
  }
  return s;
}

// Reference values: printed (%.17g) by the code of commit 578fa76, before the
// element set, with the same inputs and the same reductions as below (a
// throw-away program built against that commit). The evaluators now iterate
// the element set in the same order as the old hand-written loops, so the
// results were bit-identical (full vectors and matrices compared byte for
// byte); the tolerance 1e-14 relative only allows for a different compiler.
constexpr double kTolerance = 1e-14;
#define EXPECT_REL(actual, expected) \
  EXPECT_NEAR((actual) / (expected), 1.0, kTolerance) << #actual

TEST(ElementSetRegressionTest, FingerMatchesThePreElementSetCode) {
  const Mesh ref = testing::LoadData("finger/finger0.ply");
  const Mesh def = testing::LoadData("finger/finger1.ply");
  const ShellSpace space =
      testing::MakeSpace(ref);  // mu = lambda = 1, eta 0.01
  const Positions& R = ref.positions;
  const Positions& D = def.positions;

  const DeformationEnergy e = EvaluateDeformationEnergy(space, R, D);
  EXPECT_REL(e.membrane, 0.044294266765160344);
  EXPECT_REL(e.bending, 143.1154482358275);
  EXPECT_REL(e.total, 1.4754487491234354);
  EXPECT_REL(EnergyGradient(space, R, D, ShellSide::kReference).norm(),
             58.621978348841587);
  EXPECT_REL(EnergyGradient(space, R, D, ShellSide::kDeformed).norm(),
             81.651287442837315);
  Eigen::VectorXd p(3 * space.num_vertices);
  for (int i = 0; i < p.size(); ++i) p(i) = std::sin(1.0 + i);
  EXPECT_REL(EnergyGradientDerivative(space, R, D, ShellSide::kDeformed,
                                      ShellSide::kDeformed, p)
                 .norm(),
             92307.785053689644);
  EXPECT_REL(EnergyGradientDerivative(space, R, D, ShellSide::kReference,
                                      ShellSide::kDeformed, p)
                 .norm(),
             88732.078572095546);
  const auto columns = EnergyHessianColumns(space, R, D, ShellSide::kDeformed);
  EXPECT_REL(AbsSum(columns.first), 18526675.114080075);
  EXPECT_REL(AbsSum(columns.second), 19125671.113675199);
  EXPECT_EQ(columns.second.nonZeros(), 237546);
  EXPECT_REL(AbsSum(EnergyHessian(space, R, D, ShellSide::kReference,
                                  ShellSide::kReference)),
             18377920.822175451);

  // The Ceres adapter: 1/2 |r|^2 of 1.7 W with both arguments variable.
  {
    Positions r = R, d = D;
    ceres::Problem problem;
    AddDeformationEnergy(space, ShellArgument::Variable(&r),
                         ShellArgument::Variable(&d), 1.7, &problem);
    double cost = 0;
    problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr,
                     nullptr);
    EXPECT_REL(cost, 2.5082628735098509);
    EXPECT_EQ(problem.NumResiduals(), 22484);
  }

  // The EXP residual cache, both unknown sides, with Jacobians.
  const std::pair<ShellSide, double> cache_cases[] = {
      {ShellSide::kReference, 2297.5262392646155},
      {ShellSide::kDeformed, 2007.7275013673861}};
  for (const auto& [unknown, expected] : cache_cases) {
    const Positions& fixed = unknown == ShellSide::kReference ? D : R;
    const Positions& var = unknown == ShellSide::kReference ? R : D;
    GradientFieldCache cache(space, fixed, unknown, &var);
    cache.PrepareForEvaluation(true, true);
    ASSERT_TRUE(cache.ok());
    EXPECT_EQ(static_cast<int>(cache.elements().size()),
              space.elements().num_elements());
    double sum = 0;
    for (const auto& element : cache.elements()) {
      for (int i = 0; i < 3 * element.count; ++i) {
        sum += std::abs(element.gradient[i]);
      }
    }
    EXPECT_REL(sum, expected);
  }

  // The path energy and the path Hessian (K = 8, perturbed linear path,
  // rigid gauge), the elastic-mean sum and a mixed block.
  const int K = 8;
  ShellPath path = LinearPath(R, D, K);
  for (int k = 1; k < K; ++k) {
    for (int i = 0; i < path[k].size(); ++i) {
      path[k].data()[i] += 1e-3 * std::cos(3.0 * i + k);
    }
  }
  EXPECT_REL(PathEnergy(space, path), 70.371732475739847);
  EXPECT_REL(*TryPathEnergy(space, path), 70.371732475739847);
  const PathHessianAssembler assembler(space);
  const std::vector<SparseMatrix> bases(K - 1, RigidGaugeBasis(R));
  const SparseMatrix h = assembler.Assemble(path, bases, 2);
  EXPECT_REL(AbsSum(h), 2477863029.2764421);
  EXPECT_EQ(h.nonZeros(), 2274178);
  EXPECT_REL(AbsSum(assembler.AssembleDeformedSum({R, path[3], path[5]}, D,
                                                  bases[0], 2)),
             33327694.388805952);
  EXPECT_REL(AbsSum(assembler.AssembleMixed(R, D, ShellSide::kReference,
                                            bases[0], bases[1])),
             18472679.000822511);
}

TEST(ElementSetRegressionTest, PlateWithoutBendingMatchesThePreElementSetCode) {
  ShellMaterial without_bending;
  without_bending.eta = 0;
  const auto [ref, def, space] = testing::LoadPair(
      "plate/plate121.ply", "plate/plate121_rolledA.ply", without_bending);
  const DeformationEnergy e =
      EvaluateDeformationEnergy(space, ref.positions, def.positions);
  EXPECT_REL(e.membrane, 0.0004041208844484317);
  EXPECT_REL(e.bending, 106.59166386221459);  // reported, not in W
  EXPECT_EQ(e.total, e.membrane);
  EXPECT_REL(
      EnergyGradient(space, ref.positions, def.positions, ShellSide::kDeformed)
          .norm(),
      0.036283837963598631);
  EXPECT_REL(AbsSum(EnergyHessian(space, ref.positions, def.positions,
                                  ShellSide::kDeformed, ShellSide::kDeformed)),
             6158.3162548806158);
}

// A shell with triangle `face` collapsed onto its first vertex.
Positions CollapseFace(const Mesh& mesh, int face) {
  Positions p = mesh.positions;
  p.row(mesh.faces(face, 1)) = p.row(mesh.faces(face, 0));
  p.row(mesh.faces(face, 2)) = p.row(mesh.faces(face, 0));
  return p;
}

TEST(ElementSetStatusTest, DegenerateElementIsAStatusNotAnException) {
  const Mesh mesh = testing::LoadData("plate/plate121.ply");
  const ShellSpace space = testing::MakeSpace(mesh);
  const int face = 37;
  const Positions bad = CollapseFace(mesh, face);
  // Collapsing face 37 also collapses its neighbours across its edges (two of
  // their vertices coincide). The status names the first degenerate element
  // of the enumeration: the lowest-numbered face with zero area.
  int first = -1;
  for (int f = 0; f < mesh.num_faces() && first < 0; ++f) {
    const Eigen::Vector3d a = bad.row(mesh.faces(f, 0)).transpose();
    const Eigen::Vector3d b = bad.row(mesh.faces(f, 1)).transpose();
    const Eigen::Vector3d c = bad.row(mesh.faces(f, 2)).transpose();
    if ((b - a).cross(c - a).norm() == 0) first = f;
  }
  ASSERT_GE(first, 0);
  ASSERT_LE(first, face);
  const std::string named = "triangle " + std::to_string(first) + " ";

  DeformationEnergy energy;
  ElementFailure failure;
  EXPECT_FALSE(TryEvaluateDeformationEnergy(space, mesh.positions, bad, &energy,
                                            &failure));
  EXPECT_EQ(failure.element, first);
  EXPECT_NE(failure.description.find(named), std::string::npos)
      << failure.description;
  try {
    EvaluateDeformationEnergy(space, mesh.positions, bad);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(named), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("degenerate"), std::string::npos);
  }

  Eigen::VectorXd g;
  ElementFailure gradient_failure;
  EXPECT_FALSE(TryEnergyGradient(space, mesh.positions, bad,
                                 ShellSide::kDeformed, &g, &gradient_failure));
  EXPECT_EQ(gradient_failure.element, first);
  EXPECT_THROW(EnergyGradient(space, mesh.positions, bad, ShellSide::kDeformed),
               InputError);
  std::pair<SparseMatrix, SparseMatrix> blocks;
  EXPECT_FALSE(TryEnergyHessianColumns(space, mesh.positions, bad,
                                       ShellSide::kDeformed, &blocks));
  Eigen::VectorXd d;
  EXPECT_FALSE(TryEnergyGradientDerivative(
      space, mesh.positions, bad, ShellSide::kDeformed, ShellSide::kDeformed,
      Eigen::VectorXd::Ones(3 * mesh.num_vertices()), &d));

  ShellPath path = LinearPath(mesh.positions, mesh.positions, 3);
  path[2] = bad;
  ElementFailure path_failure;
  EXPECT_FALSE(TryPathEnergy(space, path, nullptr, &path_failure).has_value());
  EXPECT_EQ(path_failure.description.rfind("W[s_1, s_2]: ", 0), 0u)
      << path_failure.description;
  EXPECT_THROW(PathEnergy(space, path), InputError);
  SparseMatrix h;
  const std::vector<SparseMatrix> bases(2, RigidGaugeBasis(mesh.positions));
  EXPECT_FALSE(PathHessianAssembler(space).TryAssemble(path, bases, 2, &h));

  // The same calls on the valid shell succeed and agree with the throwing
  // versions.
  ASSERT_TRUE(TryEvaluateDeformationEnergy(space, mesh.positions,
                                           mesh.positions, &energy));
  EXPECT_EQ(energy.total, 0.0);
  ASSERT_TRUE(TryEnergyGradient(space, mesh.positions, path[1],
                                ShellSide::kReference, &g));
  EXPECT_EQ(
      g, EnergyGradient(space, mesh.positions, path[1], ShellSide::kReference));
}

}  // namespace
}  // namespace shellspace
