// The shape-operator bending model (docs/math.md, "Bending energy: two models";
// cost_functions/shell/shape_operator_element.h): residuals against an
// independent implementation of the formula (the intrinsic S_T conormal form
// with atan2 dihedral angles), rest and rigid invariance, Jacobians (ceres
// GradientChecker) and Hessians (central differences) each with a negative
// twin, and the convergence of the curvature functional on icospheres and of
// the flat-sheet-to-cylinder energy (meshes generated here).
#include <gtest/gtest.h>

#include <ceres/problem.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <type_traits>
#include <utility>
#include <vector>

#include "shellspace/cost_functions/deformation_energy_residuals.h"
#include "shellspace/cost_functions/shape_operator_bending_cost_function.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/element_hessian.h"
#include "shellspace/cost_functions/shell/element_set.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/topology.h"
#include "tests/testing/derivative_check.h"
#include "tests/testing/test_support.h"

namespace shellspace {
namespace {

constexpr double kPi = 3.14159265358979323846;
using Vec3d = Eigen::Vector3d;

// ---------------------------------------------------------------------------
// Independent implementation of the spec's formula: for each face, the
// intrinsic shape operator S_T = sum_i (l_i sin(theta_i / 2) / a_T) t_i t_i^T
// (t_i the outward in-plane conormal of edge i, theta_i = atan2(N_i . t_i,
// N . N_i) the signed dihedral angle), H_ab = E_a^T S_T E_b, and
// e_T = abar (alpha (tr M)^2 + beta tr(M^2)), M = Gbar^-1 (H - Hbar) with an
// explicit 2 x 2 inverse. Neighbours are found from the face list alone.
class DirectShapeOperator {
 public:
  explicit DirectShapeOperator(const Faces& faces) : faces_(faces) {
    for (int f = 0; f < faces.rows(); ++f) {
      for (int a = 0; a < 3; ++a) {
        half_edge_[{faces(f, a), faces(f, (a + 1) % 3)}] = faces(f, (a + 2) % 3);
      }
    }
  }

  // H_T of face f of `shape` in the basis E_1 = X_1 - X_0, E_2 = X_2 - X_0.
  Eigen::Matrix2d SecondForm(const Positions& shape, int f) const {
    Vec3d x[3];
    for (int a = 0; a < 3; ++a) x[a] = shape.row(faces_(f, a)).transpose();
    const Vec3d m = (x[1] - x[0]).cross(x[2] - x[0]);
    const double area = 0.5 * m.norm();
    const Vec3d n = m.normalized();
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 3; ++i) {
      const int a = faces_(f, (i + 1) % 3), b = faces_(f, (i + 2) % 3);
      // The neighbour holds the edge as b -> a.
      const auto it = half_edge_.find({b, a});
      if (it == half_edge_.end()) continue;
      const Vec3d xa = shape.row(a).transpose(), xb = shape.row(b).transpose();
      const Vec3d xp = shape.row(it->second).transpose();
      const Vec3d edge = (xb - xa).normalized();
      Vec3d t = 0.5 * (xa + xb) - x[i];
      t = (t - t.dot(edge) * edge).normalized();
      const Vec3d n_i = (xa - xb).cross(xp - xb).normalized();
      const double theta = std::atan2(n_i.dot(t), n.dot(n_i));
      s += ((xb - xa).norm() * std::sin(theta / 2) / area) * t * t.transpose();
    }
    const Vec3d e[2] = {x[1] - x[0], x[2] - x[0]};
    Eigen::Matrix2d h;
    for (int p = 0; p < 2; ++p) {
      for (int q = 0; q < 2; ++q) h(p, q) = e[p].dot(s * e[q]);
    }
    return h;
  }
  Eigen::Matrix2d FirstForm(const Positions& shape, int f) const {
    const Vec3d x0 = shape.row(faces_(f, 0)).transpose();
    const Vec3d e[2] = {shape.row(faces_(f, 1)).transpose() - x0,
                        shape.row(faces_(f, 2)).transpose() - x0};
    Eigen::Matrix2d g;
    for (int p = 0; p < 2; ++p) {
      for (int q = 0; q < 2; ++q) g(p, q) = e[p].dot(e[q]);
    }
    return g;
  }
  double Area(const Positions& shape, int f) const {
    return 0.5 * std::sqrt(FirstForm(shape, f).determinant());
  }
  // e_T (without eta).
  double FaceEnergy(const Positions& ref, const Positions& def, int f,
                    double alpha, double beta) const {
    const Eigen::Matrix2d m = FirstForm(ref, f).inverse() *
                              (SecondForm(def, f) - SecondForm(ref, f));
    return Area(ref, f) * (alpha * m.trace() * m.trace() + beta * (m * m).trace());
  }
  double Energy(const Positions& ref, const Positions& def, double alpha,
                double beta) const {
    double sum = 0;
    for (int f = 0; f < faces_.rows(); ++f) {
      sum += FaceEnergy(ref, def, f, alpha, beta);
    }
    return sum;
  }

