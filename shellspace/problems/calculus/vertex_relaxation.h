// Vertex-local relaxation of the path energy E_K (docs/math.md, "Path energy
// and discrete geodesics"): each chosen vertex of an inner shape moves alone,
// by damped Newton on E_K in its own three coordinates, everything else held.
//
// Why: on a mesh with slivers (a triangle whose height is a tiny fraction
// of its edges) or flaps nearly shut, the energy of the few elements at such
// a vertex changes on the scale of that height. A global step -- LM or a
// trust-region Newton step over all (K - 1) x 3n coordinates -- is held to
// the length where their model is good, and the largest entries of the
// gradient sit on those vertices while the rest of the path is nearly
// stationary. A 3 x 3 Newton solve per vertex, with its own line search,
// resolves exactly that local nonlinearity and lowers E_K; the global stages
// then resume from there.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_VERTEX_RELAXATION_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_VERTEX_RELAXATION_H_

#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"

namespace shellspace {

struct VertexRelaxationReport {
  int vertices = 0;      // (shape, vertex) pairs relaxed
  int newton_steps = 0;  // accepted local Newton steps, summed
  double energy_before = 0, energy_after = 0;  // E_K (0: degenerate)
};

// One sweep over the vertices of the inner shapes s_1..s_{K-1} of `path`
// (K + 1 shapes, #V x 3 each) whose gradient G_k(v) = dE_K/dx_k(v) has a
// max norm of at least `fraction` of its largest over the path (vertices of
// `fixed_vertices` excluded). Each moves by at most `max_steps` Newton steps
// on the local energy K (W[s_{k-1}, s_k] + W[s_k, s_{k+1}]) restricted to
// the elements at the vertex (the exact 3 x 3 Hessian, its eigenvalues
// raised to a positive floor where it is not positive definite), each step
// halved until the local energy falls by the Armijo fraction 1e-4 of its
// predicted decrease (a degenerate element counts as an increase). The
// shapes of even k are relaxed (in parallel over k), then those of odd k;
// within a shape the vertices in increasing order: the result does not
// depend on `threads`. E_K never rises.
// Relaxes vertices[k] of each inner shape s_k (k = 1..K-1; entries 0, K
// and any beyond are ignored), in the order given, as RelaxPeakVertices
// does: even k (in parallel), then odd k.
VertexRelaxationReport RelaxVertices(
    const ShellSpace& space, const std::vector<std::vector<int>>& vertices,
    int max_steps, int threads, std::vector<Positions>* path);

VertexRelaxationReport RelaxPeakVertices(const ShellSpace& space,
                                         const std::vector<int>& fixed_vertices,
                                         double fraction, int max_steps,
                                         int threads, std::vector<Positions>* path);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_VERTEX_RELAXATION_H_
