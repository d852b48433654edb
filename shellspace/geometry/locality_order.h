// A vertex numbering that keeps neighbours close: Cuthill-McKee's
// breadth-first order. Loops that scatter into per-vertex or per-vertex-pair
// storage (the path Hessian assembler) visit memory in this order instead of
// the mesh file's, whose numbering may put a triangle's vertices thousands
// of entries apart.
#ifndef SHELLSPACE_GEOMETRY_LOCALITY_ORDER_H_
#define SHELLSPACE_GEOMETRY_LOCALITY_ORDER_H_

#include <vector>

namespace shellspace {

// rank[v] = the position of vertex v (0 .. n - 1, n = neighbours.size()) in
// the Cuthill-McKee order of the graph (neighbours[v]: v's neighbours, any
// order, v itself ignored). Each connected component is numbered in one
// block, breadth first from a pseudo-peripheral vertex (the last vertex
// reached by a breadth-first search from the component's vertex of least
// degree), the neighbours of a vertex in increasing degree. The order is a
// deterministic function of the graph: ties go to the lower index. So the
// bandwidth max |rank[v] - rank[w]| over edges is at most about the width of
// the widest breadth-first level (a side of a grid, not the number of
// vertices).
std::vector<int> CuthillMcKeeRanks(
    const std::vector<std::vector<int>>& neighbours);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_LOCALITY_ORDER_H_