 private:
  Faces faces_;
  std::map<std::pair<int, int>, int> half_edge_;
};

using testing::ShapeOperatorMaterial;
using TestShells = testing::BumpySheetPair;
TestShells MakeTestShells() { return testing::MakeBumpySheetPair(); }

// ---------------------------------------------------------------------------

TEST(ShapeOperatorTest, ElementSetHasOneFaceElementPerFaceByInteriorEdges) {
  const TestShells s = MakeTestShells();
  const ShellSpace space = testing::MakeSpace(s.mesh, ShapeOperatorMaterial(0.1));
  const ElementSet& set = space.elements();
  EXPECT_EQ(set.num_elements(), 2 * s.mesh.num_faces());
  std::map<int, int> faces_by_vertices;
  std::vector<int> seen(s.mesh.num_faces(), 0);
  set.ForEachGroup([&](const auto& group) {
    if (group.part != EnergyPart::kBending) return;
    faces_by_vertices[group.kVertices] += group.size();
    for (int i = 0; i < group.size(); ++i) {
      const int f = group.labels[i];
      ++seen[f];
      // The stencil's first three vertices are face f rotated cyclically.
      const auto& st = group.stencils[i];
      bool rotation = false;
      for (int r = 0; r < 3; ++r) {
        rotation |= st[0] == s.mesh.faces(f, r) &&
                    st[1] == s.mesh.faces(f, (r + 1) % 3) &&
                    st[2] == s.mesh.faces(f, (r + 2) % 3);
      }
      EXPECT_TRUE(rotation) << group.Describe(i);
    }
  });
  for (int f = 0; f < s.mesh.num_faces(); ++f) EXPECT_EQ(seen[f], 1);
  // Counted by hand on the 5 x 4 sheet: 2 corner faces with 1 interior edge,
  // 14 with 2 (along the border), 24 with 3.
  EXPECT_EQ(faces_by_vertices[4], 2);
  EXPECT_EQ(faces_by_vertices[5], 14);
  EXPECT_EQ(faces_by_vertices[6], 24);
  EXPECT_EQ(faces_by_vertices[3], 0);
}

TEST(ShapeOperatorTest, HalfSumOfSquaresIsTheDirectFormula) {
  const TestShells s = MakeTestShells();
  const DirectShapeOperator direct(s.mesh.faces);
  for (const auto& [alpha, beta] :
       std::vector<std::pair<double, double>>{{0.0, 1.0}, {0.3, 0.7}, {-0.2, 1.0}}) {
    const double eta = 0.1;
    const ShellSpace space =
        testing::MakeSpace(s.mesh, ShapeOperatorMaterial(eta, alpha, beta));
    const double expected = direct.Energy(s.reference, s.deformed, alpha, beta);
    ASSERT_GT(expected, 1e-3);
    // The elements' closed form.
    const DeformationEnergy e =
        EvaluateDeformationEnergy(space, s.reference, s.deformed);
    EXPECT_NEAR(e.bending, expected, 1e-12 * expected);
    // The residuals, face by face and summed through Ceres.
    double half_sum = 0;
    space.elements().ForEachGroup([&](const auto& group) {
      if (group.part != EnergyPart::kBending) return;
      constexpr int kV = std::decay_t<decltype(group)>::kVertices;
      for (int i = 0; i < group.size(); ++i) {
        Vec3<double> ref[kV], def[kV];
        GatherVertices(s.reference, group.stencils[i], ref);
        GatherVertices(s.deformed, group.stencils[i], def);
        double r[4] = {0, 0, 0, 0};
        ASSERT_TRUE(group.element.template Evaluate<double>(ref, def, r,
                                                             nullptr, nullptr));
        const double face = 0.5 * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
        const double want =
            eta * direct.FaceEnergy(s.reference, s.deformed, group.labels[i],
                                    alpha, beta);
        EXPECT_NEAR(face, want, 1e-12 * expected) << group.Describe(i);
        half_sum += face;
      }
    });
    EXPECT_NEAR(half_sum, eta * expected, 1e-12 * expected);
    Positions def = s.deformed;
    ceres::Problem problem;
    AddDeformationEnergy(space, ShellArgument::Fixed(s.reference),
                         ShellArgument::Variable(&def), 1.0, &problem);
    double cost = 0;
    problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr,
                     nullptr);
    EXPECT_NEAR(cost, e.membrane + eta * expected, 1e-11 * cost);
    std::printf("alpha %.1f beta %.1f: W_bend^SO = %.12g\n", alpha, beta,
                expected);
  }
}

