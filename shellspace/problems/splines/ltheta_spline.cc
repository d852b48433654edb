#include "shellspace/problems/splines/ltheta_spline.h"


#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "shellspace/cost_functions/ltheta_cost_functions.h"
#include "shellspace/runtime/blas_threads.h"
#include "shellspace/runtime/parallel_for.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/problems/splines/cubic_spline.h"

namespace shellspace {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
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

// Keyframes with their time indices.
using TimedKeyframes = std::vector<std::pair<int, const Positions*>>;

// Keyframe quantities, one row per keyframe: [lengths | areas | angles].
// Dihedral angles are unwrapped along the keyframes (each within pi of
// the previous one) so that no spline jumps by 2 pi.
Eigen::MatrixXd KeyframeQuantities(const ShellSpace& space,
                                   const std::vector<Positions>& keyframes,
                                   int num_edges, int num_faces,
                                   int num_flaps) {
  const int m = static_cast<int>(keyframes.size());
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
  return values;
}

// Keyframes in time order with, for a periodic path, the last one
// repeated one period earlier and the first one a period later.
TimedKeyframes TimeOrderedKeyframes(const std::vector<Positions>& keyframes,
                                    const std::vector<int>& at, int steps,
                                    bool periodic) {
  const int m = static_cast<int>(keyframes.size());
  TimedKeyframes neighbours;
  if (periodic) neighbours.emplace_back(at[m - 1] - steps, &keyframes[m - 1]);
  for (int j = 0; j < m; ++j) neighbours.emplace_back(at[j], &keyframes[j]);
  if (periodic) neighbours.emplace_back(at[0] + steps, &keyframes[0]);
  return neighbours;
}

// Frame k's shape if it is a keyframe (true), else its reconstruction's
// guess (false): the nearer end keyframe outside them, else the rigid blend
// of its neighbouring keyframes.
bool KeyframeOrGuess(const TimedKeyframes& neighbours, int k,
                     Positions* shape) {
  // Neighbouring keyframes: the last at or before k, the first after it.
  int before = -1;
  for (size_t n = 0; n < neighbours.size(); ++n) {
    if (neighbours[n].first <= k) before = static_cast<int>(n);
  }
  if (before >= 0 && neighbours[before].first == k) {
    *shape = *neighbours[before].second;  // a keyframe, exactly
    return true;
  }
  if (before < 0) {
    *shape = *neighbours.front().second;  // before the first keyframe
  } else if (before + 1 == static_cast<int>(neighbours.size())) {
    *shape = *neighbours.back().second;  // after the last keyframe
  } else {
    const auto& [index_a, a] = neighbours[before];
    const auto& [index_b, b] = neighbours[before + 1];
    *shape = BlendRigidly(
        *a, *b, static_cast<double>(k - index_a) / (index_b - index_a));
  }
  return false;
}

// Frames 0..last_frame: a keyframe's shape into *path, exactly; the others
// (to reconstruct) into *frames, their guesses into *guesses.
void PlaceKeyframes(const TimedKeyframes& neighbours, int last_frame,
                    ShellPath* path, std::vector<int>* frames,
                    std::vector<Positions>* guesses) {
  for (int k = 0; k <= last_frame; ++k) {
    Positions guess;
    if (KeyframeOrGuess(neighbours, k, &guess)) {
      (*path)[k] = std::move(guess);  // a keyframe, exactly
      continue;
    }
    frames->push_back(k);
    guesses->push_back(std::move(guess));
  }
}

// Frame k's target quantities: row k of the splines' `targets`.
LThetaQuantities FrameTarget(const Eigen::MatrixXd& targets, int k,
                             int num_edges, int num_faces, int num_flaps) {
  LThetaQuantities target;
  target.lengths = targets.row(k).head(num_edges).transpose();
  target.areas = targets.row(k).segment(num_edges, num_faces).transpose();
  target.dihedrals = targets.row(k).tail(num_flaps).transpose();
  return target;
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

ShellPath LThetaSpline(const ShellSpace& space,
                       const std::vector<Positions>& keyframes,
                       const std::vector<int>& at, int steps, bool periodic,
                       const SolverSettings& settings,
                       LThetaSplineReport* report) {
  CheckInputs(space, keyframes, at, steps, periodic);
  const auto spline_start = Clock::now();
  const int num_edges = static_cast<int>(space.topology.edges.size());
  const int num_faces = static_cast<int>(space.faces.rows());
  const int num_flaps = static_cast<int>(space.topology.interior_edges.size());

  const Eigen::MatrixXd values =
      KeyframeQuantities(space, keyframes, num_edges, num_faces, num_flaps);
  const LThetaWeights weights = LThetaResidualWeights(space, keyframes[0]);
  const Eigen::MatrixXd targets = InterpolateCubicSplineAtSteps(
      at, values, steps,
      periodic ? SplineEnds::kPeriodic : SplineEnds::kNatural);

  const TimedKeyframes neighbours =
      TimeOrderedKeyframes(keyframes, at, steps, periodic);
  if (report != nullptr) {
    *report = LThetaSplineReport();
    report->spline_seconds = SecondsSince(spline_start);
  }

  const auto solve_start = Clock::now();
  ShellPath path(steps + 1);
  const int last_frame = periodic ? steps - 1 : steps;
  std::vector<int> frames;  // to reconstruct, with their guesses
  std::vector<Positions> guesses;
  PlaceKeyframes(neighbours, last_frame, &path, &frames, &guesses);
  // The frames are independent: solved in parallel, each on one thread
  // (Ceres' and the BLAS's), so that the digits do not depend on the thread
  // count. Cactus 2, 10, 17 at 0, 2, 4, K = 4 (two frames): 25.3 s wall /
  // 29.1 user + 21.0 s system serially with 2 Ceres and 2 BLAS threads.
  std::vector<ceres::Solver::Summary> summaries(frames.size());
  const ScopedBlasThreads one_blas_thread(1);
  ParallelFor(static_cast<int>(frames.size()), settings.num_threads,
              [&](int i) {
                const int k = frames[i];
                const LThetaQuantities target =
                    FrameTarget(targets, k, num_edges, num_faces, num_flaps);
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
