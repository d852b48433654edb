// `shellspace branching simulate|construct [flags]`: the branching problem
// (docs/math.md, "Branching: the Kohn–Müller model"). Each sub-command is a
// verb ("branching simulate", "branching construct") with its own flags.
//
//   simulate  — relaxed diffuse-interface simulation on a graded grid (sparse
//               LM, continuation in delta); writes DIR/u.csv, DIR/uy.png,
//               DIR/interfaces.csv, DIR/summary.json.
//   construct — the reduced sharp-interface model: the KM (psi-junction),
//               needle (T2) or lens self-similar construction, optionally
//               optimised, or the general optimiser (--family general
//               [--search]); writes DIR/pattern.png and DIR/summary.json
//               (general: also DIR/pattern.txt, the knots).
//
// --epsilon here is the twin-boundary energy (default 1e-3), not the step of
// `transport`; --height is the domain height H.
#include <gflags/gflags.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/problems/branching/km_family.h"
#include "shellspace/problems/branching/simulation.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/png_writer.h"
#include "shellspace/render/branching_image.h"
#include "shellspace/workflows/branching.h"
#include "tools/run/common_flags.h"
#include "tools/run/run_output.h"
#include "tools/run/run_paths.h"
#include "tools/run/run_status.h"
#include "tools/run/stop_request.h"
#include "shellspace/io/json_writer.h"
#include "tools/verbs/verb.h"

DEFINE_double(length, 1.0, "branching: domain length L");
DEFINE_int32(nx, 64, "branching simulate: number of x-cells");
DEFINE_int32(ny, 128, "branching simulate: number of y-nodes (periodic)");
DEFINE_double(delta, 0.0,
              "branching simulate: interface width (0: 3 H/ny, the rule "
              "dy = delta/3)");
DEFINE_double(grading, 2.0,
              "branching simulate: x-grading exponent, x_i = L (i/nx)^g");
DEFINE_int32(continuation, 3,
             "branching simulate: continuation stages in delta (factor 2)");
DEFINE_int32(periods, 0,
             "branching simulate: periods of the initial pattern in H (0: "
             "nearest to the optimal KM period)");
DEFINE_int32(init_seed, 1, "branching simulate: seed of --init random");
DEFINE_int32(lm_iterations, 200,
             "branching simulate: LM iterations per continuation stage");
DEFINE_int32(delta_extrapolation, 0,
             "branching simulate: >= 2: also run widths delta, delta/r, .. "
             "(this many, r = 2^(1/2)) and fit the constant as delta -> 0");
DEFINE_string(family, "km",
              "branching construct: km (psi-junction) | needle (T2) | lens | "
              "general (reduced sharp-interface optimiser)");
DEFINE_bool(search, false,
            "branching construct --family general: multi-start search over "
            "topologies (else one solve of the lens topology)");
DEFINE_string(search_ratios, "2,3,4",
              "branching construct --search: refinement ratios r");
DEFINE_int32(search_pairs, 2,
             "branching construct --search: largest super-cell (lamella pairs)");
DEFINE_int32(subintervals, 3,
             "branching construct --family general: linear pieces per segment");
DEFINE_int32(search_starts, 1,
             "branching construct --search: noisy restarts per start");
DEFINE_string(search_filter, "",
              "branching construct --search: only topologies whose name "
              "contains this text (e.g. r3-n2)");
DEFINE_int32(search_threads, 1,
             "branching construct --search: threads (result independent)");
DEFINE_bool(optimize, false,
            "branching construct: optimise h0, theta (and the lens shape) by LM");

