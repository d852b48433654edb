// A path of shells: K + 1 shapes s_0 ... s_K of one mesh, each #V x 3.
#ifndef SHELLSPACE_PROBLEMS_CALCULUS_SHELL_PATH_H_
#define SHELLSPACE_PROBLEMS_CALCULUS_SHELL_PATH_H_

#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

using ShellPath = std::vector<Positions>;

// Linear interpolation of vertex positions: K + 1 shapes from a to b.
ShellPath LinearPath(const Positions& a, const Positions& b, int steps);

}  // namespace shellspace

#endif  // SHELLSPACE_PROBLEMS_CALCULUS_SHELL_PATH_H_
