// Discrete geodesics (docs/math.md, "Path energy and discrete geodesics"):
// interpolation minimising E_K = K sum_k W[s_{k-1}, s_k], the weighted 3-shape
// problem behind midpoints and convex geodesic combinations, evaluating E_K.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_GEODESIC_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_GEODESIC_H_

#include <ceres/solver.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/problems/calculus/geodesic_initial_path.h"
#include "shellspace/problems/calculus/path_energy.h"
#include "shellspace/problems/calculus/path_newton.h"
#include "shellspace/problems/calculus/shell_path.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {

// The solver of a geodesic's Levenberg-Marquardt stages:
//  - kCeres: Ceres' sparse LM on the residuals (SPARSE_NORMAL_CHOLESKY: one
//    factorisation of the whole space-time J^T J per iteration);
//  - kEngine: the Newton engine's LM (NewtonSettings::Globalisation::
//    kLevenbergMarquardt) on the same Gauss-Newton matrix J^T J, assembled
//    as the path Hessian is, with the Newton finish's linear solver
//    (GeodesicInput::linear_solver: block-Jacobi CG with memory
//    O(K x one shape), or the direct space-time Cholesky);
//  - kAuto: kEngine where the linear solver is block-Jacobi by size
//    (ChooseLinearSolver) or where the start shape has sliver triangles
//    (FindSliverFaces: the engine's trials keep kStepMinAreaFraction of
//    every triangle's area), else kCeres.
enum class GeodesicLm { kAuto, kCeres, kEngine };

// The GeodesicLm that runs for `choice` on a problem with `unknowns` reduced
// unknowns and linear solver `linear_solver` (kAuto resolved; never kAuto).
GeodesicLm ChooseGeodesicLm(GeodesicLm choice, PathLinearSolver linear_solver,
                            int unknowns);

// The globalisation of a geodesic's Newton finish where the LM stages are
// Ceres' (with the engine's LM stages it is always the trust region):
//  - kTrustRegion: NewtonSettings::Globalisation::kTrustRegion on the exact
//    Hessian (Steihaug-Toint CG in the norm of the linear solver's
//    factorisation);
//  - kLineSearch: the Newton step with a line search and shifted Hessians
//    H + lambda I where it cannot be used.
enum class GeodesicNewton { kTrustRegion, kLineSearch };

// What globalises a geodesic solve once its exact Newton attempts are spent
// (kMaxNewtonAttempts attempts, each after an LM stage to a ten times
// smaller gradient, stopped short: the Hessian indefinite, not yet in
// Newton's basin) and LM alone to the tolerance has stopped short too with
// iterations of the budget left (Ceres' cost no longer decreasing, the
// engine's LM rejecting its steps):
//  - kProjectedNewton: projected-Newton stages (the trust region on the
//    path Hessian with every element term's Hessian projected onto the
//    positive semidefinite cone, HessianModel::kProjected: a model that is
//    never indefinite, equal to the exact Hessian where the terms are
//    convex), each ended by a tenfold gradient cut
//    (kProjectedStageContraction), a stall or the budget, and followed by
//    an exact Newton probe of the basin (the exact Hessian's quadratic
//    convergence near the geodesic); the phase ends when a round of the two
//    makes no progress (kRoundProgress, kRoundEnergyProgress);
//  - kLevenbergMarquardt: the solve ends there.
// A solve that converges before does not depend on the choice. (As the
// stage after the first failed attempt, or instead of LM alone, projected
// Newton made no corpus case converge that failed, and made the
// triceratops bent by 75 degrees fail where LM alone converges in 13
// iterations.)
enum class GeodesicGlobalisation { kProjectedNewton, kLevenbergMarquardt };

// A round of the projected phase (a projected-Newton stage and an exact
// probe) that leaves the gradient max norm above kRoundProgress times its
// value at the round's start and E_K above (1 - kRoundEnergyProgress) times
// its value ends the solve: neither method makes progress, and the result
// says so (GeodesicResult::stall).
inline constexpr double kRoundProgress = 0.5;
inline constexpr double kRoundEnergyProgress = 1e-4;

