// The gflags variables that several verbs read (one binary, so a flag name
// has one definition). What a flag means in a verb, its default there and
// its valid range are in that verb's FlagTable (tools/verbs/verb_flags.h), which
// is also what `shellspace VERB --help` prints; a verb accepts no flag
// outside its table.
#ifndef SHELLSPACE_TOOLS_RUN_COMMON_FLAGS_H_
#define SHELLSPACE_TOOLS_RUN_COMMON_FLAGS_H_

#include <gflags/gflags.h>

DECLARE_string(output);
DECLARE_bool(json);
DECLARE_bool(quiet);
DECLARE_double(epsilon);
DECLARE_double(width);
DECLARE_double(height);
DECLARE_double(mu);
DECLARE_double(lambda);
DECLARE_double(eta);
DECLARE_double(relative_eta);
DECLARE_string(bending);
DECLARE_string(membrane);
DECLARE_string(png);
DECLARE_string(gltf);
DECLARE_string(html);
DECLARE_string(reference);
DECLARE_string(mask);
DECLARE_int32(steps);
DECLARE_double(tolerance);
DECLARE_int32(max_iterations);
DECLARE_int32(threads);
DECLARE_bool(report);
DECLARE_string(start);
DECLARE_string(end);
DECLARE_string(inputs);
DECLARE_string(at);
DECLARE_string(init);
DECLARE_string(multires);
DECLARE_string(linear_solver);
DECLARE_string(lm);
DECLARE_double(time_limit);

#endif  // SHELLSPACE_TOOLS_RUN_COMMON_FLAGS_H_
