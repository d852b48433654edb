// The elastic (Frechet-type) mean of shells (docs/math.md, "Elastic mean and
// shell PCA"): s_bar = argmin_s sum_i W[S_i, s], the inputs as references.
#ifndef SHELLSPACE_PROBLEMS_STATISTICS_ELASTIC_MEAN_H_
#define SHELLSPACE_PROBLEMS_STATISTICS_ELASTIC_MEAN_H_

#include <ceres/solver.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {

// Checks that `shapes` is non-empty and that every shape has
// space.num_vertices finite rows; throws InputError otherwise. `what` names
// the shapes in the message.
void CheckShapeSet(const ShellSpace& space,
                   const std::vector<Positions>& shapes, const char* what);

// The vertex average (1/n) sum_i A_i(S_i) of the inputs after rigid alignment
// A_i = AlignRigidly(., S_1) of each to the first one. The initial guess of
// the elastic mean; equivariant under rigid motions of the inputs (moving S_1
// moves the average with it, moving S_i, i > 1, leaves it unchanged).
Positions AlignedVertexAverage(const std::vector<Positions>& shapes);

// The Newton finish of the elastic mean. LM on the sum of squares
// sum_i W[S_i, s] = 1/2 sum r^2 is Gauss-Newton in the limit: it neglects
// sum_k r_k D^2 r_k, which does not vanish at the mean (the residuals of
// W[S_i, s_bar] are not zero), so its tail converges only linearly. Once the
// relative gradient |G|_inf / max(1, |G(s_0)|_inf) is below
// `switch_tolerance`, or after `lm_chunk_iterations` LM iterations (LM
// stalls far out on the cactus: relative gradient 3e-2 after 100
// iterations), or when LM stops for any other reason, Newton's method on
//   G(s) = sum_i D_2 W[S_i, s] = 0,  H(s) = sum_i D_2^2 W[S_i, s]
// takes over: H p = -G solved modulo rigid motions (H assembled by
// PathHessianAssembler::AssembleDeformedSum on RigidGaugeBasis, factorised by
// ReusableCholesky; the iteration is SolveNewton, solvers/newton_solver.h,
// in minimisation mode), s <- s + t p with t the first of 1, 1/2, ..., 1/16 that either satisfies
// Armijo's condition E(s + t p) <= E(s) + 1e-4 t G . p on E = sum_i W[S_i, .]
// or lowers |G|_2 (near the mean the energy decrease is below round-off and
// |G| decides; farther out, on the faces, the full step lowers E but first
// raises |G|), never one that raises E beyond round-off (1e-10 |E|).
// Globalisation: if the reduced H is singular, p is not a descent direction
// (G . p >= 0: H is not positive definite along G), or no t is accepted, the
// step of H + lambda I is tried, lambda = 1e-3, 1e-2, ... times mean
// |diag H|, up to 6 times (NewtonSettings::max_shifts). Safeguard: if even
// that gives no accepted step, Newton stops and another LM chunk (now aiming at the final
// target) runs from the current s, then Newton again (at most
// `max_newton_attempts` times, then LM alone), until Newton reaches
// settings.gradient_tolerance * max(1, |G(s_0)|_inf) (the target of the LM-only
// solve) or settings.max_iterations iterations (LM iterations plus Newton
// steps) are spent.
struct ElasticMeanOptions {
  bool newton = true;              // false: LM only (the previous behaviour)
  double switch_tolerance = 1e-4;  // relative gradient at the hand-over
  int lm_chunk_iterations = 25;    // LM iterations before a Newton attempt
  int max_newton_iterations = 10;  // per attempt
  int max_newton_attempts = 4;     // then LM alone for the rest
};

struct ElasticMeanResult {
  Positions mean;                  // s_bar, rigidly aligned to the first input
  double energy = 0;               // sum_i W[S_i, s_bar]
  std::vector<double> energies;    // W[S_i, s_bar]
  ceres::Solver::Summary summary;  // the first LM solve (chunk)
  int lm_iterations = 0;           // LM iterations, all solves (without
                                   // Ceres' iteration 0, the evaluation)
  int newton_iterations = 0;       // accepted Newton steps
  bool newton_fell_back = false;   // a Newton attempt was stopped
  double initial_gradient_norm = 0;  // |G(s_0)|_inf
  double gradient_norm = 0;          // |G(s_bar)|_inf, G = sum_i D_2 W
  // |G(s_bar)|_inf <= settings.gradient_tolerance * max(1, |G(s_0)|_inf)
  // (the target of the LM solves) and the solves usable.
  bool converged = false;
  double gradient_target = 0;  // settings.gradient_tolerance * max(1, |G(s_0)|)
  // Why it stopped: "converged", "max iterations" (settings.max_iterations
  // LM iterations + Newton steps spent), "LM failed", "Newton: <stop reason>" (the last
  // Newton attempt's, when LM had stopped on its own test).
  std::string termination;
};

// s_bar = argmin_s sum_i W[S_i, s] by sparse LM: every W[S_i, s] adds its
// membrane and bending residuals with S_i as fixed data, s is the variable;
// the rigid gauge of s is pinned (problems/rigid_gauge.h). Then (if
// options.newton) the Newton finish of ElasticMeanOptions. Starts from
// `initial` if given (same vertex count), else from
// AlignedVertexAverage(shapes). The result is aligned rigidly to shapes[0]
// (W is invariant under rigid motions of either argument). Throws InputError
// on an empty or inconsistent input set.
ElasticMeanResult ComputeElasticMean(const ShellSpace& space,
                                     const std::vector<Positions>& shapes,
                                     const SolverSettings& settings,
                                     const Positions* initial = nullptr,
                                     const ElasticMeanOptions& options = {});

// G(s) = sum_i D_2 W[S_i, s] (3n, vertex-major): the gradient of the
// elastic-mean energy. Throws InputError if s has a degenerate triangle.
Eigen::VectorXd ElasticMeanGradient(const ShellSpace& space,
                                    const std::vector<Positions>& shapes,
                                    const Positions& s);

// The median of `values` (the mean of the two middle ones for an even
// count); NaN for none.
double Median(std::vector<double> values);

// Inputs far from the others: the indices i with W[S_i, s_bar] > factor *
// Median_j W[S_j, s_bar] (energies as ElasticMeanResult::energies), in
// increasing order; none for fewer than 3 inputs or a zero median. A lone
// far input dominates the mean's energy and the leading PCA mode; on the
// cactus, cactus8 (a folded patch) has W = 2.07 against a median of 0.045.
std::vector<int> FarInputs(const std::vector<double>& energies,
                           double factor = 10.0);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_STATISTICS_ELASTIC_MEAN_H_