TEST(ShapeOperatorTest, ZeroAtRestAndInvariantUnderRigidMotions) {
  const TestShells s = MakeTestShells();
  const ShellSpace space =
      testing::MakeSpace(s.mesh, ShapeOperatorMaterial(0.1, 0.3, 0.7));
  EXPECT_EQ(EvaluateDeformationEnergy(space, s.reference, s.reference).bending,
            0.0);
  EXPECT_EQ(EvaluateDeformationEnergy(space, s.deformed, s.deformed).bending,
            0.0);
  const double w =
      EvaluateDeformationEnergy(space, s.reference, s.deformed).bending;
  ASSERT_GT(w, 1e-3);
  const double w_ref =
      EvaluateDeformationEnergy(
          space, testing::RandomRigidMotion(s.reference, 3), s.deformed)
          .bending;
  const double w_def =
      EvaluateDeformationEnergy(
          space, s.reference, testing::RandomRigidMotion(s.deformed, 4))
          .bending;
  EXPECT_NEAR(w_ref, w, 1e-12 * w);
  EXPECT_NEAR(w_def, w, 1e-12 * w);
  // A non-rigid map (a stretch of the deformed shell) changes it.
  Positions stretched = s.deformed;
  stretched.col(2) *= 1.5;
  EXPECT_GT(std::abs(
                EvaluateDeformationEnergy(space, s.reference, stretched).bending -
                w),
            1e-3 * w);
}

// One stencil with kInterior interior edges: a face and the vertices across
// its edges, at random positions near a bent configuration.
template <int kInterior>
void RandomStencil(unsigned seed, std::vector<double>* ref,
                   std::vector<double>* def) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-0.15, 0.15);
  const double base[6][3] = {{0, 0, 0},      {1, 0, 0},     {0.4, 0.9, 0},
                             {1.2, 0.9, 0.3}, {-0.5, 0.6, -0.2},
                             {0.5, -0.8, 0.25}};
  ref->assign(3 * (3 + kInterior), 0);
  def->assign(3 * (3 + kInterior), 0);
  for (int v = 0; v < 3 + kInterior; ++v) {
    for (int c = 0; c < 3; ++c) {
      // Centred at (2, 2, 2): Ceres' steps are relative to |x|.
      (*ref)[3 * v + c] = 2 + base[v][c] + noise(rng);
      (*def)[3 * v + c] = 2 + 1.1 * base[v][c] + noise(rng) +
                          (c == 2 ? 0.2 * base[v][0] * base[v][1] : 0);
    }
  }
}

enum class Mode { kBothVariable, kReferenceFixed, kDeformedFixed };

