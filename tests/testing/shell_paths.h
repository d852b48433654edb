// Paths of shells for the tests of the path solvers: a perturbed linear
// path (no Hessian block vanishes by symmetry) and the distance of two
// paths.
#ifndef SHELLSPACE_TESTS_TESTING_SHELL_PATHS_H_
#define SHELLSPACE_TESTS_TESTING_SHELL_PATHS_H_

#include "shellspace/geometry/mesh.h"
#include "shellspace/problems/calculus/shell_path.h"

namespace shellspace::testing {

// The linear path from a to b in K steps (LinearPath) with every coordinate
// of its inner shapes moved by a uniform random amount in [-amplitude,
// amplitude] (fixed seed), so that no block vanishes by symmetry.
ShellPath PerturbedLinearPath(const Positions& a, const Positions& b, int K,
                              double amplitude, unsigned seed);

// max_k |a_k - b_k| / max_k |b_k| (Frobenius norms of the shapes).
double RelativePathDistance(const ShellPath& a, const ShellPath& b);

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_SHELL_PATHS_H_
