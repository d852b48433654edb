#include "shellspace/tools/common_flags.h"

DEFINE_string(output, "", "output file or directory");
DEFINE_bool(json, false, "print a JSON summary on stdout");
DEFINE_bool(quiet, false, "suppress progress output");
DEFINE_double(epsilon, 1.0,
              "transport: step epsilon; branching: twin-boundary energy");
DEFINE_double(width, 0, "render: image width in pixels (0: default)");
DEFINE_double(height, 0,
              "render: image height in pixels (0: default); branching: "
              "domain height H");
DEFINE_double(mu, 1.0, "membrane Lame weight mu (> 0)");
DEFINE_double(lambda, 1.0, "membrane Lame weight lambda (> 0)");
DEFINE_double(eta, 0.01, "bending weight eta (>= 0, squared thickness)");
DEFINE_string(png, "", "also write a PNG film strip of the frames here");
DEFINE_string(reference, "", "reference (undeformed) shell: PLY, OBJ or OFF");
DEFINE_string(mask, "",
              "vertex mask file: one 0-based index per line, '#' comments; "
              "listed vertices are held fixed");
DEFINE_int32(steps, 8, "number of time steps K (the path has K + 1 shapes)");
DEFINE_double(tolerance, 1e-8,
              "stop when the gradient max-norm falls below this fraction of "
              "its initial value");
DEFINE_int32(max_iterations, 200, "maximum Levenberg-Marquardt iterations");
DEFINE_int32(threads, 2, "threads of the Ceres solves (>= 1)");
DEFINE_bool(report, false,
            "print Ceres full solver report (timings) on stderr");
DEFINE_string(start, "", "first shell s_0 of the path");
DEFINE_string(end, "", "last shell s_K of the path");
DEFINE_string(inputs, "", "comma-separated list of input shells");
DEFINE_string(at, "", "comma-separated time indices of the keyframes / inputs");
