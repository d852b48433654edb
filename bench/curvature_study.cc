// The convergence study of the two bending models (docs/math.md, "Bending
// energy: two models"), one run of the project's own code:
//
//   curvature_study            the convergence table (about a minute)
//   curvature_study geodesics  the finger and cactus geodesics (K = 8) with
//                              both models (a few minutes)
//
// Table: for the unit sphere (icospheres, levels 2..5) the curvature
// functional of the shape against its continuum value, sum_T a_T tr(B_T^2)
// / 8 pi (shape operator, B_T = G_T^-1 H_T) and sum_E theta_E^2 |E|^2 / d_E
// / 8 pi (Discrete Shells, the bending energy of the shape against a flat
// metric); for the cylinder of radius 1 (a flat equilateral sheet spanning
// the circumference, `around` = 16..128 edges (triangle columns) per row,
// rolled onto it) the
// bending energy W_bend[flat, rolled] of each model against (1/R^2) x the
// area it covers: the faces with three interior edges for the shape
// operator, the interior edges with their areas d_E = (a_1 + a_2) / 3 for
// Discrete Shells. "regular": the meshes as generated; "jittered": every
// vertex moved tangentially by a random vector of length <= 0.3 h (h the
// mean edge length; seed 1), then projected back (onto the sphere; the
// sheet is jittered flat and then rolled). "SO+phi": the edge-angle variant
// (one angle phi_E per interior edge, alpha_i = theta_i / 2 + s phi_E,
// c_i = 2 h_i sin(alpha_i), the phi of the shape minimising the functional
// by Levenberg-Marquardt over all faces). "rate" = log2(err_{l-1} / err_l),
// err = |ratio - 1| (1: first order, 2: second order); Discrete Shells tends
// to a mesh-dependent multiple of the continuum value, so its column shows
// the change from the previous level instead.
#include <ceres/ceres.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "shellspace/cost_functions/edge_angle_bending.h"
#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/element_set.h"
#include "shellspace/geometry/element_geometry.h"
#include "shellspace/geometry/mid_edge_second_form.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/topology.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/geodesic.h"

namespace shellspace {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------
// The shape-operator functional sum_T w_T tr(Gbar_T^-1 H_T)^2 of `shape`
// with metric `metric` (same connectivity; target Hbar = 0), at phi = 0 and
// with the edge angles fitted (cost_functions/edge_angle_bending.h), summed
// over the faces with three interior edges; `area` their metric area.
struct FunctionalValue {
  double plain = 0, rotated = 0, area = 0;
};
FunctionalValue Functional(const Mesh& mesh, const Topology& topo,
                           const Positions& metric, const Positions& shape) {
  const std::vector<EdgeAngleFace> faces = EdgeAngleFaces(mesh, topo, shape);
  const std::vector<EdgeAngleReferenceFace> reference =
      EdgeAngleReferenceFaces(mesh, metric);
  const int num_edges = static_cast<int>(topo.interior_edges.size());
  // The objective is the whole functional of the shape (all faces),
  // whichever faces are reported.
  const EdgeAngleFit fit = FitEdgeAngles(faces, reference, num_edges);
  if (!fit.converged) std::fprintf(stderr, "phi fit: %s\n", fit.message.c_str());
  FunctionalValue out;
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!(faces[f].interior(0) && faces[f].interior(1) && faces[f].interior(2))) {
      continue;
    }
    out.plain += fit.face_energy_at_zero[f];
    out.rotated += fit.face_energy[f];
    out.area += reference[f].area;
  }
  return out;
}

// Discrete Shells: sum over interior edges of theta^2 |E|^2 / d_E with the
// metric's |E|, d_E and the shape's theta (minus the metric's), and the sum
// of d_E.
struct ShellsValue {
  double energy = 0, area = 0;
};
ShellsValue DiscreteShells(const Topology& topo, const Positions& metric,
                           const Positions& shape, bool metric_is_flat) {
  ShellsValue out;
  for (const EdgeFlap& f : topo.interior_edges) {
    const Vec3<double> m[4] = {metric.row(f.i).transpose(),
                               metric.row(f.j).transpose(),
                               metric.row(f.k).transpose(),
                               metric.row(f.l).transpose()};
    const Vec3<double> x[4] = {shape.row(f.i).transpose(), shape.row(f.j).transpose(),
                               shape.row(f.k).transpose(), shape.row(f.l).transpose()};
    const double theta = DihedralAngle<double>(x[0], x[1], x[2], x[3]).theta;
    const double theta_bar =
        metric_is_flat ? DihedralAngle<double>(m[0], m[1], m[2], m[3]).theta : 0.0;
    const double d = (TriangleArea<double>(m[0], m[1], m[2]).area +
                      TriangleArea<double>(m[1], m[0], m[3]).area) /
                     3;
    out.energy += (theta - theta_bar) * (theta - theta_bar) *
                  (m[1] - m[0]).squaredNorm() / d;
    out.area += d;
  }
  return out;
}

struct Row {
  std::string shape, mesh;
  int level, faces;
  double so, so_phi, ds;
};

Row SphereRow(int level, bool jittered) {
  Mesh mesh = MakeIcosphere(level);
  const Topology topo = Topology::Build(mesh);
  if (jittered) {
    const double h = MeanEdgeLength(mesh, topo);
    mesh.positions = JitterTangentially(mesh.positions, mesh.positions, 0.3 * h, 1);
    mesh.positions.rowwise().normalize();
  }
  const FunctionalValue so = Functional(mesh, topo, mesh.positions, mesh.positions);
  const ShellsValue ds = DiscreteShells(topo, mesh.positions, mesh.positions, false);
  return {"sphere", jittered ? "jittered" : "regular", level, mesh.num_faces(),
          so.plain / (8 * kPi), so.rotated / (8 * kPi), ds.energy / (8 * kPi)};
}

