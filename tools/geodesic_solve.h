// The geodesic solve of the `geodesic` and `log` verbs: single level or
// multiresolution by --multires.
#ifndef SHELLSPACE_TOOLS_GEODESIC_SOLVE_H_
#define SHELLSPACE_TOOLS_GEODESIC_SOLVE_H_

#include "shellspace/io/json_writer.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/reports/solve_choices.h"
#include "shellspace/tools/verb_flags.h"

namespace shellspace {

// The --multires flag of the verbs that solve geodesics.
FlagSpec MultiresFlag();

// The multiresolution settings of --multires for a mesh of `num_vertices`:
// "off" (or 0) none; a number, that many coarse levels; "auto" as many
// levels as keep the coarsest at kAutoMinVertices or more (none for meshes
// below 4 kAutoMinVertices). Throws InputError naming --multires for
// anything else.
MultiresolutionSettings MultiresFromFlags(int num_vertices);

// The --linear_solver flag: the linear solver of the Newton finish.
FlagSpec LinearSolverFlag();

// PathLinearSolver of --linear_solver: auto, direct, block-jacobi. Throws
// InputError naming --linear_solver for anything else.
PathLinearSolver LinearSolverFromFlags();

// The name of a PathLinearSolver in --linear_solver's spelling.
const char* LinearSolverName(PathLinearSolver solver);

// SolveGeodesicMultiresolution with those settings (with 0 levels the
// plain single-level solve) and input.linear_solver from --linear_solver.
MultiresolutionResult SolveGeodesicFromFlags(const ShellSpace& space,
                                             const GeodesicInput& input,
                                             const SolverSettings& settings);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_GEODESIC_SOLVE_H_
