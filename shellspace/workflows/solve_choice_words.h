// The words of a geodesic solve's choices (the CLI's flag values, the
// Python module's keyword arguments) and the types they stand for: the one
// translator both front ends use. Each parser names the input in its error
// as the caller does (`name`: "--lm" for the CLI, "lm" for Python); the
// workflows take the parsed types.
//   multires       auto | off | LEVELS (0 .. 8)   MultiresolutionChoice
//   linear_solver  auto | direct | block-jacobi   PathLinearSolver
//   lm             auto | ceres | engine          GeodesicLm
//   init           auto | linear | ltheta | rotations  GeodesicInit
#ifndef SHELLSPACE_WORKFLOWS_SOLVE_CHOICE_WORDS_H_
#define SHELLSPACE_WORKFLOWS_SOLVE_CHOICE_WORDS_H_

#include <string>

#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/problems/calculus/path_newton.h"

namespace shellspace {

// "off" (or "0"): no coarse level; a number from 0 to 8: that many;
// "auto": MultiresolutionChoice::Automatic(). Throws InputError starting
// with `name` for anything else.
MultiresolutionChoice ParseMultiresolution(const std::string& value,
                                           const std::string& name);
// "auto", "off" or the number of levels.
std::string MultiresolutionWord(const MultiresolutionChoice& choice);

// PathLinearSolver of "auto", "direct", "block-jacobi". Throws InputError
// starting with `name` for anything else.
PathLinearSolver ParsePathLinearSolver(const std::string& value,
                                       const std::string& name);
std::string PathLinearSolverWord(PathLinearSolver solver);

// GeodesicLm of "auto", "ceres", "engine". Throws InputError starting with
// `name` for anything else.
GeodesicLm ParseGeodesicLm(const std::string& value, const std::string& name);
std::string GeodesicLmWord(GeodesicLm lm);

// GeodesicInit of "auto", "linear", "ltheta", "rotations". Throws
// InputError starting with `name` for anything else.
GeodesicInit ParseGeodesicInit(const std::string& value,
                               const std::string& name);

}  // namespace shellspace

#endif  // SHELLSPACE_WORKFLOWS_SOLVE_CHOICE_WORDS_H_
