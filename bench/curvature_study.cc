// The convergence study of the two bending models (shape_operator.md,
// issue 18), one run of the project's own code:
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
#include <map>
#include <string>
#include <vector>

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
// Per-face data of the functional sum_T w_T tr((L^-1 H_T L^-T)^2), with
// w_T, L from a metric face (the shape itself for the sphere, the flat sheet
// for the cylinder) and H_T from the shape's mid-edge normals, possibly
// rotated by phi.
struct FaceData {
  double weight = 0;        // area of the metric face
  double p = 0, q = 0, s = 0;  // L^-1 = [[p, 0], [q, s]]
  double h[3] = {0, 0, 0};     // altitudes of the shape's face
  double half_theta[3] = {0, 0, 0};
  int edge[3] = {-1, -1, -1};  // interior edge index, -1 boundary
  double sign[3] = {0, 0, 0};
  bool counted = true;  // part of the reported sum
};

// Residuals of one face (alpha = 0, beta = 1): 1/2 |r|^2 = w tr(K^2).
struct FaceResidual {
  explicit FaceResidual(const FaceData& d) : d(d) {}
  template <typename T>
  void Residuals(const T* phi0, const T* phi1, const T* phi2,
                 T* r) const {
    const T* phi[3] = {phi0, phi1, phi2};
    T c[3];
    for (int i = 0; i < 3; ++i) {
      c[i] = d.edge[i] < 0 ? T(0)
                           : T(2 * d.h[i]) *
                                 sin(T(d.half_theta[i]) + T(d.sign[i]) * phi[i][0]);
    }
    const T a11 = c[0] + c[1], a12 = c[0], a22 = c[0] + c[2];
    const T k11 = T(d.p * d.p) * a11;
    const T k12 = T(d.p) * (T(d.q) * a11 + T(d.s) * a12);
    const T k22 = T(d.q * d.q) * a11 + T(2 * d.q * d.s) * a12 + T(d.s * d.s) * a22;
    const T w(std::sqrt(d.weight));
    r[0] = w * (k11 + k22);
    r[1] = w * (k11 - k22);
    r[2] = T(2) * w * k12;
  }
  template <typename T>
  bool operator()(const T* phi0, const T* phi1, const T* phi2, T* r) const {
    Residuals(phi0, phi1, phi2, r);
    return true;
  }
  FaceData d;
};

// w tr(K^2) = 1/2 |r|^2 at phi.
double FaceValue(const FaceData& d, const std::vector<double>& phi) {
  double p[3];
  for (int i = 0; i < 3; ++i) p[i] = d.edge[i] < 0 ? 0.0 : phi[d.edge[i]];
  double r[3];
  FaceResidual(d).Residuals(&p[0], &p[1], &p[2], r);
  return 0.5 * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
}

