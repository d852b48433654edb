// The geodesic solve of the `geodesic` and `log` verbs: single level or
// multiresolution by --multires.
#ifndef SHELLSPACE_TOOLS_VERBS_GEODESIC_SOLVE_H_
#define SHELLSPACE_TOOLS_VERBS_GEODESIC_SOLVE_H_

#include <string>

#include "shellspace/io/json_writer.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/reports/solve_choices.h"
#include "tools/run/run_paths.h"
#include "tools/run/shell_inputs.h"
#include "tools/verbs/verb_flags.h"

namespace shellspace {

// The --multires flag of the verbs that solve geodesics.
FlagSpec MultiresFlag();

// The multiresolution settings of --multires for a mesh of `num_vertices`:
// "off" (or 0) none; a number, that many coarse levels; "auto" as many
// levels as keep the coarsest at kAutoMinVertices or more (none for meshes
// below 4 kAutoMinVertices). Throws InputError naming --multires for
// anything else.
MultiresolutionSettings MultiresFromFlags(int num_vertices);

// The memory model of a geodesic solve of K steps (GeodesicBytes in
// memory_limits.h), as named in errors and --help.
inline constexpr const char* kGeodesicModel = "64 MB + 1500 B x #V x K^2";

// The required --start and --end flags of the verbs that solve geodesics,
// with their meanings in that verb.
FlagTable GeodesicEndsFlags(const std::string& start, const std::string& end);

// The --steps flag of the verbs that solve geodesics: `what` says what K is
// in that verb; the help text adds the bound of kGeodesicModel.
FlagSpec GeodesicStepsFlag(const std::string& what);

// The --linear_solver flag: the linear solver of the Newton finish.
FlagSpec LinearSolverFlag();

// The --lm flag: who runs the LM stages (GeodesicLm).
// --init auto|linear|ltheta (GeodesicInit) and its value.
FlagSpec GeodesicInitFlag();
GeodesicInit GeodesicInitFromFlags();

FlagSpec GeodesicLmFlag();

// PathLinearSolver of --linear_solver: auto, direct, block-jacobi. Throws
// InputError naming --linear_solver for anything else.
PathLinearSolver LinearSolverFromFlags();

// SolveGeodesicMultiresolution with those settings (with 0 levels the
// plain single-level solve) and input.linear_solver from --linear_solver.
MultiresolutionResult SolveGeodesicFromFlags(const ShellSpace& space,
                                             const GeodesicInput& input,
                                             const SolverSettings& settings);

// The input files of the verbs that solve geodesics (--start, --end,
// --mask), to which the verb adds its outputs before RunPaths::Check.
RunPaths GeodesicInputPaths();

// The geodesic of the flags of `verb` (geodesic, log): --start, --end,
// --steps (checked against kGeodesicModel's memory estimate first), --mask,
// the material and the solver flags.
struct GeodesicOfFlags {
  Shell start;
  ShellSpace space;  // of start, with the flags' material
  MultiresolutionResult multires;
};
GeodesicOfFlags SolveGeodesicOfFlags(const std::string& verb);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_VERBS_GEODESIC_SOLVE_H_
