#include "shellspace/problems/splines/ltheta_spline.h"

#include <ceres/problem.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "shellspace/cost_functions/ltheta_cost_functions.h"
#include "shellspace/geometry/blas_threads.h"
#include "shellspace/geometry/element_geometry.h"
#include "shellspace/geometry/parallel_for.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/splines/cubic_spline.h"
#include "shellspace/solvers/rigid_gauge.h"

namespace shellspace {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Eigen::Vector3d Vertex(const Positions& shape, int v) {
  return shape.row(v).transpose();
}

// The guess between keyframes a and b at fraction t (see LThetaSpline in the
// header): blend of a and b rigidly aligned to a, moved by the fraction t of
// the rigid motion from a's placement to b's.
Positions BlendKeyframes(const Positions& a, const Positions& b, double t) {
  if (t <= 0) return a;
  if (t >= 1) return b;
  const Eigen::Matrix3Xd a_t = a.transpose(), b_t = b.transpose();
  const Eigen::Matrix4d to_a = Eigen::umeyama(b_t, a_t, false);
  const Eigen::Matrix3d r = to_a.topLeftCorner<3, 3>();
  const Eigen::Vector3d c = to_a.topRightCorner<3, 1>();
  const Eigen::Vector3d centroid_a = a_t.rowwise().mean();
  const Eigen::Vector3d centroid_b = b_t.rowwise().mean();
  const Eigen::Quaterniond partial = Eigen::Quaterniond::Identity().slerp(
      t, Eigen::Quaterniond(Eigen::Matrix3d(r.transpose())));
  const Eigen::Matrix3d q = partial.toRotationMatrix();
  const Eigen::Vector3d shift = t * (centroid_b - centroid_a);
  Positions guess(a.rows(), 3);
  for (int v = 0; v < a.rows(); ++v) {
    const Eigen::Vector3d b_aligned = r * Vertex(b, v) + c;
    const Eigen::Vector3d blend = (1 - t) * Vertex(a, v) + t * b_aligned;
    guess.row(v) = (q * (blend - centroid_a) + centroid_a + shift).transpose();
  }
  return guess;
}

void CheckInputs(const ShellSpace& space,
                 const std::vector<Positions>& keyframes,
                 const std::vector<int>& at, int steps, bool periodic) {
  if (steps < 1) {
    throw InputError("LΘA spline: steps must be >= 1, got " +
                     std::to_string(steps));
  }
  if (keyframes.empty()) throw InputError("LΘA spline: no keyframes");
  if (keyframes.size() != at.size()) {
    throw InputError("LΘA spline: " + std::to_string(keyframes.size()) +
                     " keyframes but " + std::to_string(at.size()) +
                     " indices");
  }
  const int last = periodic ? steps - 1 : steps;
  for (size_t j = 0; j < at.size(); ++j) {
    if (at[j] < 0 || at[j] > last) {
      throw InputError("LΘA spline: keyframe index " + std::to_string(at[j]) +
                       " outside [0, " + std::to_string(last) + "]" +
                       (periodic ? " (periodic: index K is index 0)" : ""));
    }
    if (j > 0 && at[j] <= at[j - 1]) {
      throw InputError(
          "LΘA spline: keyframe indices must be strictly "
          "increasing");
    }
    if (keyframes[j].rows() != space.num_vertices) {
      throw InputError("LΘA spline: keyframe " + std::to_string(j) + " has " +
                       std::to_string(keyframes[j].rows()) +
                       " vertices, expected " +
                       std::to_string(space.num_vertices));
    }
    if (!keyframes[j].allFinite()) {
      throw InputError("LΘA spline: keyframe " + std::to_string(j) +
                       " has non-finite coordinates");
    }
  }
}

}  // namespace

int LThetaSplineReport::lm_iterations() const {
  int total = 0;
  for (const ceres::Solver::Summary& s : summaries) {
    // Ceres records iteration 0 (the initial guess) too.
    total += std::max(0, static_cast<int>(s.iterations.size()) - 1);
  }
  return total;
}

std::vector<int> LThetaSplineReport::unconverged_frames() const {
  std::vector<int> frames;
  for (size_t i = 0; i < summaries.size(); ++i) {
    if (summaries[i].termination_type != ceres::CONVERGENCE) {
      frames.push_back(solved_frames[i]);
    }
  }
  return frames;
}