template <int kInterior>
void CheckJacobians() {
  constexpr int kV = 3 + kInterior;
  double worst = 0, twin_least = 1e300;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    std::vector<double> ref, def;
    RandomStencil<kInterior>(seed, &ref, &def);
    for (Mode mode :
         {Mode::kBothVariable, Mode::kReferenceFixed, Mode::kDeformedFixed}) {
      std::vector<double*> params;
      for (int v = 0; v < kV && mode != Mode::kReferenceFixed; ++v) {
        params.push_back(ref.data() + 3 * v);
      }
      for (int v = 0; v < kV && mode != Mode::kDeformedFixed; ++v) {
        params.push_back(def.data() + 3 * v);
      }
      auto make = [&] {
        return std::unique_ptr<ceres::CostFunction>(
            ShapeOperatorBendingCostFunction<kInterior>::Create(
                0.2, 0.3, 0.7,
                mode == Mode::kReferenceFixed ? ref.data() : nullptr,
                mode == Mode::kDeformedFixed ? def.data() : nullptr, 1.7));
      };
      const auto cost = make();
      ASSERT_EQ(cost->parameter_block_sizes().size(), params.size());
      if (kInterior == 0) {
        // No interior edge: H = Hbar = 0, residuals and Jacobians vanish.
        double r[3];
        std::vector<double> jac(params.size() * 9, 1.0);
        std::vector<double*> blocks(params.size());
        for (size_t b = 0; b < params.size(); ++b) blocks[b] = &jac[9 * b];
        ASSERT_TRUE(cost->Evaluate(params.data(), r, blocks.data()));
        EXPECT_EQ(r[0] * r[0] + r[1] * r[1] + r[2] * r[2], 0.0);
        for (double j : jac) EXPECT_EQ(j, 0.0);
        continue;
      }
      const double error = testing::CostFunctionJacobianError(*cost, params);
      EXPECT_LT(error, 1e-7) << "interior edges " << kInterior << " seed "
                             << seed << " mode " << int(mode);
      // Negative twin: one entry of the last block (a P vertex if any)
      // off by 1e-4 is caught by the same helper.
      const int block = static_cast<int>(params.size()) - 1;
      testing::CostFunctionWithWrongJacobian wrong(make(), block, 4, 1e-4);
      const double twin = testing::CostFunctionJacobianError(wrong, params);
      EXPECT_GT(twin, 1e-6);
      worst = std::max(worst, error);
      twin_least = std::min(twin_least, twin);
    }
  }
  if (kInterior > 0) std::printf("%d interior edges: largest Jacobian error %.2e, smallest "
              "negative-twin error %.2e\n",
              kInterior, worst, twin_least);
}

TEST(ShapeOperatorTest, JacobiansMatchGradientCheckerWithNegativeTwin) {
  CheckJacobians<0>();
  CheckJacobians<1>();
  CheckJacobians<2>();
  CheckJacobians<3>();
}