Row CylinderRow(int level, bool jittered) {
  const double radius = 1;
  const int around = 16 << level;  // edges per row around
  const int columns = around;
  const double h = 2 * kPi * radius / columns;
  Mesh flat = MakeEquilateralSheet(columns, columns, h);
  const Topology topo = Topology::Build(flat);
  if (jittered) {
    Positions normals = Positions::Zero(flat.num_vertices(), 3);
    normals.col(2).setOnes();
    flat.positions = JitterTangentially(flat.positions, normals, 0.3 * h, 1);
  }
  const Positions rolled = RollOntoCylinder(flat.positions, radius);
  const FunctionalValue so = Functional(flat, topo, flat.positions, rolled);
  const ShellsValue ds = DiscreteShells(topo, flat.positions, rolled, true);
  const double k2 = 1 / (radius * radius);
  return {"cylinder", jittered ? "jittered" : "regular", level, flat.num_faces(),
          so.plain / (k2 * so.area), so.rotated / (k2 * so.area),
          ds.energy / (k2 * ds.area)};
}

void PrintTable() {
  std::printf(
      "| shape | mesh | level | faces | SO ratio | SO rate | SO+phi ratio | "
      "SO+phi rate | DS ratio | DS change |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string shape : {"sphere", "cylinder"}) {
    for (bool jittered : {false, true}) {
      std::vector<Row> rows;
      for (int l = 0; l < 4; ++l) {
        rows.push_back(shape == "sphere" ? SphereRow(l + 2, jittered)
                                         : CylinderRow(l, jittered));
      }
      for (int l = 0; l < 4; ++l) {
        const Row& r = rows[l];
        auto change = [&](double Row::*value) -> std::string {
          if (l == 0) return "";
          char buffer[32];
          std::snprintf(buffer, sizeof buffer, "%+.5f",
                        r.*value - rows[l - 1].*value);
          return buffer;
        };
        auto rate = [&](double Row::*value) -> std::string {
          if (l == 0) return "";
          char buffer[32];
          std::snprintf(buffer, sizeof buffer, "%.2f",
                        std::log2(std::abs(rows[l - 1].*value - 1) /
                                  std::abs(r.*value - 1)));
          return buffer;
        };
        const std::string level =
            shape == "sphere" ? std::to_string(r.level)
                              : std::to_string(16 << r.level) + " around";
        std::printf(
            "| %s | %s | %s | %d | %.5f | %s | %.5f | %s | %.5f | %s |\n",
            r.shape.c_str(), r.mesh.c_str(), level.c_str(), r.faces, r.so,
            rate(&Row::so).c_str(), r.so_phi, rate(&Row::so_phi).c_str(), r.ds,
            change(&Row::ds).c_str());
        std::fflush(stdout);
      }
    }
  }
}

// ---------------------------------------------------------------------------
std::string Data(const std::string& name) {
  return std::string(SHELLSPACE_DATA_DIR) + "/" + name;
}

void Geodesics() {
  struct Case {
    const char *name, *a, *b, *mask;
    double eta;
  };
  const Case cases[] = {
      {"finger", "finger/finger0.ply", "finger/finger1.ply",
       "finger/finger_mask.txt", 0.001},
      {"cactus", "cactus/cactus0.ply", "cactus/cactus1.ply",
       "cactus/cactus_bottom_mask.txt", 0.01},
  };
  std::printf(
      "| shape | model | E_K | iterations | converged | seconds |\n"
      "|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    const Mesh a = ReadMesh(Data(c.a));
    const Mesh b = ReadMesh(Data(c.b));
    const Topology topo = Topology::Build(a);
    GeodesicInput input;
    input.start = a.positions;
    input.end = b.positions;
    input.steps = 8;
    input.fixed_vertices = ReadMask(Data(c.mask), a.num_vertices());
    std::vector<ShellPath> paths;
    for (BendingModel model :
         {BendingModel::kDiscreteShells, BendingModel::kShapeOperator}) {
      ShellMaterial material;
      material.eta = c.eta;
      material.bending_model = model;
      const ShellSpace space(a, topo, material);
      SolverSettings settings;
      settings.progress = false;
      const auto t0 = std::chrono::steady_clock::now();
      const GeodesicResult g = SolveGeodesic(space, input, settings);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
              .count();
      std::printf("| %s (eta %g) | %s | %.6g | %d | %s | %.1f |\n", c.name,
                  c.eta, BendingModelName(model), g.path_energy, g.iterations,
                  g.converged ? "yes" : "no", seconds);
      std::fflush(stdout);
      paths.push_back(g.path);
    }
    double sum = 0;
    int count = 0;
    for (size_t k = 1; k + 1 < paths[0].size(); ++k) {
      sum += (paths[0][k] - paths[1][k]).rowwise().norm().sum();
      count += a.num_vertices();
    }
    const double diameter =
        (a.positions.colwise().maxCoeff() - a.positions.colwise().minCoeff())
            .norm();
    std::printf(
        "%s: mean vertex distance between the two paths (inner shapes) "
        "%.6g (bounding-box diagonal %.4g)\n\n",
        c.name, sum / count, diameter);
    std::fflush(stdout);
  }
}

}  // namespace
}  // namespace shellspace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "geodesics") == 0) {
    shellspace::Geodesics();
  } else {
    shellspace::PrintTable();
  }
  return 0;
}