// A projected-Newton stage ends once the gradient max norm is this fraction
// of the one it received (or at the tolerance), and an exact Newton probe
// follows.
inline constexpr double kProjectedStageContraction = 0.1;

// The step limit of every stage run by the engine (PathNewtonSettings::
// min_area_fraction): no trial keeps less than this fraction of a
// triangle's area in the current path, or turns it over.
inline constexpr double kStepMinAreaFraction = 0.1;

// The ratio rho (actual / predicted decrease) below which a Newton step
// taken after an early hand-over (GeodesicInput::newton_contraction) shows
// that Newton's basin is not reached yet (NewtonSettings::tr_basin_ratio).
inline constexpr double kNewtonBasinRatio = 0.5;

struct GeodesicInput {
  // The geodesic of `steps` steps from `start` to `end`, other fields at
  // their defaults.
  static GeodesicInput Between(const Positions& start, const Positions& end,
                               int steps) {
    GeodesicInput input;
    input.start = start;
    input.end = end;
    input.steps = steps;
    return input;
  }

  Positions start, end;
  int steps = 8;                    // K >= 1
  std::vector<int> fixed_vertices;  // Dirichlet mask (may be empty)
  // Optional K + 1 shapes; else the path of `init`
  // (MakeGeodesicInitialPath, with the solve's settings for its LΘA
  // reconstructions).
  ShellPath initial;
  GeodesicInit init = GeodesicInit::kAuto;
  // Without a mask: pin the rigid gauge of each inner shape (true), or leave
  // it free for LM's damping to handle (false; for tests of gauge
  // independence).
  bool pin_gauge = true;
  // LM (Gauss-Newton) hands over to Newton's method (path_newton.h) once the
  // gradient has dropped to newton_from times the initial one: Gauss-Newton
  // converges only linearly near a geodesic. If Newton stops short of the
  // tolerance (Hessian not positive definite: not yet in its basin), LM
  // continues to a ten times smaller gradient and Newton tries again, at
  // most kMaxNewtonAttempts times; then LM alone (and, with
  // GeodesicGlobalisation::kProjectedNewton, projected Newton where LM
  // stops short). 0 disables Newton, exact and projected: LM alone.
  double newton_from = 1e-3;
  // Newton also takes over earlier, on the first attempt, after an LM step
  // of the library's engine (GeodesicLm) that divided the gradient by at
  // least newton_contraction (NewtonSettings::hand_over_contraction: a
  // Gauss-Newton step that good leaves little for the exact Hessian to
  // add). On a problem that is nearly quadratic from the start -- the
  // cactus 10-ring, K = 8: 0.061 -> 0.0043 in its first LM step -- this
  // saves the LM steps down to newton_from; where the rule hands over too
  // early, Newton stops short and LM continues as above. 0: off.
  double newton_contraction = 10;
  // The linear solver of the Newton steps (path_newton.h; kAuto: by size).
  PathLinearSolver linear_solver = PathLinearSolver::kAuto;
  static constexpr int kMaxNewtonAttempts = 3;
  // Who runs the LM stages (GeodesicLm).
  GeodesicLm lm = GeodesicLm::kAuto;
  GeodesicNewton newton = GeodesicNewton::kTrustRegion;
  GeodesicGlobalisation globalisation =
      GeodesicGlobalisation::kProjectedNewton;
  // PathNewtonSettings::keep_best_iterate of every stage the engine runs
  // (false only to show what the rule prevents).
  bool keep_best_iterate = true;
  // After an exact Newton attempt that stops short, and before each round
  // of the projected phase, a sweep of RelaxPeakVertices
  // (vertex_relaxation.h) moves the vertices that hold the gradient, each
  // alone (false only to show what it changes).
  bool relax_peak_vertices = true;
  // Nonlinear elimination of the stiff vertices (stiff_vertex_elimination.h)
  // in every trial of the engine's stages: the vertices of the start's
  // triangles with an angle below kStiffAngleDegrees, unless they are more
  // than kMaxStiffFraction of the vertices (false only to show what it
  // changes).
  bool eliminate_stiff_vertices = true;
  // The gradient max norm g_0 that the relative tolerance refers to
  // (stop at |grad| <= tolerance * max(1, g_0)); negative: the initial
  // path's. A solve started from a prolongated coarse solution passes the
  // gradient at the fine level's own initial path (PathGradientNorm of
  // MakeGeodesicInitialPath's path), so that it stops where a solve from
  // that path would.
  double reference_gradient = -1;
};

