// Nonlinear elimination of the stiff vertices of a path (docs/math.md,
// "Stiff vertices: nonlinear elimination").
//
// Why: a cap (an angle near 180 degrees) or a needle (an angle near 0) of the
// input has a height h that is a tiny fraction of its edges. Its energy
// changes on the scale of h: moving its apex by h doubles or crushes it. On
// such a mesh the path gradient of a global iterate sits almost entirely on
// the few vertices of these triangles (on a 13k-vertex mannequin bent by 75
// degrees: |G| 1.8e5 on three vertices of a fan of caps, 14 anywhere else),
// and a global step -- LM or trust-region Newton over all (K - 1) x 3n
// coordinates -- is held by them to a length at which its quadratic model
// explains their energy. The rest of the path then crawls.
//
// Nonlinear elimination (Cai and Keyes' nonlinearly preconditioned Newton):
// after every global trial step the stiff vertices of all inner shapes are
// brought back to equilibrium by a small Newton solve of their own, the rest
// of the path held. The global merit is measured there, so the global model
// needs to explain only the soft part. At a stationary path the stiff
// vertices are already in equilibrium and the solve does nothing: the
// solution and the convergence test are those of E_K itself.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_STIFF_VERTEX_ELIMINATION_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_STIFF_VERTEX_ELIMINATION_H_

#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/problems/calculus/shell_path.h"

namespace shellspace {

// A triangle with an angle below this (degrees) makes its vertices stiff
// (FindStiffVertices).
inline constexpr double kStiffAngleDegrees = 2.0;

// Elimination is off when more than this fraction of the vertices is stiff:
// the stiff part is then the problem itself, which the global solve owns.
inline constexpr double kMaxStiffFraction = 0.05;

// The face rings of the sub-space (StiffVertexElimination): the widest
// stencil of a stiff vertex's elements, a shape-operator element of a face
// next to one holding the vertex, reaches its own neighbours: three rings.
inline constexpr int kEliminationFaceRings = 3;

// Newton steps of one elimination solve.
inline constexpr int kEliminationNewtonSteps = 8;

// The vertices of `shape` (#V x 3, faces `faces`) that lie on a triangle
// with an angle below `degrees`, in increasing order, without those in
// `fixed` (increasing).
std::vector<int> FindStiffVertices(const Faces& faces, const Positions& shape,
                                   const std::vector<int>& fixed,
                                   double degrees);

struct StiffEliminationReport {
  int steps = 0;               // accepted Newton steps
  double gradient_before = 0;  // max |G| over the stiff coordinates
  double gradient_after = 0;
  bool solved = false;  // the solve ran (a feasible start)
};

// The elimination solve of one space and one set of stiff vertices.
//
// The sub-space: the faces within kEliminationFaceRings face rings of the
// stiff vertices
// (a face is in ring 1 if it has a stiff vertex, in ring r + 1 if it shares
// an edge with a face of ring r). Every element whose stencil holds a stiff
// vertex -- a membrane element (one face), a Discrete-Shells hinge (two
// faces) or a shape-operator element (a face and its three neighbours) --
// is the same element there as in the whole space, so E_K of the sub-space
// differs from E_K of the whole by a constant in the stiff coordinates and
// has the same gradient and Hessian in them.
class StiffVertexElimination {
 public:
  StiffVertexElimination() = default;
  // `stiff`: vertices of `space` (increasing), none fixed by the caller.
  // `min_area_fraction`: the step limit of the solve's trials
  // (PathNewtonSettings::min_area_fraction). `rings`: the face rings of the
  // sub-space (fewer than kEliminationFaceRings only to show that they are
  // needed).
  StiffVertexElimination(const ShellSpace& space,
                         const std::vector<int>& stiff,
                         double min_area_fraction,
                         int rings = kEliminationFaceRings);

  bool empty() const { return stiff_.empty(); }
  const std::vector<int>& stiff_vertices() const { return stiff_; }
  int sub_space_faces() const {
    return static_cast<int>(sub_space_.faces.rows());
  }

  // Trust-region Newton on the exact Hessian, direct solves, on the stiff
  // vertices of the inner shapes of `path` (K + 1 shapes of the whole
  // space), every other vertex held: at most `max_steps` steps, down to a
  // gradient max norm `tolerance` over the stiff coordinates. E_K never
  // rises; only the stiff vertices' rows of the inner shapes change. A start
  // with a degenerate element leaves the path as it is (solved false).
  StiffEliminationReport Solve(int max_steps, double tolerance,
                               ShellPath* path);
  // The accepted Newton steps of every Solve so far, summed.
  int newton_steps() const { return newton_steps_; }

 private:
  std::vector<int> stiff_;        // whole-space ids
  double min_area_fraction_ = 0;
  ShellSpace sub_space_;
  std::vector<int> whole_of_;     // sub-space vertex -> whole-space vertex
  std::vector<int> sub_fixed_;    // sub-space vertices held (not stiff)
  std::vector<int> sub_stiff_;    // sub-space ids of stiff_, same order
  int newton_steps_ = 0;
};

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_STIFF_VERTEX_ELIMINATION_H_
