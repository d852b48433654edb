// The LΘA spline (docs/math.md, "Riemannian splines"): a fast approximation of
// the time-discrete spline through keyframes, and the initial guess of the
// nonlinear spline.
//
// Every edge length l_e, triangle area a_f and interior dihedral angle
// theta_e is interpolated in time by a cubic spline through its keyframe
// values (problems/cubic_spline.h; natural ends, or periodic with period K);
// each non-keyframe shape s_k is then reconstructed from the interpolated
// values l*, a*, theta* by sparse Levenberg-Marquardt on
//
//   1/2 sum_e (l_e - l*_e)^2 / L_e^2 + 1/2 sum_f (a_f - a*_f)^2 / A_f
//     + 1/2 eta sum_{e interior} 3 L_e^2 / (A_f1 + A_f2) (theta_e - theta*_e)^2
//
// with L, A the lengths and areas of the first keyframe and eta the bending
// weight of the space's material; one residual per element
// (cost_functions/ltheta_cost_functions.h), one parameter block per vertex.
#ifndef SHELLSPACE_PROBLEMS_SPLINES_LTHETA_SPLINE_H_
#define SHELLSPACE_PROBLEMS_SPLINES_LTHETA_SPLINE_H_

#include <ceres/solver.h>

#include <Eigen/Core>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/ltheta_reconstruction.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {

// Per-frame record of an LΘA spline solve.
struct LThetaSplineReport {
  std::vector<int> solved_frames;                 // non-keyframe indices k
  std::vector<ceres::Solver::Summary> summaries;  // one per solved frame
  double spline_seconds = 0;  // quantities and their splines
  double solve_seconds = 0;   // all reconstructions

  // LM iterations over all solved frames (Ceres' iteration 0 not counted).
  int lm_iterations() const;
  // The solved frames whose reconstruction stopped short of its tolerances
  // (Ceres' termination not CONVERGENCE: the iteration cap, or a failure).
  std::vector<int> unconverged_frames() const;
};

// The LΘA spline through `keyframes` at the strictly increasing indices `at`
// of a path with steps + 1 shapes (K = steps >= 1).
// - Natural (periodic = false): indices in [0, K]. Outside [at.front(),
//   at.back()] the splines continue linearly.
// - Periodic: indices in [0, K), the path is closed (shape K = shape 0) and
//   the splines are periodic with period K.
// Keyframes are returned exactly (copied) at their indices (and, periodic,
// shape K = shape 0). Every other frame k is reconstructed independently
// (ReconstructFromLTheta) from an initial guess interpolating its two
// neighbouring keyframes a (index k_a <= k) and b (k_b > k), wrapping
// around for a periodic path, t = (k - k_a) / (k_b - k_a): b is rigidly
// aligned to a (Kabsch, b' = R b + c), the positions are blended linearly,
// (1 - t) a + t b', and the blend is moved by the fraction t of the rigid
// motion back to b (rotation slerped from I to R^T about a's centroid,
// centroid moved linearly). This is the plain linear interpolation
// (1 - t) a + t b when a and b are rigidly aligned, and never collapses a
// large rotation between keyframes. Frames outside the keyframe range
// (natural ends) start from the nearest keyframe. The gauge of each solve is
// pinned at three vertices of its guess (PinRigidMotions) and the solved
// frame is finally rigidly aligned to its guess, so the output does not
// depend on the pinned vertices and follows the keyframes' placement. The
// frames are solved in parallel on settings.num_threads threads, each solve
// on one thread (Ceres and the BLAS): the result does not depend on the
// thread count.
// Throws InputError on bad indices, counts or vertex numbers.
ShellPath LThetaSpline(const ShellSpace& space,
                       const std::vector<Positions>& keyframes,
                       const std::vector<int>& at, int steps, bool periodic,
                       const SolverSettings& settings,
                       LThetaSplineReport* report = nullptr);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_SPLINES_LTHETA_SPLINE_H_