// Gradients of the closed-form energy and Hessians (dual numbers over the
// analytic gradient J^T r) against central differences, both sides.
template <int kInterior>
void CheckSecondDerivatives() {
  constexpr int kV = 3 + kInterior, n = 3 * kV;
  ShapeOperatorElement<kInterior> element;
  element.eta = 1;
  element.alpha = 0.3;
  element.beta = 0.7;
  const double weight = 0.4;
  std::vector<double> ref, def;
  RandomStencil<kInterior>(11, &ref, &def);
  for (ShellSide side : {ShellSide::kDeformed, ShellSide::kReference}) {
    const bool active_ref = side == ShellSide::kReference;
    const Eigen::VectorXd x0 = Eigen::Map<const Eigen::VectorXd>(
        active_ref ? ref.data() : def.data(), n);
    auto at = [&](const Eigen::VectorXd& x, std::vector<double>* r,
                  std::vector<double>* d) {
      *r = ref;
      *d = def;
      std::copy(x.data(), x.data() + n, active_ref ? r->data() : d->data());
    };
    // Energy and its gradient on the active side.
    const testing::VectorFunction energy = [&](const Eigen::VectorXd& x) {
      std::vector<double> r, d;
      at(x, &r, &d);
      Vec3<double> rv[kV], dv[kV];
      for (int v = 0; v < kV; ++v) {
        rv[v] = Vec3<double>(r.data() + 3 * v);
        dv[v] = Vec3<double>(d.data() + 3 * v);
      }
      double e = 0;
      EXPECT_TRUE(element.Energy(rv, dv, &e));
      return Eigen::VectorXd::Constant(1, weight * e);
    };
    auto derivatives = [&](const Eigen::VectorXd& x) {
      std::vector<double> r, d;
      at(x, &r, &d);
      ElementSecondDerivatives<kV> out;
      EXPECT_TRUE(out.Compute(element, r.data(), d.data(), side, weight));
      return out;
    };
    const ElementSecondDerivatives<kV> d0 = derivatives(x0);
    const Eigen::VectorXd gradient =
        active_ref ? Eigen::VectorXd(d0.grad_reference)
                   : Eigen::VectorXd(d0.grad_deformed);
    std::vector<int> all(n);
    for (int j = 0; j < n; ++j) all[j] = j;
    const testing::DerivativeColumn grad_column = [&](int j) {
      return Eigen::VectorXd::Constant(1, gradient(j));
    };
    if (kInterior == 0) {
      // A face without interior edges has H = Hbar = 0: e = 0 identically.
      EXPECT_LT(
          testing::CentralDifferenceError(energy, x0, grad_column, all, 1e-6),
          1e-7);
      EXPECT_EQ(gradient.norm(), 0.0);
      EXPECT_EQ(d0.d_grad_reference.norm() + d0.d_grad_deformed.norm(), 0.0);
      continue;
    }
    const testing::ErrorAndTwin g = testing::CentralDifferenceErrorAndTwin(
        energy, x0, grad_column, all, 1e-6, {0, 2, 1e-4 * gradient.norm()});
    EXPECT_LT(g.error, 1e-7);
    EXPECT_GT(g.twin_error, 1e-6);
    // The gradient on the reference side (rows_ref) or the deformed side as
    // a function of the active side's coordinates, and its derivative by
    // them at x0: the block d_grad_reference or d_grad_deformed of d0.
    auto gradient_of = [&](bool rows_ref) -> testing::VectorFunction {
      return [&derivatives, rows_ref](const Eigen::VectorXd& x) {
        const ElementSecondDerivatives<kV> d = derivatives(x);
        return rows_ref ? Eigen::VectorXd(d.grad_reference)
                        : Eigen::VectorXd(d.grad_deformed);
      };
    };
    auto derivative_block = [&](bool rows_ref) {
      return rows_ref ? Eigen::MatrixXd(d0.d_grad_reference)
                      : Eigen::MatrixXd(d0.d_grad_deformed);
    };
    auto columns =
        [](const Eigen::MatrixXd& block) -> testing::DerivativeColumn {
      return [&block](int j) { return Eigen::VectorXd(block.col(j)); };
    };
    // Hessian: f = the active side's gradient, columns of d_grad.
    const testing::VectorFunction grad_fn = gradient_of(active_ref);
    const Eigen::MatrixXd hessian = derivative_block(active_ref);
    const testing::ErrorAndTwin h = testing::CentralDifferenceErrorAndTwin(
        grad_fn, x0, columns(hessian), all, 1e-5,
        {1, 3, 1e-3 * hessian.norm()});
    EXPECT_LT(h.error, 1e-6) << "interior edges " << kInterior;
    EXPECT_GT(h.twin_error, 1e-5);
    std::printf("%d interior edges, %s side: Hessian error %.2e\n", kInterior,
                active_ref ? "reference" : "deformed", h.error);
    // The mixed block (rows the other side's gradient, columns active).
    const testing::VectorFunction other_grad = gradient_of(!active_ref);
    const Eigen::MatrixXd mixed = derivative_block(!active_ref);
    const testing::ErrorAndTwin m = testing::CentralDifferenceErrorAndTwin(
        other_grad, x0, columns(mixed), all, 1e-5, {2, 4, 1e-3 * mixed.norm()});
    EXPECT_LT(m.error, 1e-6);
    EXPECT_GT(m.twin_error, 1e-5) << "interior edges " << kInterior;
  }
}

TEST(ShapeOperatorTest, GradientsAndHessiansMatchCentralDifferences) {
  CheckSecondDerivatives<0>();
  CheckSecondDerivatives<1>();
  CheckSecondDerivatives<2>();
  CheckSecondDerivatives<3>();
}

