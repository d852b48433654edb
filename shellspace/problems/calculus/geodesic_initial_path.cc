#include "shellspace/problems/calculus/geodesic_initial_path.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "shellspace/cost_functions/ltheta_cost_functions.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/runtime/blas_threads.h"
#include "shellspace/geometry/named_values.h"
#include "shellspace/runtime/parallel_for.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/calculus/path_energy.h"
#include "shellspace/problems/calculus/ltheta_reconstruction.h"
#include "shellspace/problems/calculus/rotation_blend_path.h"

namespace shellspace {
namespace {

// The rotation angle (degrees) of the Kabsch rotation of `end` onto `start`.
double RotationDegrees(const Positions& start, const Positions& end) {
  const Eigen::Matrix3Xd a = start.transpose(), b = end.transpose();
  const Eigen::Matrix4d to_a = Eigen::umeyama(b, a, false);
  const Eigen::AngleAxisd rotation(Eigen::Matrix3d(to_a.topLeftCorner<3, 3>()));
  return std::abs(rotation.angle()) * 180.0 / M_PI;
}

}  // namespace

const char* GeodesicInitName(GeodesicInit init) {
  return NameOf(kGeodesicInitNames, init);
}

ShellPath LinearPathWithoutRigidMotion(const Positions& start,
                                       const Positions& end, int steps,
                                       const std::vector<int>& fixed_vertices,
                                       double* rotation_degrees) {
  const double degrees = start.rows() >= 3 ? RotationDegrees(start, end) : 0;
  if (rotation_degrees != nullptr) *rotation_degrees = degrees;
  if (!fixed_vertices.empty() || !(degrees >= kRigidBlendMinDegrees)) {
    return LinearPath(start, end, steps);
  }
  ShellPath path(steps + 1);
  path.front() = start;
  path.back() = end;
  for (int k = 1; k < steps; ++k) {
    path[k] = BlendRigidly(start, end, static_cast<double>(k) / steps);
  }
  return path;
}

std::string PathDegeneracy::Describe() const {
  if (turned_faces > 0) {
    return "triangle " + std::to_string(turned_face) + " turns over between "
           "shapes " + std::to_string(turned_shape - 1) + " and " +
           std::to_string(turned_shape) +
           (turned_faces > 1 ? " (" + std::to_string(turned_faces) +
                                   " triangles turn over)"
                             : std::string());
  }
  if (smallest_area_ratio < kDegenerateAreaRatio) {
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.3g", smallest_area_ratio);
    return "triangle " + std::to_string(area_face) + " of shape " +
           std::to_string(area_shape) + " keeps " + ratio + " of its area";
  }
  return "no degenerate triangle";
}

PathDegeneracy FindPathDegeneracy(const Faces& faces, const ShellPath& path,
                                  const std::vector<int>& ignored) {
  PathDegeneracy d;
  const int K = static_cast<int>(path.size()) - 1;
  std::vector<char> skip(faces.rows(), 0);
  for (int f : ignored) skip[f] = 1;
  for (int f = 0; f < faces.rows(); ++f) {
    if (skip[f]) continue;
    const double reference =
        0.5 * std::min(FaceNormal(faces, path.front(), f).norm(),
                       FaceNormal(faces, path.back(), f).norm());
    Eigen::Vector3d previous = FaceNormal(faces, path.front(), f);
    bool turned = false;
    for (int k = 1; k <= K; ++k) {
      const Eigen::Vector3d normal = FaceNormal(faces, path[k], f);
      if (k < K && reference > 0) {
        const double ratio = 0.5 * normal.norm() / reference;
        if (ratio < d.smallest_area_ratio) {
          d.smallest_area_ratio = ratio;
          d.area_shape = k;
          d.area_face = f;
        }
      }
      if (!turned && normal.dot(previous) < 0) {
        turned = true;
        if (d.turned_faces == 0) {
          d.turned_shape = k;
          d.turned_face = f;
        }
        ++d.turned_faces;
      }
      previous = normal;
    }
  }
  return d;
}

ShellPath LThetaPath(const ShellSpace& space, const Positions& start,
                     const Positions& end, int steps,
                     const std::vector<int>& fixed_vertices,
                     const SolverSettings& settings, int* iterations,
                     std::vector<int>* unconverged) {
  ShellPath path =
      LinearPathWithoutRigidMotion(start, end, steps, fixed_vertices);
  if (steps < 2) return path;
  const LThetaQuantities q0 = ComputeLThetaQuantities(space, start);
  LThetaQuantities q1 = ComputeLThetaQuantities(space, end);
  for (int e = 0; e < q1.dihedrals.size(); ++e) {
    q1.dihedrals[e] = q0.dihedrals[e] + WrapAngle(q1.dihedrals[e] -
                                                  q0.dihedrals[e]);
  }
  const LThetaWeights weights = LThetaResidualWeights(space, start);
  std::vector<ceres::Solver::Summary> summaries(steps - 1);
  // One thread per frame (Ceres' and the BLAS's): the digits do not depend
  // on the thread count.
  const ScopedBlasThreads one_blas_thread(1);
  const ShellPath guesses = path;
  ParallelFor(steps - 1, settings.num_threads, [&](int i) {
    const int k = i + 1;
    const double t = static_cast<double>(k) / steps;
    LThetaQuantities target;
    target.lengths = (1 - t) * q0.lengths + t * q1.lengths;
    target.areas = (1 - t) * q0.areas + t * q1.areas;
    target.dihedrals = (1 - t) * q0.dihedrals + t * q1.dihedrals;
    SolverSettings frame = settings;
    frame.num_threads = 1;
    frame.progress_label =
        settings.progress_label + " ltheta frame " + std::to_string(k);
    const Positions solved =
        ReconstructFromLTheta(space, target, weights, guesses[k], frame,
                              &summaries[i], fixed_vertices);
    path[k] =
        fixed_vertices.empty() ? AlignRigidly(solved, guesses[k]) : solved;
  });
  if (iterations != nullptr) {
    *iterations = 0;
    for (const ceres::Solver::Summary& s : summaries) {
      *iterations += std::max(0, static_cast<int>(s.iterations.size()) - 1);
    }
  }
  if (unconverged != nullptr) {
    unconverged->clear();
    for (int i = 0; i < steps - 1; ++i) {
      if (summaries[i].termination_type != ceres::CONVERGENCE) {
        unconverged->push_back(i + 1);
      }
    }
  }
  return path;
}

namespace {

// Which start `init` gives (r->used, r->reason, r->linear): the requested
// one, or for auto and linear the linear path unless auto finds it
// degenerate, then the rotation blend (returned, already made) unless it
// degenerates too, then the LΘA path. Empty unless the blend was made.
ShellPath ChooseInitialPath(const ShellSpace& space, const Positions& start,
                            const Positions& end, int steps,
                            const std::vector<int>& fixed_vertices,
                            GeodesicInit init, const ShellPath& linear,
                            InitialPathReport* report) {
  InitialPathReport& r = *report;
  ShellPath path;
  if (init == GeodesicInit::kLTheta) {
    r.used = GeodesicInit::kLTheta;
    r.reason = "ltheta (requested)";
  } else if (init == GeodesicInit::kRotations) {
    r.used = GeodesicInit::kRotations;
    r.reason = "rotations (requested)";
  } else {
    r.linear = FindPathDegeneracy(space.faces, linear);
    const bool replace = init == GeodesicInit::kAuto &&
                         r.linear.degenerate() && steps >= 2;
    r.used = GeodesicInit::kLinear;
    r.reason = std::string("linear (") +
               (init == GeodesicInit::kLinear ? "requested; " : "") +
               r.linear.Describe() + ")";
    if (replace) {
      // Auto: the rotation blend when it does not degenerate itself (one
      // factorisation), else the LΘA path (K - 1 nonlinear solves).
      ShellPath blend = RotationBlendPath(space.faces, space.topology, start,
                                          end, steps, fixed_vertices);
      const PathDegeneracy blend_degeneracy =
          blend.empty() ? PathDegeneracy() : FindPathDegeneracy(space.faces,
                                                                blend);
      if (!blend.empty() && !blend_degeneracy.degenerate() &&
          TryPathEnergy(space, blend)) {
        r.used = GeodesicInit::kRotations;
        r.reason = "rotations (the linear path degenerates: " +
                   r.linear.Describe() + ")";
        path = std::move(blend);
      } else {
        r.used = GeodesicInit::kLTheta;
        r.reason = "ltheta (the linear path degenerates: " +
                   r.linear.Describe() + "; so does the rotation blend" +
                   (blend.empty() ? std::string(": no factorisation")
                                  : ": " + blend_degeneracy.Describe()) +
                   ")";
      }
    }
  }
  return path;
}

// The path of the chosen start r->used (`path`: the rotation blend if
// ChooseInitialPath made it), falling back to `linear` where auto's LΘA
// path has a degenerate triangle or the blend cannot be solved.
ShellPath MakeChosenPath(const ShellSpace& space, const Positions& start,
                         const Positions& end, int steps,
                         const std::vector<int>& fixed_vertices,
                         GeodesicInit init, const SolverSettings& settings,
                         ShellPath path, ShellPath linear,
                         InitialPathReport* report) {
  InitialPathReport& r = *report;
  if (r.used == GeodesicInit::kLTheta) {
    SolverSettings frames = settings;
    if (init == GeodesicInit::kAuto) {
      frames.max_iterations =
          std::min(settings.max_iterations, kAutoLThetaFrameIterations);
    }
    path = LThetaPath(space, start, end, steps, fixed_vertices, frames,
                      &r.ltheta_iterations, &r.ltheta_unconverged);
    // Auto: a reconstruction with a degenerate triangle (no energy) is no
    // better a start than the linear path it replaces, if that one has an
    // energy.
    ElementFailure failure;
    if (init == GeodesicInit::kAuto &&
        !TryPathEnergy(space, path, nullptr, &failure) &&
        TryPathEnergy(space, linear)) {
      r.used = GeodesicInit::kLinear;
      r.reason += "; the ltheta path has a degenerate triangle (" +
                  failure.description + "), linear used";
      path = std::move(linear);
    }
  } else if (r.used == GeodesicInit::kRotations && path.empty()) {
    path = RotationBlendPath(space.faces, space.topology, start, end, steps,
                             fixed_vertices);
    if (path.empty()) {
      r.used = GeodesicInit::kLinear;
      r.reason += "; the rotation blend could not be solved, linear used";
      path = std::move(linear);
    }
  } else if (r.used == GeodesicInit::kLinear) {
    path = std::move(linear);
  }
  return path;
}

}  // namespace

ShellPath MakeGeodesicInitialPath(const ShellSpace& space,
                                  const Positions& start, const Positions& end,
                                  int steps,
                                  const std::vector<int>& fixed_vertices,
                                  GeodesicInit init,
                                  const SolverSettings& settings,
                                  InitialPathReport* report) {
  const auto clock = std::chrono::steady_clock::now();
  InitialPathReport local;
  InitialPathReport& r = report != nullptr ? *report : local;
  r = InitialPathReport();
  r.requested = init;
  ShellPath linear = LinearPathWithoutRigidMotion(start, end, steps,
                                                  fixed_vertices,
                                                  &r.rotation_degrees);
  r.rigid_motion_removed =
      fixed_vertices.empty() && r.rotation_degrees >= kRigidBlendMinDegrees;
  ShellPath path = ChooseInitialPath(space, start, end, steps, fixed_vertices,
                                     init, linear, &r);
  if (r.rigid_motion_removed) {
    char rotation[48];
    std::snprintf(rotation, sizeof rotation,
                  ", rigid motion of %.1f degrees removed",
                  r.rotation_degrees);
    r.reason += rotation;
  }
  path = MakeChosenPath(space, start, end, steps, fixed_vertices, init,
                        settings, std::move(path), std::move(linear), &r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                            clock)
                  .count();
  return path;
}

}  // namespace shellspace
