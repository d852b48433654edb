// The shared gflags variables. Their meanings are per verb: see each verb's
// FlagTable (`shellspace VERB --help`); the text here is only gflags' own.
#include "tools/run/common_flags.h"

#include "shellspace/cost_functions/shell/relative_bending_weight.h"

#define SHELLSPACE_PER_VERB "see `shellspace VERB --help`"

DEFINE_string(output, "", SHELLSPACE_PER_VERB);
DEFINE_bool(json, false, SHELLSPACE_PER_VERB);
DEFINE_bool(quiet, false, SHELLSPACE_PER_VERB);
DEFINE_double(epsilon, 1.0, SHELLSPACE_PER_VERB);
DEFINE_double(width, 0, SHELLSPACE_PER_VERB);
DEFINE_double(height, 0, SHELLSPACE_PER_VERB);
DEFINE_double(mu, 1.0, SHELLSPACE_PER_VERB);
DEFINE_double(lambda, 1.0, SHELLSPACE_PER_VERB);
// -1: not given (eta is then relative_eta x the reference's area; a given
// --eta must be >= 0).
DEFINE_double(eta, -1, SHELLSPACE_PER_VERB);
DEFINE_double(relative_eta, shellspace::kDefaultRelativeEta,
              SHELLSPACE_PER_VERB);
DEFINE_string(bending, "discrete-shells", SHELLSPACE_PER_VERB);
DEFINE_string(membrane, "neo-hookean", SHELLSPACE_PER_VERB);
DEFINE_string(png, "", SHELLSPACE_PER_VERB);
DEFINE_string(gltf, "", SHELLSPACE_PER_VERB);
DEFINE_string(html, "", SHELLSPACE_PER_VERB);
DEFINE_string(reference, "", SHELLSPACE_PER_VERB);
DEFINE_string(mask, "", SHELLSPACE_PER_VERB);
DEFINE_int32(steps, 8, SHELLSPACE_PER_VERB);
DEFINE_double(tolerance, 1e-8, SHELLSPACE_PER_VERB);
DEFINE_int32(max_iterations, 200, SHELLSPACE_PER_VERB);
DEFINE_int32(threads, 2, SHELLSPACE_PER_VERB);
DEFINE_bool(report, false, SHELLSPACE_PER_VERB);
DEFINE_string(start, "", SHELLSPACE_PER_VERB);
DEFINE_string(end, "", SHELLSPACE_PER_VERB);
DEFINE_string(inputs, "", SHELLSPACE_PER_VERB);
DEFINE_string(at, "", SHELLSPACE_PER_VERB);
DEFINE_string(init, "", SHELLSPACE_PER_VERB);  // each verb sets its default
DEFINE_string(multires, "auto", SHELLSPACE_PER_VERB);
DEFINE_string(linear_solver, "auto", SHELLSPACE_PER_VERB);
DEFINE_string(lm, "auto", SHELLSPACE_PER_VERB);
DEFINE_double(time_limit, 0, SHELLSPACE_PER_VERB);