// The assembled W = W_mem + eta W_bend^SO: its gradient and D_2^2 W against
// central differences (the shape-operator groups go through the generic
// evaluators of energy_derivatives.h).
TEST(ShapeOperatorTest, AssembledGradientAndHessianOfW) {
  const TestShells s = MakeTestShells();
  const ShellSpace space =
      testing::MakeSpace(s.mesh, ShapeOperatorMaterial(0.5, 0.3, 0.7));
  const int n = 3 * s.mesh.num_vertices();
  const Eigen::VectorXd x0 =
      Eigen::Map<const Eigen::VectorXd>(Positions(s.deformed).data(), n);
  auto shape = [&](const Eigen::VectorXd& x) {
    Positions p(s.mesh.num_vertices(), 3);
    Eigen::Map<Eigen::VectorXd>(p.data(), n) = x;
    return p;
  };
  const testing::VectorFunction total = [&](const Eigen::VectorXd& x) {
    return Eigen::VectorXd::Constant(
        1, EvaluateDeformationEnergy(space, s.reference, shape(x)).total);
  };
  const Eigen::VectorXd g =
      EnergyGradient(space, s.reference, s.deformed, ShellSide::kDeformed);
  const std::vector<int> probes = testing::ProbeCoordinates(n, 20, 5);
  const testing::DerivativeColumn g_column = [&](int j) {
    return Eigen::VectorXd::Constant(1, g(j));
  };
  EXPECT_LT(testing::CentralDifferenceError(total, x0, g_column, probes, 1e-6),
            1e-7);
  const SparseMatrix h = EnergyHessian(space, s.reference, s.deformed,
                                       ShellSide::kDeformed, ShellSide::kDeformed);
  const testing::VectorFunction grad = [&](const Eigen::VectorXd& x) {
    return EnergyGradient(space, s.reference, shape(x), ShellSide::kDeformed);
  };
  const testing::DerivativeColumn h_column = [&](int j) {
    return Eigen::VectorXd(h.col(j));
  };
  EXPECT_LT(testing::CentralDifferenceError(grad, x0, h_column, probes, 1e-5),
            1e-6);
  EXPECT_GT(testing::CentralDifferenceError(
                grad, x0, testing::WrongInOneEntry(h_column, probes[0], probes[0], 1e-2),
                probes, 1e-5),
            1e-5);
}

// ---------------------------------------------------------------------------
// Convergence (docs/math.md, "Bending energy: two models").

// sum_T a_T tr(B_T^2) and sum_T a_T (tr B_T)^2 of one shape, B_T = G^-1 H,
// H from the library's mid-edge second form (through the element set's
// stencils) and, independently, from DirectShapeOperator.
struct CurvatureFunctional {
  double frobenius = 0, trace = 0, frobenius_direct = 0;
};
CurvatureFunctional Curvature(const Mesh& mesh) {
  const ShellSpace space = testing::MakeSpace(mesh, ShapeOperatorMaterial(1));
  const DirectShapeOperator direct(mesh.faces);
  CurvatureFunctional out;
  space.elements().ForEachGroup([&](const auto& group) {
    if (group.part != EnergyPart::kBending) return;
    constexpr int kV = std::decay_t<decltype(group)>::kVertices;
    for (int i = 0; i < group.size(); ++i) {
      Vec3<double> x[kV];
      GatherVertices(mesh.positions, group.stencils[i], x);
      const MidEdgeSecondForm<double, kV - 3> h(x, false);
      const FirstFundamentalForm<double> g(x[0], x[1], x[2]);
      Eigen::Matrix2d gm, hm;
      gm << g.g11, g.g12, g.g12, g.g22;
      hm << h.h11, h.h12, h.h12, h.h22;
      const Eigen::Matrix2d b = gm.inverse() * hm;
      const double area = 0.5 * std::sqrt(gm.determinant());
      out.frobenius += area * (b * b).trace();
      out.trace += area * b.trace() * b.trace();
      const int f = group.labels[i];
      const Eigen::Matrix2d bd = direct.FirstForm(mesh.positions, f).inverse() *
                                 direct.SecondForm(mesh.positions, f);
      out.frobenius_direct += area * (bd * bd).trace();
    }
  });
  return out;
}

TEST(ShapeOperatorTest, IcosphereCurvatureFunctionalConvergesAtFirstOrder) {
  const double expected[4] = {1.01086, 1.00440, 1.00193, 1.00090};  // spec
  double error[4];
  for (int level = 2; level <= 5; ++level) {
    const Mesh sphere = MakeIcosphere(level);
    const CurvatureFunctional c = Curvature(sphere);
    const double ratio = c.frobenius / (8 * kPi);
    error[level - 2] = ratio - 1;
    std::printf("icosphere level %d (%d faces): sum a tr(B^2) / 8 pi = %.6f, "
                "sum a (tr B)^2 / 16 pi = %.6f\n",
                level, sphere.num_faces(), ratio, c.trace / (16 * kPi));
    EXPECT_NEAR(ratio, expected[level - 2], 5e-6);
    EXPECT_NEAR(c.frobenius_direct, c.frobenius, 1e-10 * c.frobenius);
    EXPECT_NEAR(c.trace / (16 * kPi), ratio, 0.01);
  }
  for (int l = 0; l + 1 < 4; ++l) {
    const double rate = std::log2(error[l] / error[l + 1]);
    std::printf("rate %d->%d: %.3f\n", l + 2, l + 3, rate);
    EXPECT_GT(rate, 0.9);
    EXPECT_LT(rate, 1.5);
  }
}