// max |grad E_K| over the free coordinates at the linear path from
// input.start to input.end (with input's mask or gauge): the g_0 of a solve
// from the linear path.
double LinearPathGradient(const ShellSpace& space, const GeodesicInput& input);

// max |grad E_K| over the free coordinates at `path` (K + 1 shapes, with
// input's mask or gauge): the g_0 of a solve started from `path`; 0 if an
// element is degenerate.
double PathGradientNorm(const ShellSpace& space, const GeodesicInput& input,
                        const ShellPath& path, int threads);

// The round-off floor of that gradient at `path`: the largest max norm (as
// above) of its change when every free coordinate of the inner shapes is
// moved by one unit in the last place, up or down, over kRoundOffProbes
// fixed sign patterns (the same digits on every run). A gradient below it
// cannot be told from zero in double precision: rounding the positions
// once changes it by that much (a sliver triangle, stiff in its short
// direction, raises it by orders of magnitude).
inline constexpr int kRoundOffProbes = 3;
double GradientRoundOff(const ShellSpace& space, const GeodesicInput& input,
                        const ShellPath& path, int threads);

// One stage of a geodesic solve: an LM run or a Newton polish, in the order
// they ran.
struct GeodesicStage {
  // kVertexRelaxation: one sweep of RelaxPeakVertices (vertex_relaxation.h);
  // its iterations are the vertices it moved.
  enum class Method {
    kLevenbergMarquardt,
    kNewton,
    kProjectedNewton,
    kVertexRelaxation
  };
  Method method = Method::kLevenbergMarquardt;
  int iterations = 0;         // LM iterations (not Ceres' iteration 0) or
                              // accepted Newton steps
  double final_gradient = 0;  // max |grad E_K| at its end
  std::string termination;    // Ceres' termination type or Newton's reason
  // What ran: "ceres" (Ceres' LM) or the engine's linear solver
  // ("block-jacobi", "direct") for engine LM and Newton stages.
  std::string solver;
  // The stage ended on an earlier iterate than its last, with a smaller
  // gradient (PathNewtonSettings::keep_best_iterate).
  bool restored_best = false;
};

// An LM stage of the engine that resumes after a Newton stage stopped short
// (a probe or an attempt), with another attempt to follow, stops once its
// gradient max norm has not halved in this many steps (stalled: the
// Gauss-Newton model no longer explains the problem, as next to a sliver
// the step limit holds back) and the attempt comes at once; where Newton
// stops short, LM goes on down to a ten times smaller threshold as after
// any failed attempt. The first LM stage runs to its threshold as before
// (on the triceratops twisted by 180 degrees of the stress corpus a stall
// hand-over there cost 29 more steps).
inline constexpr int kLmStallSteps = 20;

// RelaxPeakVertices as a stage of the geodesic solve: the vertices whose
// gradient max norm is at least this fraction of the path's largest, each
// at most kRelaxationNewtonSteps local Newton steps.
inline constexpr double kRelaxationFraction = 0.1;
inline constexpr int kRelaxationNewtonSteps = 10;

