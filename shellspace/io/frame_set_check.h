// The check every writer of a whole sequence of shells (a glTF animation, a
// viewer page) makes of its frames before it encodes them.
#ifndef SHELLSPACE_IO_FRAME_SET_CHECK_H_
#define SHELLSPACE_IO_FRAME_SET_CHECK_H_

#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

// At least one frame, every frame with the vertex count of the first and
// only finite coordinates, at least one face and every face index a vertex.
// Throws InputError starting with "WHAT: " otherwise.
void CheckFrameSet(const std::vector<Positions>& frames, const Faces& faces,
                   const std::string& what);

}  // namespace shellspace

#endif  // SHELLSPACE_IO_FRAME_SET_CHECK_H_
