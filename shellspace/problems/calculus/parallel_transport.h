// Parallel transport (docs/math.md, "Parallel transport (Schild's ladder)").
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_PARALLEL_TRANSPORT_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_PARALLEL_TRANSPORT_H_

#include <vector>

#include "shellspace/problems/calculus/exponential_map.h"

namespace shellspace {

struct TransportResult {
  std::vector<Positions> variations;  // xi_0 .. xi_K
  // p_k = s_k + eps xi_k; fewer than the path's shapes if settings.stop
  // ended the transport (the rungs completed before it).
  std::vector<Positions> shapes;
  // Per rung k = 1..K: max |F| of the EXP step's Euler-Lagrange residual at
  // p_k relative to max |D_2 W[s_{k-1}, m_k]| (0: solved exactly). Thin
  // shells make the EXP step badly conditioned; a large value says the rung
  // was not solved.
  std::vector<double> exp_residuals;
  // Per rung k = 1..K ([k - 1]): how the rung was solved.
  struct Rung {
    bool solved = false;  // its EXP step reached kExpStepAcceptance
    double relative_residual = 0;  // the EXP step's (ExpStepResult)
    ExpStepResult::Method method = ExpStepResult::Method::kNewton;
    // 1: the rung at epsilon; n > 1: at epsilon / n, scaled back
    // (sub-stepping, see ParallelTransport).
    int divisor = 1;
    int newton_steps = 0;   // of the EXP solves of this rung, all tries
    int lm_iterations = 0;
    // The midpoint solves' iterations (LM + Newton, GeodesicResult::
    // iterations), all tries.
    int midpoint_iterations = 0;
  };
  std::vector<Rung> rungs;
  // Every rung of the path solved: false if a rung is unsolved or
  // settings.stop ended the transport before the last rung.
  bool all_solved = true;
};

// A rung whose EXP step has no root at epsilon is retried at epsilon / 2,
// epsilon / 4, ..., at most this many halvings.
inline constexpr int kMaxRungHalvings = 4;

// The LM fallback of a rung's EXP step (after Newton on F failed) runs at
// most this many iterations on every try but the last one (epsilon /
// 2^kMaxRungHalvings), which runs with the full settings: 0, so a failed
// Newton goes straight to the next, smaller sub-step. A root that Newton
// misses is not found by LM on |F|^2 there: on the faces transport (disgust
// - neutral along neutral -> smile) the fallback's 20 capped iterations
// left max |F| where it was on each of rungs 4..8 (16 s a rung), which
// Newton then solved at epsilon / 2.
inline constexpr int kRungFallbackLmIterations = 0;

// Transports the variation xi_0 at s_0 along path (s_0 .. s_K):
// p_0 = s_0 + eps xi_0; for k = 1..K: m_k = geodesic midpoint of (p_{k-1},
// s_k) (argmin W[p_{k-1}, m] + W[m, s_k], solved as the 2-step geodesic by
// SolveGeodesic: LM, then Newton on the exact Hessian, to the relative
// gradient settings.gradient_tolerance); p_k = forward EXP step from
// (s_{k-1}, m_k); xi_k = (p_k - s_k) / eps. eps = 1 transports a finite
// shape difference (detail transfer); small eps the tangent vector.
// `fixed_vertices` are held in the midpoint and EXP problems.
// Sub-stepping: if rung k's EXP step is not solved (no root near the
// initial guesses: the reflection of a large variation), the rung is
// retried with the variation divided by n = 2, 4, ... 2^kMaxRungHalvings:
// p'_{k-1} = s_{k-1} + (p_{k-1} - s_{k-1}) / n, the midpoint and EXP step of
// (p'_{k-1}, s_k) give p'_k, and p_k = s_k + n (p'_k - s_k) (the rung at
// epsilon / n, the transported variation scaled back: for small epsilon the
// same transport to first order). The first solved try is kept, else the
// try with the smallest relative residual (rung unsolved, all_solved
// false).
TransportResult ParallelTransport(const ShellSpace& space,
                                  const ShellPath& path,
                                  const Positions& variation, double epsilon,
                                  const std::vector<int>& fixed_vertices,
                                  const SolverSettings& settings);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_PARALLEL_TRANSPORT_H_
