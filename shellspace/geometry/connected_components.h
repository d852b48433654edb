// The connected components of a triangle mesh's vertices.
#ifndef SHELLSPACE_GEOMETRY_CONNECTED_COMPONENTS_H_
#define SHELLSPACE_GEOMETRY_CONNECTED_COMPONENTS_H_

#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// The vertices 0 .. vertex_count - 1 grouped by the components of the graph
// whose edges are those of `faces` (#F x 3); each group ascending, the
// groups ordered by their least vertex. A vertex in no face is a group of
// its own.
std::vector<std::vector<int>> ConnectedComponents(const Faces& faces,
                                                  int vertex_count);

}  // namespace shellspace

#endif  // SHELLSPACE_GEOMETRY_CONNECTED_COMPONENTS_H_