LThetaQuantities ComputeLThetaQuantities(const ShellSpace& space,
                                         const Positions& shape) {
  const Topology& topo = space.topology;
  LThetaQuantities q;
  q.lengths.resize(topo.edges.size());
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    q.lengths[e] =
        (Vertex(shape, topo.edges[e][1]) - Vertex(shape, topo.edges[e][0]))
            .norm();
  }
  q.areas.resize(space.faces.rows());
  for (int f = 0; f < space.faces.rows(); ++f) {
    q.areas[f] = TriangleArea<double>(Vertex(shape, space.faces(f, 0)),
                                      Vertex(shape, space.faces(f, 1)),
                                      Vertex(shape, space.faces(f, 2)))
                     .area;
  }
  q.dihedrals.resize(topo.interior_edges.size());
  for (size_t e = 0; e < topo.interior_edges.size(); ++e) {
    const EdgeFlap& flap = topo.interior_edges[e];
    q.dihedrals[e] =
        DihedralAngle<double>(Vertex(shape, flap.i), Vertex(shape, flap.j),
                              Vertex(shape, flap.k), Vertex(shape, flap.l))
            .theta;
  }
  return q;
}

LThetaWeights LThetaResidualWeights(const ShellSpace& space,
                                    const Positions& reference) {
  const LThetaQuantities ref = ComputeLThetaQuantities(space, reference);
  if (!(ref.lengths.size() == 0 || ref.lengths.minCoeff() > 0) ||
      !(ref.areas.size() == 0 || ref.areas.minCoeff() > 0) ||
      !ref.lengths.allFinite() || !ref.areas.allFinite()) {
    throw InputError(
        "LΘA spline: the first keyframe has a degenerate edge "
        "or triangle");
  }
  LThetaWeights w;
  w.edge = ref.lengths.cwiseInverse();
  w.area = ref.areas.cwiseSqrt().cwiseInverse();
  const double eta = space.material.eta;
  w.dihedral.resize(space.topology.interior_edges.size());
  for (size_t e = 0; e < space.topology.interior_edges.size(); ++e) {
    const EdgeFlap& flap = space.topology.interior_edges[e];
    const double length2 =
        (Vertex(reference, flap.j) - Vertex(reference, flap.i)).squaredNorm();
    w.dihedral[e] = std::sqrt(
        3 * eta * length2 / (ref.areas[flap.face_0] + ref.areas[flap.face_1]));
  }
  return w;
}

Positions ReconstructFromLTheta(const ShellSpace& space,
                                const LThetaQuantities& target,
                                const LThetaWeights& weights,
                                const Positions& initial,
                                const SolverSettings& settings,
                                ceres::Solver::Summary* summary) {
  const Topology& topo = space.topology;
  Positions x = initial;
  double* data = x.data();
  ceres::Problem problem;
  for (int v = 0; v < space.num_vertices; ++v) {
    problem.AddParameterBlock(data + 3 * v, 3);
  }
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    problem.AddResidualBlock(
        EdgeLengthCostFunction::Create(target.lengths[e], weights.edge[e]),
        nullptr, data + 3 * topo.edges[e][0], data + 3 * topo.edges[e][1]);
  }
  for (int f = 0; f < space.faces.rows(); ++f) {
    problem.AddResidualBlock(
        TriangleAreaCostFunction::Create(target.areas[f], weights.area[f]),
        nullptr, data + 3 * space.faces(f, 0), data + 3 * space.faces(f, 1),
        data + 3 * space.faces(f, 2));
  }
  if (space.material.eta > 0) {
    for (size_t e = 0; e < topo.interior_edges.size(); ++e) {
      const EdgeFlap& flap = topo.interior_edges[e];
      problem.AddResidualBlock(DihedralAngleCostFunction::Create(
                                   target.dihedrals[e], weights.dihedral[e]),
                               nullptr, data + 3 * flap.i, data + 3 * flap.j,
                               data + 3 * flap.k, data + 3 * flap.l);
    }
  }
  PinRigidMotions(&x, &problem);
  ceres::Solver::Summary result = SolveWithSettings(&problem, settings);
  if (summary != nullptr) *summary = std::move(result);
  return x;
}

