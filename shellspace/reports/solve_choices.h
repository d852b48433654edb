// The choices of a geodesic solve given as words (the CLI's flag values,
// the Python module's keyword arguments): the multiresolution levels
// ("auto", "off" or a number of levels) and the linear solver of the Newton
// finish ("auto", "direct", "block-jacobi") and the solver of the LM stages
// ("auto", "ceres", "engine").
#ifndef SHELLSPACE_REPORTS_SOLVE_CHOICES_H_
#define SHELLSPACE_REPORTS_SOLVE_CHOICES_H_

#include <string>

#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/problems/calculus/path_newton.h"

namespace shellspace {

// Multiresolution below this many vertices per level is not used by "auto".
constexpr int kAutoMinVertices = 2500;

// The settings of `value` for a mesh of `num_vertices`: "off" (or 0) none; a
// number from 0 to 8, that many coarse levels; "auto" as many levels as keep
// the coarsest at kAutoMinVertices or more (none for meshes below
// 4 kAutoMinVertices). Throws InputError starting with `name` (the input's
// name, e.g. the flag) for anything else.
MultiresolutionSettings ParseMultiresolution(const std::string& value,
                                             int num_vertices,
                                             const std::string& name);

// PathLinearSolver of "auto", "direct", "block-jacobi". Throws InputError
// starting with `name` for anything else.
PathLinearSolver ParsePathLinearSolver(const std::string& value,
                                       const std::string& name);

// GeodesicLm of "auto", "ceres", "engine". Throws InputError starting with
// `name` for anything else.
GeodesicLm ParseGeodesicLm(const std::string& value, const std::string& name);

// GeodesicInit of "auto", "linear", "ltheta", "rotations". Throws InputError starting
// with `name` for anything else.
GeodesicInit ParseGeodesicInit(const std::string& value,
                               const std::string& name);

}  // namespace shellspace

#endif  // SHELLSPACE_REPORTS_SOLVE_CHOICES_H_