// An exact Newton attempt between LM stages (trust region on the exact,
// possibly indefinite Hessian) ends as stalled once its gradient max norm
// has not halved in this many accepted steps: in Newton's basin each step
// at least halves it, so such a stage is not in the basin, and its steps
// along negative curvature would spend the budget (and the time limit) at
// up to 4 x 8 steps per attempt. LM resumes from its last iterate.
inline constexpr int kNewtonStallSteps = 8;

// A discrete geodesic has (nearly) equal step energies W[s_{k-1}, s_k]
// (docs/math.md, "Path energy and discrete geodesics": E_K = K sum_k W is
// minimal among paths of equal length at constant speed). A result whose
// largest step energy exceeds this factor times the smallest is flagged
// (GeodesicResult::uneven_steps): a local minimiser passing through a fold or a
// mirrored shape, or a path far from converged.
inline constexpr double kUnevenStepEnergyRatio = 2.0;

// A triangle of an inner shape whose area is below this fraction of its area
// in the start shape is reported (GeodesicResult::collapsing_faces): the
// path passes (nearly) through a degenerate triangle, where the bending
// term's normals turn over and Newton and LM crawl -- on the faces at
// relative eta 0.01 a sliver (reference angles down to 0.65 degrees)
// reaches area 0 at k = 4.
inline constexpr double kCollapsingFaceAreaRatio = 1e-3;

// The smallest area ratio |f(s_k)| / |f(s_0)| over the faces f and the
// inner shapes s_1..s_{K-1} of `path` (1 if there are none), and where.
struct FaceAreaRatio {
  double ratio = 1;
  int shape = -1, face = -1;
};
FaceAreaRatio SmallestFaceAreaRatio(const Faces& faces, const ShellPath& path);

// Where the gradient of E_K is largest on a path: the inner shape k and
// vertex v whose |G_k(v)|_inf (G_k = dE_K/ds_k, 3 coordinates) is the
// largest over the vertices a mask leaves free, and that value (-1 / 0 when
// the path has no inner shape or an element is degenerate). Tells where an
// unconverged solve is held back.
struct GradientPeak {
  double value = 0;
  int shape = -1, vertex = -1;
};
GradientPeak LargestPathGradient(const ShellSpace& space,
                                 const std::vector<int>& fixed_vertices,
                                 const ShellPath& path, int threads);

// max_k W_k / min_k W_k of step energies (1 for fewer than two steps; +inf
// if the smallest is 0 and the largest is not).
double StepEnergyRatio(const std::vector<double>& step_energies);

struct GeodesicResult {
  ShellPath path;                     // s_0 = start ... s_K = end
  // How the initial path was made (used == kLinear and reason "given" when
  // GeodesicInput::initial was given).
  InitialPathReport init;
  double path_energy = 0;             // E_K
  std::vector<double> step_energies;  // W[s_{k-1}, s_k]
  ceres::Solver::Summary summary;     // the last Ceres LM stage (if any)
  // Not empty if an LM stage could not run at all (Ceres' FAILURE, or the
  // engine's degenerate start): what happened.
  std::string failure;
  // Not empty if the solve ended because neither the projected-Newton
  // stages nor the exact probes made progress (kRoundProgress): one line.
  std::string stall;
  // Unconverged, or converged at the gradient's round-off, the solve
  // reports the path with the smallest gradient max norm it met after a
  // stage, not its last one.
  bool best_iterate_restored = false;
  PathNewtonReport newton;            // the Newton stage(s), summed
  std::vector<GeodesicStage> stages;  // every stage, in order
  // The stiff vertices eliminated in the engine's trials (0: none, or
  // elimination off) and the Newton steps of those elimination solves,
  // summed over all trials (inner iterations, like CG's: not in
  // `iterations`).
  int stiff_vertices = 0;
  int elimination_newton_steps = 0;
  int iterations = 0;           // sum of stages[i].iterations (LM + Newton)
  double initial_gradient = 0;  // max |grad E_K| (free coords), initial path
  double final_gradient = 0;    // max |grad E_K| (free coords), result
  // The absolute gradient target gradient_tolerance * max(1, g_0).
  double gradient_target = 0;
  // The stopping criterion was met: final_gradient <= gradient_target (the
  // relative gradient criterion; docs/math.md, "Path energy and discrete
  // geodesics"), or, where no stage makes progress any more (`stall`),
  // final_gradient <= gradient_round_off: the target is below what double
  // precision can resolve (converged_at_round_off). Ceres' function- or
  // parameter-tolerance convergence of an LM stage does not count: LM stops
  // there on a cost that no longer decreases, not at a geodesic. True for
  // K = 1 (no unknowns).
  bool converged = false;
  // Measured when the solve stalls (else 0): GradientRoundOff of the path.
  double gradient_round_off = 0;
  bool converged_at_round_off = false;
  // max / min of step_energies and whether it exceeds
  // kUnevenStepEnergyRatio.
  double step_energy_ratio = 1;
  bool uneven_steps = false;
  // SmallestFaceAreaRatio of the path and whether it is below
  // kCollapsingFaceAreaRatio.
  FaceAreaRatio smallest_face_area;
  bool collapsing_faces = false;
  // LargestPathGradient of the result's path.
  GradientPeak gradient_peak;
};

