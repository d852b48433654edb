// `shellspace compare`: two shells or two paths of one connectivity against
// each other, up to rigid motion (problems/calculus/shape_comparison.h):
// the check of a downstream test against a pinned reference solution.
#include <gflags/gflags.h>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/problems/calculus/shape_comparison.h"
#include "tools/run/common_flags.h"
#include "tools/run/run_status.h"
#include "tools/run/shell_inputs.h"
#include "tools/verbs/verb.h"

DEFINE_string(a, "", "compare: the first shell or path");
DEFINE_string(b, "", "compare: the second shell or path");
DEFINE_double(energy_tolerance, 1e-6, "compare: relative E_K difference");

namespace shellspace {
namespace {

constexpr char kSide[] =
    "a mesh file (PLY, OBJ, OFF), a path directory (its *.ply, *.obj, *.off "
    "in natural name order) or a comma-separated list of mesh files";

FlagTable CompareFlags() {
  return Flags({{
                    TextFlag("a", std::string("the reference side: ") + kSide)
                        .Required(),
                    TextFlag("b",
                             std::string("the side checked against it, with "
                                         "a's connectivity and frame count: ") +
                                 kSide)
                        .Required(),
                    RealFlag("tolerance",
                             "largest vertex distance after rigid alignment, "
                             "relative to the bounding-box diagonal of a's "
                             "first frame, that still counts as equal",
                             0, End::kClosed)
                        .Default("1e-6"),
                    RealFlag("energy_tolerance",
                             "paths: largest |E_K(a) - E_K(b)| / max(E_K) that "
                             "still counts as equal",
                             0, End::kClosed),
                    TextFlag("quiet", "no lines on stdout"),
                },
                MaterialFlags(), JsonFlag()});
}

int RunCompare() {
  const ShellSet side_a = LoadShellFiles(ListFrameFiles(FLAGS_a));
  const ShellSet side_b = LoadShellFiles(ListFrameFiles(FLAGS_b), &side_a.first);
  const Shell& first_a = side_a.first;
  const ShellPath& a = side_a.shapes;
  const ShellPath& b = side_b.shapes;
  if (a.size() != b.size()) {
    throw InputError("compare: " + FLAGS_a + " has " + std::to_string(a.size()) +
                     " frame(s), " + FLAGS_b + " has " + std::to_string(b.size()));
  }
  const ShellSpace space(first_a.mesh, first_a.topology,
                         MaterialChoiceFromFlags(first_a.mesh).material);
  const ShapeComparison c = CompareShapes(space, a, b);
  const bool paths = a.size() > 1;
  const ComparisonVerdict verdict =
      JudgeComparison(c, FLAGS_tolerance, FLAGS_energy_tolerance);
  if (FLAGS_json) {
    JsonObject json = ComparisonJson(c, FLAGS_tolerance, FLAGS_energy_tolerance);
    std::cout << json.Add("a", FLAGS_a).Add("b", FLAGS_b).str() << "\n";
  } else if (!FLAGS_quiet) {
    std::printf("%zu frame(s): max distance %.6g (%.3g of the diameter %.6g), "
                "mean %.6g\n",
                a.size(), c.max_distance, c.relative_max_distance, c.diameter,
                c.mean_distance);
    if (paths) {
      std::printf("E_K: a %.12g, b %.12g (relative difference %.3g)\n",
                  c.energy_a, c.energy_b, c.relative_energy_difference);
    } else {
      std::printf("W[a, b] = %.12g\n", c.energy_a_to_b);
    }
  }
  if (verdict.agree()) return 0;
  std::string why;
  if (!verdict.shapes_agree) {
    why = "relative max distance " + Short(c.relative_max_distance) + " > " +
          Short(FLAGS_tolerance);
  }
  if (!verdict.energies_agree) {
    why += std::string(why.empty() ? "" : "; ") + "relative E_K difference " +
           Short(c.relative_energy_difference) + " > " +
           Short(FLAGS_energy_tolerance);
  }
  std::fprintf(stderr, "shellspace compare: differ: %s\n", why.c_str());
  return 1;
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "compare",
    "compare --a A --b B [--tolerance 1e-6] [--energy_tolerance 1e-6] [--json] "
    "(A, B: meshes or path directories; exit 0 equal, 1 different or bad input)",
    shellspace::CompareFlags(), shellspace::RunCompare);