// The faces' data of `shape` with metric `metric` (same connectivity).
std::vector<FaceData> Faces(const Mesh& mesh, const Topology& topo,
                            const Positions& metric, const Positions& shape) {
  // Directed edge -> (interior edge index, vertex across, sign).
  struct Across {
    int edge, vertex;
    double sign;
  };
  std::map<std::pair<int, int>, Across> across;
  for (int e = 0; e < static_cast<int>(topo.interior_edges.size()); ++e) {
    const EdgeFlap& f = topo.interior_edges[e];
    across[{f.i, f.j}] = {e, f.l, 1.0};
    across[{f.j, f.i}] = {e, f.k, -1.0};
  }
  std::vector<FaceData> out(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    FaceData& d = out[f];
    Vec3<double> x[3], m[3];
    for (int a = 0; a < 3; ++a) {
      x[a] = shape.row(mesh.faces(f, a)).transpose();
      m[a] = metric.row(mesh.faces(f, a)).transpose();
    }
    const FirstFundamentalForm<double> g(m[0], m[1], m[2]);
    const double l11 = std::sqrt(g.g11), l21 = g.g12 / l11;
    const double l22 = std::sqrt(g.g22 - l21 * l21);
    d.p = 1 / l11;
    d.q = -l21 / (l11 * l22);
    d.s = 1 / l22;
    d.weight = TriangleArea<double>(m[0], m[1], m[2]).area;
    const Vec3<double> normal = (x[1] - x[0]).cross(x[2] - x[0]);
    const double area = 0.5 * normal.norm();
    const Vec3<double> n = normal.normalized();
    int interior = 0;
    for (int i = 0; i < 3; ++i) {
      const int a = mesh.faces(f, (i + 1) % 3), b = mesh.faces(f, (i + 2) % 3);
      const Vec3<double> xa = shape.row(a).transpose(),
                         xb = shape.row(b).transpose();
      d.h[i] = 2 * area / (xb - xa).norm();
      const auto it = across.find({a, b});
      if (it == across.end()) continue;
      ++interior;
      const Vec3<double> xp = shape.row(it->second.vertex).transpose();
      const Vec3<double> edge = (xb - xa).normalized();
      Vec3<double> t = 0.5 * (xa + xb) - x[i];
      t = (t - t.dot(edge) * edge).normalized();
      const Vec3<double> n_i = (xa - xb).cross(xp - xb).normalized();
      d.half_theta[i] = 0.5 * std::atan2(n_i.dot(t), n.dot(n_i));
      d.edge[i] = it->second.edge;
      d.sign[i] = it->second.sign;
    }
    d.counted = interior == 3;
  }
  return out;
}

// sum over counted faces of w tr(K^2), phi = 0 and minimised over phi.
struct FunctionalValue {
  double plain = 0, rotated = 0, area = 0;
};
FunctionalValue Functional(const std::vector<FaceData>& faces, int num_edges,
                           bool minimise) {
  FunctionalValue out;
  std::vector<double> phi(num_edges, 0.0);
  for (const FaceData& d : faces) {
    if (!d.counted) continue;
    out.plain += FaceValue(d, phi);
    out.area += d.weight;
  }
  if (!minimise) return out;
  ceres::Problem problem;
  double boundary[3] = {0, 0, 0};  // constant phi of boundary edge slot i
  for (const FaceData& d : faces) {
    // The objective is the whole bending functional of the shape (all
    // faces), whichever faces are reported.
    double* blocks[3];
    for (int i = 0; i < 3; ++i) {
      blocks[i] = d.edge[i] < 0 ? &boundary[i] : &phi[d.edge[i]];
    }
    auto* cost = new ceres::AutoDiffCostFunction<FaceResidual, 3, 1, 1, 1>(
        new FaceResidual(d));
    problem.AddResidualBlock(cost, nullptr, blocks[0], blocks[1], blocks[2]);
    for (int i = 0; i < 3; ++i) {
      if (d.edge[i] < 0) problem.SetParameterBlockConstant(blocks[i]);
    }
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = 100;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-14;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (summary.termination_type != ceres::CONVERGENCE) {
    std::fprintf(stderr, "phi minimisation: %s\n", summary.BriefReport().c_str());
  }
  for (const FaceData& d : faces) {
    if (d.counted) out.rotated += FaceValue(d, phi);
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

double MeanEdgeLength(const Mesh& mesh, const Topology& topo) {
  double sum = 0;
  for (const auto& e : topo.edges) {
    sum += (mesh.positions.row(e[0]) - mesh.positions.row(e[1])).norm();
  }
  return sum / topo.edges.size();
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
  const auto faces = Faces(mesh, topo, mesh.positions, mesh.positions);
  const FunctionalValue so =
      Functional(faces, static_cast<int>(topo.interior_edges.size()), true);
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
  const auto faces = Faces(flat, topo, flat.positions, rolled);
  const FunctionalValue so =
      Functional(faces, static_cast<int>(topo.interior_edges.size()), true);
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