// Geodesic interpolation: minimises E_K over s_1..s_{K-1} by sparse LM
// followed by Newton (see GeodesicInput::newton_from; the LM stages by Ceres
// or by the Newton engine, GeodesicInput::lm; after the engine's LM the
// Newton finish is the engine's trust region on the exact Hessian, at most
// 4 PathNewtonSettings::max_steps steps per attempt). settings.max_iterations
// caps the iterations of this solve: LM iterations plus Newton steps, summed
// over all stages (each Newton attempt also at most
// PathNewtonSettings::max_steps, at most GeodesicInput::kMaxNewtonAttempts
// attempts). Each
// W[s_{k-1}, s_k] adds its membrane and bending residuals scaled by sqrt(K);
// the end shapes are data. With a mask the listed vertices stay at their
// initial (linearly interpolated) positions in every shape; without one the
// rigid motions of every inner shape are pinned (rigid_gauge.h) at three
// vertices of the initial path (Ceres' LM) or removed by the rigid-gauge
// basis of each shape (the engine's stages and the Newton finish).
// The engine's stages run in the space renumbered for memory locality
// (RenumberForLocality, shell_space_renumbering.h; the path is mapped back,
// the gauge pinned at the caller's vertices): the result is the caller's
// numbering's to round-off, and a degenerate element they report is named
// by the caller's face, edge and vertex ids (the first in the renumbered
// order where several are).
GeodesicResult SolveGeodesic(const ShellSpace& space,
                             const GeodesicInput& input,
                             const SolverSettings& settings);

// argmin_s weight_a W[a, s] + weight_b W[s, b] from `initial`, with the
// vertices in `fixed_vertices` held at their initial positions (gauge pinned
// if there are none). (1, 1) is the geodesic midpoint of a and b;
// (1 - lambda, lambda) the convex geodesic combination.
Positions SolveWeightedMidpoint(const ShellSpace& space, const Positions& a,
                                const Positions& b, double weight_a,
                                double weight_b, const Positions& initial,
                                const std::vector<int>& fixed_vertices,
                                const SolverSettings& settings,
                                ceres::Solver::Summary* summary = nullptr);

// The shape at time t in [0, 1] on a discrete geodesic with K + 1 shapes:
// with k = floor(t K), lambda = t K - k, the convex geodesic combination
// argmin_s (1 - lambda) W[s_k, s] + lambda W[s, s_{k+1}] (s_k itself when
// lambda = 0).
Positions GeodesicAtTime(const ShellSpace& space, const ShellPath& path,
                         double t, const std::vector<int>& fixed_vertices,
                         const SolverSettings& settings);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_GEODESIC_H_