ShellPath LThetaSpline(const ShellSpace& space,
                       const std::vector<Positions>& keyframes,
                       const std::vector<int>& at, int steps, bool periodic,
                       const SolverSettings& settings,
                       LThetaSplineReport* report) {
  CheckInputs(space, keyframes, at, steps, periodic);
  const auto spline_start = Clock::now();
  const int m = static_cast<int>(keyframes.size());
  const int num_edges = static_cast<int>(space.topology.edges.size());
  const int num_faces = static_cast<int>(space.faces.rows());
  const int num_flaps = static_cast<int>(space.topology.interior_edges.size());

  // Keyframe quantities, one row per keyframe: [lengths | areas | angles].
  // Dihedral angles are unwrapped along the keyframes (each within pi of
  // the previous one) so that no spline jumps by 2 pi.
  Eigen::MatrixXd values(m, num_edges + num_faces + num_flaps);
  for (int j = 0; j < m; ++j) {
    const LThetaQuantities q = ComputeLThetaQuantities(space, keyframes[j]);
    Eigen::VectorXd dihedrals = q.dihedrals;
    if (j > 0) {
      const auto previous = values.row(j - 1).tail(num_flaps).transpose();
      for (int e = 0; e < num_flaps; ++e) {
        dihedrals[e] = previous[e] + WrapAngle(dihedrals[e] - previous[e]);
      }
    }
    values.row(j) << q.lengths.transpose(), q.areas.transpose(),
        dihedrals.transpose();
  }
  const LThetaWeights weights = LThetaResidualWeights(space, keyframes[0]);
  const Eigen::MatrixXd targets = InterpolateCubicSplineAtSteps(
      at, values, steps,
      periodic ? SplineEnds::kPeriodic : SplineEnds::kNatural);

  // Keyframes in time order with, for a periodic path, the last one
  // repeated one period earlier and the first one a period later.
  std::vector<std::pair<int, const Positions*>> neighbours;
  if (periodic) neighbours.emplace_back(at[m - 1] - steps, &keyframes[m - 1]);
  for (int j = 0; j < m; ++j) neighbours.emplace_back(at[j], &keyframes[j]);
  if (periodic) neighbours.emplace_back(at[0] + steps, &keyframes[0]);
  if (report != nullptr) {
    *report = LThetaSplineReport();
    report->spline_seconds = SecondsSince(spline_start);
  }

  const auto solve_start = Clock::now();
  ShellPath path(steps + 1);
  const int last_frame = periodic ? steps - 1 : steps;
  std::vector<int> frames;  // to reconstruct, with their guesses
  std::vector<Positions> guesses;
  for (int k = 0; k <= last_frame; ++k) {
    // Neighbouring keyframes: the last at or before k, the first after it.
    int before = -1;
    for (size_t n = 0; n < neighbours.size(); ++n) {
      if (neighbours[n].first <= k) before = static_cast<int>(n);
    }
    if (before >= 0 && neighbours[before].first == k) {
      path[k] = *neighbours[before].second;  // a keyframe, exactly
      continue;
    }
    Positions guess;
    if (before < 0) {
      guess = *neighbours.front().second;  // before the first keyframe
    } else if (before + 1 == static_cast<int>(neighbours.size())) {
      guess = *neighbours.back().second;  // after the last keyframe
    } else {
      const auto& [index_a, a] = neighbours[before];
      const auto& [index_b, b] = neighbours[before + 1];
      guess = BlendKeyframes(
          *a, *b, static_cast<double>(k - index_a) / (index_b - index_a));
    }
    frames.push_back(k);
    guesses.push_back(std::move(guess));
  }
  // The frames are independent: solved in parallel, each on one thread
  // (Ceres' and the BLAS's), so that the digits do not depend on the thread
  // count. Cactus 2, 10, 17 at 0, 2, 4, K = 4 (two frames): 25.3 s wall /
  // 29.1 user + 21.0 s system serially with 2 Ceres and 2 BLAS threads.
  std::vector<ceres::Solver::Summary> summaries(frames.size());
  const ScopedBlasThreads one_blas_thread(1);
  ParallelFor(static_cast<int>(frames.size()), settings.num_threads,
              [&](int i) {
                const int k = frames[i];
                LThetaQuantities target;
                target.lengths = targets.row(k).head(num_edges).transpose();
                target.areas =
                    targets.row(k).segment(num_edges, num_faces).transpose();
                target.dihedrals = targets.row(k).tail(num_flaps).transpose();
                SolverSettings frame_settings = settings;
                frame_settings.num_threads = 1;
                frame_settings.progress_label = settings.progress_label +
                                                " ltheta frame " +
                                                std::to_string(k);
                const Positions solved =
                    ReconstructFromLTheta(space, target, weights, guesses[i],
                                          frame_settings, &summaries[i]);
                path[k] = AlignRigidly(solved, guesses[i]);
              });
  if (report != nullptr) {
    report->solved_frames = frames;
    report->summaries = std::move(summaries);
  }
  if (periodic) path[steps] = path[0];
  if (report != nullptr) report->solve_seconds = SecondsSince(solve_start);
  return path;
}

}  // namespace shellspace