namespace shellspace {
namespace {

using namespace branching;

// The dimensional flags (epsilon, lengths, heights) lie in [1e-12, 1e12]:
// the energies use powers such as eps^(2/3) L^(1/3) and H / ny, which
// underflow or overflow far outside it (--height 1e-300 gave energy nan and
// exit 0).
constexpr double kSmallestScale = 1e-12, kLargestScale = 1e12;

FlagSpec ScaleFlag(const std::string& name, const std::string& meaning) {
  return RealFlag(name, meaning, kSmallestScale, End::kClosed, kLargestScale,
                  End::kClosed);
}

// 0 (the verb's default) or a scale in [1e-12, 1e12].
FlagSpec ScaleOrZeroFlag(const std::string& name, const std::string& meaning) {
  return CheckedFlag(name, meaning, "0 or a number in [1e-12, 1e+12]",
                     [](double value) {
                       return value == 0 ||
                              (value >= kSmallestScale && value <= kLargestScale);
                     });
}

FlagTable CommonFlags() {
  return {
      ScaleFlag("epsilon", "twin-boundary (interfacial) energy per length")
          .Default("0.001"),
      ScaleFlag("length", "domain length L (distance from the austenite)"),
      TextFlag("output", "output directory").Required(),
      TextFlag("json", "print the summary JSON on stdout"),
      TextFlag("quiet", "suppress progress output"),
  };
}

FlagTable SimulateFlags() {
  return Flags(
      {CommonFlags(),
       {
           ScaleOrZeroFlag("height", "domain height H (0: 0.5)"),
           IntegerFlag("nx", "number of x-cells", 2, 4096),
           IntegerFlag("ny",
                       "number of y-nodes (periodic); the grid's estimated "
                       "memory 16 MB + 3 KB x (nx + 1) x ny must lie within "
                       "half the physical memory",
                       8, 8192),
           TextFlag("init",
                    "initial guess laminate|random|km|needle|lens (km: the "
                    "psi-junction cell; needle: the T2 cell)")
               .Default("needle")
               .Check(CheckInitialGuessName),
           RealFlag("delta",
                    "interface width (0: 3 H/ny, the rule dy = delta/3); "
                    "a positive one needs H/ny <= delta/2",
                    0, End::kClosed),
           RealFlag("grading", "x-grading exponent, x_i = L (i/nx)^g", 1,
                    End::kClosed, 4, End::kClosed),
           IntegerFlag("continuation", "continuation stages in delta (factor 2)",
                       1, 8),
           IntegerFlag("periods",
                       "periods of the initial pattern in H (0: nearest to "
                       "the optimal KM period)",
                       0),
           IntegerFlag("init_seed", "seed of --init random", 0),
           IntegerFlag("lm_iterations", "LM iterations per continuation stage",
                       0),
           CheckedFlag("delta_extrapolation",
                       "0, or >= 2: also run the widths delta, delta/r, ... "
                       "(this many, r = 2^(1/2)) and fit the constant as "
                       "delta -> 0",
                       "0 or an integer in [2, " +
                           std::to_string(kMaxExtrapolationWidths) + "]",
                       [](double v) {
                         return v == 0 ||
                                (v >= 2 && v <= kMaxExtrapolationWidths &&
                                 v == std::floor(v));
                       }),
           TimeLimitFlag(),
       }});
}

FlagTable ConstructFlags() {
  return Flags(
      {CommonFlags(),
       {
           TextFlag("family",
                    "km (psi-junction) | needle (T2) | lens | general (the "
                    "reduced sharp-interface optimiser)"),
           TextFlag("search",
                    "--family general: multi-start search over topologies "
                    "(else one solve of the lens topology)"),
           TextFlag("search_ratios", "--search: refinement ratios r, e.g. 2,3,4"),
           IntegerFlag("search_pairs",
                       "--search: largest super-cell (lamella pairs)", 1, 4),
           IntegerFlag("subintervals",
                       "--family general: linear pieces per segment", 1, 16),
           IntegerFlag("search_starts", "--search: noisy restarts per start",
                       0, 64),
           TextFlag("search_filter",
                    "--search: only topologies whose name contains this text "
                    "(e.g. r3-n2)"),
           IntegerFlag("search_threads",
                       "--search: threads (the result does not depend on them)",
                       1, 64),
           TextFlag("optimize",
                    "optimise h0, theta (and the lens shape) by LM"),
           ScaleOrZeroFlag("height", "height of the picture (0: 2 h0)"),
       }});
}

// "i,j,x,y,u,u_y" per node (u_y: the staggered slope to node j + 1).
std::string FieldCsv(const RelaxedField& field) {
  const RelaxedGrid& g = field.grid;
  std::ostringstream out;
  out.precision(12);
  out << "i,j,x,y,u,u_y\n";
  for (int i = 0; i <= g.nx; ++i) {
    for (int j = 0; j < g.ny; ++j) {
      out << i << ',' << j << ',' << g.x(i) << ',' << g.y(j) << ','
          << field.at(i, j) << ',' << field.uy(i, j) << '\n';
    }
  }
  return out.str();
}

// "i,x,interfaces" per node row i >= 1.
std::string InterfaceCsv(const RelaxedField& field,
                         const std::vector<int>& counts) {
  std::ostringstream out;
  out.precision(12);
  out << "i,x,interfaces\n";
  for (size_t k = 0; k < counts.size(); ++k) {
    out << k + 1 << ',' << field.grid.x(static_cast<int>(k) + 1) << ','
        << counts[k] << '\n';
  }
  return out.str();
}

double BranchingHeight() { return FLAGS_height > 0 ? FLAGS_height : 0.5; }

std::string PrepareOutput() {
  RunPaths().OutputDirectory("output", FLAGS_output).Check();
  return FLAGS_output;
}

// The simulation's settings from the flags (checked by the workflow).
SimulationSettings SimulationSettingsFromFlags() {
  SimulationSettings s;
  s.epsilon = FLAGS_epsilon;
  s.length = FLAGS_length;
  s.height = BranchingHeight();
  s.nx = FLAGS_nx;
  s.ny = FLAGS_ny;
  s.grading = FLAGS_grading;
  s.delta = FLAGS_delta;
  s.continuation = FLAGS_continuation;
  s.init = FLAGS_init;
  s.periods = FLAGS_periods;
  s.seed = static_cast<unsigned>(FLAGS_init_seed);
  s.max_iterations = FLAGS_lm_iterations;
  s.stop = SolveStopToken();
  return s;
}

// Without --quiet: prints the simulation's parameters and sets s->progress
// to print every tenth iteration.
void AnnounceSimulation(SimulationSettings* s) {
  if (FLAGS_quiet) return;
  std::cerr << "branching simulate: eps " << s->epsilon << ", L " << s->length
            << ", H " << s->height << ", grid " << s->nx << " x " << s->ny
            << ", delta " << s->Delta() << ", init " << s->init << "\n";
  s->progress = [](double delta, int iteration, double energy) {
    if (iteration % 10 == 0) {
      std::cerr << "  delta " << delta << "  iteration " << iteration
                << "  energy " << energy << "\n";
    }
  };
}

// Prints the extrapolation in delta: its fits, the constant as delta -> 0
// and the steps of the interface count.
void PrintExtrapolation(const DeltaExtrapolation& ex) {
  std::cerr << "  extrapolation: "
            << (ex.all_converged ? "every width converged"
                                 : "NOT every width converged")
            << ", C(delta) " << (ex.monotone ? "" : "NOT ")
            << "monotone; linear c0 " << ex.c0 << " (rms " << ex.linear_rms
            << ")";
  if (ex.has_quadratic) {
    std::cerr << ", quadratic q0 " << ex.q0 << " (rms " << ex.quadratic_rms
              << "), root s0 " << ex.s0 << " (rms " << ex.root_rms << ")";
  }
  std::cerr << "; C(delta -> 0) = " << ex.extrapolated << " +- " << ex.error
            << "\n  interface count steps (x = L -> 0):";
  for (const CountStep& st : ex.steps) {
    std::cerr << " " << st.outer << "->" << st.inner << " at x " << st.x << ";";
  }
  std::cerr << "\n";
}

// Without --quiet: one line per width of the extrapolation.
void PrintExtrapolationWidth(const DeltaWidth& w) {
  if (FLAGS_quiet) return;
  std::cerr << "  extrapolation: delta " << w.delta << "  grid " << w.nx
            << " x " << w.ny << "  C " << w.constant << "  iterations "
            << w.iterations << "  " << w.termination
            << "  interfaces x = L: " << w.interfaces_far << ", max "
            << w.interfaces_max << "\n";
}

// Writes DIR/uy.png (the slope figure), DIR/u.csv and DIR/interfaces.csv.
void WriteSimulationFiles(RunDirectory* output, const SimulationSettings& s,
                          const SimulationResult& result) {
  const int width_px = 800;
  const int height_px = std::clamp(
      static_cast<int>(std::lround(width_px * s.height / s.length)), 200, 1600);
  WriteFileAtomically(
      output->File("uy.png"),
      EncodePng(SlopeFigure(result.field, width_px, height_px)));
  WriteFileAtomically(output->File("u.csv"), FieldCsv(result.field));
  WriteFileAtomically(output->File("interfaces.csv"),
                      InterfaceCsv(result.field, result.interfaces));
}

// Prints the energy (also scaled by eps^2/3 L^1/3) and the interface counts
// at both ends.
void PrintSimulationEnergy(const SimulationSettings& s,
                           const SimulationResult& result,
                           const std::string& dir) {
  const double scale = std::pow(s.epsilon, 2.0 / 3.0) * std::cbrt(s.length);
  std::cerr << "energy " << result.energy.total() << " (elastic "
            << result.energy.elastic << ", interfacial "
            << result.energy.interfacial()
            << "), E / (eps^2/3 L^1/3) = " << result.energy.total() / scale
            << "; interfaces at x = L: " << result.interfaces.back()
            << ", near x = 0: " << result.interfaces.front() << "; wrote "
            << dir << "\n";
}

int RunSimulate() {
  workflows::BranchingSimulateOptions options;
  options.settings = SimulationSettingsFromFlags();
  options.delta_extrapolation = FLAGS_delta_extrapolation;
  options.on_width = PrintExtrapolationWidth;
  workflows::CheckBranchingSimulate(options);
  const std::string dir = PrepareOutput();
  AnnounceSimulation(&options.settings);
  const workflows::BranchingSimulateResult run =
      workflows::RunBranchingSimulate(options);
  if (run.extrapolation && !FLAGS_quiet) PrintExtrapolation(*run.extrapolation);
  // The exit code says what the summary's converged says: a last stage that
  // did not converge (NO_CONVERGENCE after --lm_iterations), or a width of
  // the extrapolation that did not, is exit 4.
  RunStatus status("branching simulate");
  for (const std::string& failure : run.status.failures) {
    status.Require(false, failure);
  }
  RunDirectory output(dir);
  WriteSimulationFiles(&output, run.settings, run.simulation);
  const std::string text = output.Commit(run.summary);
  if (FLAGS_json) std::cout << text << "\n";
  if (!FLAGS_quiet) PrintSimulationEnergy(run.settings, run.simulation, dir);
  return status.Finish();
}

// The figure's height in pixels for a pattern of `height` over --length
// at 900 pixels wide.
int ConstructionFigureHeight(double height) {
  return std::clamp(
      static_cast<int>(std::lround(900 * height / FLAGS_length)), 100, 1800);
}

// Writes DIR/pattern.png (and for the general family DIR/pattern.txt) and
// prints the summary (--json) or the construction's line.
int WriteConstruction(const workflows::BranchingConstructResult& run,
                      const std::string& dir) {
  RunDirectory output(dir);
  std::string line;
  if (run.general) {
    const branching::GeneralResult& best = run.general->best;
    Construction c;
    c.pattern = GeneralCellPattern(best);
    c.length = FLAGS_length;
    c.h0 = run.series.h0;
    c.lengths = run.series.lengths;
    const double height = FLAGS_height > 0 ? FLAGS_height : 2.0 * c.h0;
    WriteFileAtomically(output.File("pattern.png"),
                        EncodePng(ConstructionFigure(
                            c, height, 900, ConstructionFigureHeight(height))));
    WriteFileAtomically(output.File("pattern.txt"), DescribeGeneral(best));
    std::ostringstream text;
    text << DescribeGeneral(best) << "general: constant "
         << best.constant_free << " (free lengths; geometric "
         << best.constant_geometric << "), ratio to C_KM "
         << best.constant_free / KmClosedFormConstant()
         << ", to C_KM shifted "
         << best.constant_free / KmShiftedClosedFormConstant() << "; "
         << run.general->solves << " solves, " << run.general->seconds
         << " s\n";
    line = text.str();
  } else {
    const branching::ConstructionResult& result = *run.construction;
    const double height = FLAGS_height > 0 ? FLAGS_height : 2.0 * result.h0;
    WriteFileAtomically(
        output.File("pattern.png"),
        EncodePng(ConstructionFigure(result.ToConstruction(FLAGS_length),
                                     height, 900,
                                     ConstructionFigureHeight(height))));
    std::ostringstream text;
    text << result.family << ": constant " << result.constant
         << " (C_KM closed form " << KmClosedFormConstant() << ", ratio "
         << result.constant / KmClosedFormConstant() << "), h0 " << result.h0
         << ", theta " << result.theta << "\n";
    line = text.str();
  }
  const std::string text = output.Commit(run.summary);
  if (FLAGS_json) {
    std::cout << text << "\n";
  } else if (!FLAGS_quiet) {
    std::cout << line;
  }
  return 0;
}

int RunConstruct() {
  workflows::BranchingConstructOptions options;
  options.epsilon = FLAGS_epsilon;
  options.length = FLAGS_length;
  options.family = FLAGS_family;
  options.optimize = FLAGS_optimize;
  options.search = FLAGS_search;
  options.search_ratios = FLAGS_search_ratios;
  options.search_pairs = FLAGS_search_pairs;
  options.subintervals = FLAGS_subintervals;
  options.search_starts = FLAGS_search_starts;
  options.search_threads = FLAGS_search_threads;
  options.search_filter = FLAGS_search_filter;
  options.on_topology = [](const branching::GeneralResult& g) {
    if (!FLAGS_quiet && g.ok) {
      std::cerr << "  " << g.topology.name << ": C_free " << g.constant_free
                << "\n";
    }
  };
  const std::string dir = PrepareOutput();
  return WriteConstruction(workflows::RunBranchingConstruct(options), dir);
}

}  // namespace

SHELLSPACE_REGISTER_VERB(
    "branching simulate",
    "branching simulate [--epsilon E --length L --height H --nx N --ny M "
    "--init laminate|random|km|needle|lens --delta_extrapolation N] "
    "--output DIR [--json]: relaxed diffuse-interface simulation",
    SimulateFlags(), RunSimulate);
SHELLSPACE_REGISTER_VERB(
    "branching construct",
    "branching construct [--epsilon E --length L --family "
    "km|needle|lens|general --optimize --search] --output DIR [--json]: the "
    "sharp-interface constructions and the general optimiser",
    ConstructFlags(), RunConstruct);

}  // namespace shellspace
