// A ShellSpace renumbered for memory locality: the same shells with the
// vertices in Cuthill-McKee order (geometry/locality_order.h) and the faces
// sorted by their vertices' new numbers, so that an element's vertices, and
// consecutive elements, lie close together in every per-vertex array. A mesh
// file's numbering may put a triangle's vertices thousands of entries apart
// (on the GOAST cactus a median 2,957); a solve that gathers positions,
// scatters gradients and multiplies by the Hessian per element then misses
// the cache on most of them. Solvers run in the renumbered space and map
// their results back (SolveGeodesic); element descriptions still name the
// caller's vertices, faces and interior edges (ElementLabels).
#ifndef SHELLSPACE_COST_FUNCTIONS_SHELL_SHELL_SPACE_RENUMBERING_H_
#define SHELLSPACE_COST_FUNCTIONS_SHELL_SHELL_SPACE_RENUMBERING_H_

#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"

namespace shellspace {

struct RenumberedShellSpace {
  // The renumbered space: face f' is the caller's face original_face[f']
  // with its vertices renamed (same cyclic order, so the same orientation);
  // its elements' descriptions name the caller's ids.
  ShellSpace space;
  std::vector<int> new_vertex;       // [caller's vertex] -> space's vertex
  std::vector<int> original_vertex;  // [space's vertex] -> caller's vertex
  std::vector<int> original_face;    // [space's face] -> caller's face

  // A shape (#V x 3) of the caller's space in the renumbered one: row
  // new_vertex[v] = row v.
  Positions ToRenumbered(const Positions& shape) const;
  // The inverse: row v = row new_vertex[v] of a renumbered shape.
  Positions ToOriginal(const Positions& shape) const;
  // The renumbered ids of the caller's vertices, sorted increasingly.
  std::vector<int> ToRenumbered(const std::vector<int>& vertices) const;
};

// The renumbering of `space`: vertex v gets its rank in CuthillMcKeeRanks of
// the edge graph; faces are sorted by their smallest new vertex, then the
// other two (sorted), ties by the caller's index; the topology is rebuilt
// from the sorted faces (so interior edges come in the order the faces meet
// them). Deterministic: a function of the connectivity only. The element
// set's sums then run in this order, so energies and gradients agree with
// the caller's space's to round-off, not bit for bit.
RenumberedShellSpace RenumberForLocality(const ShellSpace& space);

}  // namespace shellspace

#endif  // SHELLSPACE_COST_FUNCTIONS_SHELL_SHELL_SPACE_RENUMBERING_H_
