// The flags of the verbs that solve geodesics (`geodesic`, `log`) and the
// options of the geodesic workflow (shellspace/workflows/geodesic.h) they
// give.
#ifndef SHELLSPACE_TOOLS_VERBS_GEODESIC_SOLVE_H_
#define SHELLSPACE_TOOLS_VERBS_GEODESIC_SOLVE_H_

#include <string>

#include "shellspace/io/json_writer.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/workflows/solve_choice_words.h"
#include "shellspace/workflows/geodesic.h"
#include "tools/run/run_paths.h"
#include "tools/run/shell_inputs.h"
#include "tools/verbs/verb_flags.h"

namespace shellspace {

// The --multires flag of the verbs that solve geodesics.
FlagSpec MultiresFlag();

// The memory model of a geodesic solve of K steps (GeodesicBytes in
// geometry/memory_limits.h), as named in errors and --help.
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
FlagSpec GeodesicLmFlag();

// --init auto|linear|ltheta (GeodesicInit).
FlagSpec GeodesicInitFlag();

// The input files of the verbs that solve geodesics (--start, --end,
// --mask), to which the verb adds its outputs before RunPaths::Check.
RunPaths GeodesicInputPaths();

// The geodesic workflow's options of the flags of `verb` (geodesic, log):
// --start and --end read and validated, --steps (checked against
// kGeodesicModel's memory estimate first), --mask, the material, the solve
// choices (--multires, --linear_solver, --lm, --init) and the solver flags;
// the sliver warning about --start printed on stderr unless --quiet.
workflows::GeodesicOptions GeodesicOptionsFromFlags(const std::string& verb);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_VERBS_GEODESIC_SOLVE_H_