TEST(ShapeOperatorTest, FlatSheetToCylinderInteriorFacesConvergeAtSecondOrder) {
  // The flat equilateral sheet (side h = 2 pi R / around) spanning the
  // circumference with `around` edges per row (2 around faces per row),
  // rolled onto the cylinder of radius R; the
  // energy W_bend^SO[flat, rolled] of the faces with three interior edges
  // against the continuum (1/R^2) x their area.
  const double expected[4] = {0.98405, 0.99599, 0.99900, 0.99975};  // spec
  const double radius = 1;
  double error[4], all_ratio[4], ds_ratio[4];
  for (int level = 0; level < 4; ++level) {
    const int around = 16 << level;  // triangle columns around
    const int columns = around;
    const double h = 2 * kPi * radius / columns;
    const int rows = std::max(4, int(std::round(2 * kPi * radius / h)));
    const Mesh flat = MakeEquilateralSheet(columns, rows, h);
    const Positions rolled = RollOntoCylinder(flat.positions, radius);
    const ShellSpace space = testing::MakeSpace(flat, ShapeOperatorMaterial(1));
    // All faces (boundary edges carry c = 0) against the whole sheet, and
    // Discrete Shells on the same meshes (its edges' areas d_E).
    const double all = EvaluateDeformationEnergy(space, flat.positions, rolled)
                           .bending;
    const double sheet_area = columns * rows * h * h * std::sqrt(3.0) / 2;
    ShellMaterial ds_material;
    ds_material.eta = 1;
    const double ds = EvaluateDeformationEnergy(
                          testing::MakeSpace(flat, ds_material), flat.positions,
                          rolled)
                          .bending;
    double ds_area = 0;
    for (const EdgeFlap& e : space.topology.interior_edges) {
      (void)e;
      ds_area += 2 * (h * h * std::sqrt(3.0) / 4) / 3;
    }
    all_ratio[level] = all / (sheet_area / (radius * radius));
    ds_ratio[level] = ds / (ds_area / (radius * radius));
    double energy = 0, area = 0;
    space.elements().ForEachGroup([&](const auto& group) {
      if (group.part != EnergyPart::kBending || group.kVertices != 6) return;
      constexpr int kV = std::decay_t<decltype(group)>::kVertices;
      for (int i = 0; i < group.size(); ++i) {
        Vec3<double> ref[kV], def[kV];
        GatherVertices(flat.positions, group.stencils[i], ref);
        GatherVertices(rolled, group.stencils[i], def);
        double e = 0;
        ASSERT_TRUE(group.element.Energy(ref, def, &e));
        energy += e;
        area += TriangleArea<double>(ref[0], ref[1], ref[2]).area;
      }
    });
    const double ratio = energy / (area / (radius * radius));
    error[level] = 1 - ratio;
    std::printf("cylinder %d edges around: interior-face ratio %.6f, all "
                "faces %.6f, Discrete Shells %.6f\n",
                around, ratio, all_ratio[level], ds_ratio[level]);
    EXPECT_NEAR(ratio, expected[level], 5e-6);
  }
  for (int l = 0; l + 1 < 4; ++l) {
    const double rate = std::log2(error[l] / error[l + 1]);
    std::printf("rate: %.3f\n", rate);
    EXPECT_GT(rate, 1.8);
    EXPECT_LT(rate, 2.2);
  }
  // With the boundary faces, first order (boundary edges carry c = 0). The
  // spec's "about 1.004" is for a sheet periodic around the cylinder; this
  // one also has the seam as boundary and lies below 1 (0.99627 at 128).
  // Discrete Shells tends to 3x the continuum value.
  EXPECT_NEAR(all_ratio[3], 1.0, 0.005);
  for (int l = 0; l + 1 < 4; ++l) {
    const double rate =
        std::log2(std::abs(all_ratio[l] - 1) / std::abs(all_ratio[l + 1] - 1));
    EXPECT_GT(rate, 0.8);
    EXPECT_LT(rate, 1.3);
    EXPECT_LT(std::abs(ds_ratio[l + 1] - 3), std::abs(ds_ratio[l] - 3) + 1e-3);
  }
  EXPECT_NEAR(ds_ratio[3], 3.0, 0.01);
}

}  // namespace
}  // namespace shellspace
