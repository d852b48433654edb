#include "shellspace/problems/calculus/stiff_vertex_elimination.h"

#include <algorithm>
#include <cmath>

#include "shellspace/geometry/topology.h"
#include "shellspace/geometry/vertex_flags.h"
#include "shellspace/problems/calculus/path_newton.h"

namespace shellspace {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The smallest angle (degrees) of face f of `shape`.
double SmallestAngle(const Faces& faces, const Positions& shape, int f) {
  double smallest = 180;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d p = shape.row(faces(f, a)).transpose();
    const Eigen::Vector3d u = shape.row(faces(f, (a + 1) % 3)).transpose() - p;
    const Eigen::Vector3d w = shape.row(faces(f, (a + 2) % 3)).transpose() - p;
    smallest = std::min(smallest,
                        std::atan2(u.cross(w).norm(), u.dot(w)) * 180 / kPi);
  }
  return smallest;
}

// Ring 1: the faces with a vertex flagged in `is_stiff`; then `rings` - 1
// times, the faces that share an edge with a chosen one. Increasing order.
std::vector<int> FaceRings(const ShellSpace& space,
                           const std::vector<char>& is_stiff, int rings) {
  const int num_faces = static_cast<int>(space.faces.rows());
  std::vector<char> chosen(num_faces, 0);
  for (int f = 0; f < num_faces; ++f) {
    for (int a = 0; a < 3; ++a) {
      if (is_stiff[space.faces(f, a)]) chosen[f] = 1;
    }
  }
  for (int r = 1; r < rings; ++r) {
    std::vector<char> next = chosen;
    for (const auto& faces : space.topology.edge_faces) {
      if (faces[0] < 0 || faces[1] < 0) continue;
      if (chosen[faces[0]] || chosen[faces[1]]) {
        next[faces[0]] = next[faces[1]] = 1;
      }
    }
    chosen.swap(next);
  }
  std::vector<int> list;
  for (int f = 0; f < num_faces; ++f) {
    if (chosen[f]) list.push_back(f);
  }
  return list;
}

}  // namespace

std::vector<int> FindStiffVertices(const Faces& faces, const Positions& shape,
                                   const std::vector<int>& fixed,
                                   double degrees) {
  const int n = static_cast<int>(shape.rows());
  std::vector<char> stiff(n, 0);
  for (int f = 0; f < faces.rows(); ++f) {
    if (SmallestAngle(faces, shape, f) < degrees) {
      for (int a = 0; a < 3; ++a) stiff[faces(f, a)] = 1;
    }
  }
  const std::vector<char> is_fixed = VertexFlags(n, fixed);
  std::vector<int> list;
  for (int v = 0; v < n; ++v) {
    if (stiff[v] && !is_fixed[v]) list.push_back(v);
  }
  return list;
}

StiffVertexElimination::StiffVertexElimination(const ShellSpace& space,
                                               const std::vector<int>& stiff,
                                               double min_area_fraction,
                                               int rings)
    : stiff_(stiff), min_area_fraction_(min_area_fraction) {
  if (stiff_.empty()) return;
  const std::vector<char> is_stiff = VertexFlags(space.num_vertices, stiff_);
  const std::vector<int> faces = FaceRings(space, is_stiff, rings);
  std::vector<int> sub_of(space.num_vertices, -1);
  Mesh mesh;
  mesh.faces.resize(static_cast<int>(faces.size()), 3);
  for (int i = 0; i < static_cast<int>(faces.size()); ++i) {
    for (int a = 0; a < 3; ++a) {
      int& id = sub_of[space.faces(faces[i], a)];
      if (id < 0) {
        id = static_cast<int>(whole_of_.size());
        whole_of_.push_back(space.faces(faces[i], a));
      }
      mesh.faces(i, a) = id;
    }
  }
  // Positions only give the topology its size; the elements read the
  // shapes they are evaluated on.
  mesh.positions = Positions::Zero(static_cast<int>(whole_of_.size()), 3);
  sub_space_ = ShellSpace(mesh, Topology::Build(mesh), space.material);
  for (int v : stiff_) sub_stiff_.push_back(sub_of[v]);
  const std::vector<char> sub_is_stiff =
      VertexFlags(static_cast<int>(whole_of_.size()), sub_stiff_);
  for (int i = 0; i < static_cast<int>(whole_of_.size()); ++i) {
    if (!sub_is_stiff[i]) sub_fixed_.push_back(i);
  }
}

StiffEliminationReport StiffVertexElimination::Solve(int max_steps,
                                                     double tolerance,
                                                     ShellPath* path) {
  StiffEliminationReport report;
  if (empty() || path->size() < 3) return report;
  const int K = static_cast<int>(path->size()) - 1;
  const int n = static_cast<int>(whole_of_.size());
  ShellPath sub(K + 1, Positions(n, 3));
  for (int k = 0; k <= K; ++k) {
    for (int i = 0; i < n; ++i) sub[k].row(i) = (*path)[k].row(whole_of_[i]);
  }
  PathNewtonSettings settings;
  settings.linear_solver = PathLinearSolver::kDirect;
  settings.globalisation = NewtonSettings::Globalisation::kTrustRegion;
  settings.model = HessianModel::kExact;
  settings.max_steps = max_steps;
  settings.gradient_tolerance = tolerance;
  settings.num_threads = 1;
  settings.keep_best_iterate = false;
  settings.min_area_fraction = min_area_fraction_;
  const PathNewtonReport newton =
      PolishPathNewton(sub_space_, sub_fixed_, settings, &sub);
  report.solved = newton.stop != NewtonStop::kInfeasibleStart &&
                  newton.stop != NewtonStop::kAssemblyFailed;
  report.steps = newton.steps;
  newton_steps_ += newton.steps;
  report.gradient_before = newton.initial_gradient;
  report.gradient_after = newton.final_gradient;
  if (newton.steps == 0) return report;
  for (int k = 1; k < K; ++k) {
    for (size_t j = 0; j < stiff_.size(); ++j) {
      (*path)[k].row(stiff_[j]) = sub[k].row(sub_stiff_[j]);
    }
  }
  return report;
}

}  // namespace shellspace
