// The shape-operator bending model (docs/math.md, "Bending energy: two models";
// cost_functions/shell/shape_operator_element.h): residuals against an
// independent implementation of the formula (the intrinsic S_T conormal form
// with atan2 dihedral angles), one face element per face, rest and rigid
// invariance, and the convergence of the curvature functional on icospheres
// and of the flat-sheet-to-cylinder energy (meshes generated here). Its
// derivatives: shape_operator_derivatives_test.cc.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

#include "shellspace/cost_functions/deformation_energy_residuals.h"
#include "shellspace/cost_functions/shape_operator_bending_cost_function.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/element_set.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/topology.h"
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
