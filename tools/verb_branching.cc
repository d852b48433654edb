// `shellspace branching simulate|construct [flags]`: the Kohn–Müller branching
// problem (spec branching.md). Each sub-command is a verb of its own
// ("branching simulate", "branching construct") with its own flags.
//
//   simulate  — relaxed diffuse-interface simulation on a graded grid (sparse
//               LM, continuation in delta); writes DIR/u.csv, DIR/uy.png,
//               DIR/interfaces.csv, DIR/summary.json.
//   construct — the reduced sharp-interface model: the KM or lens
//               self-similar construction, optionally optimised; writes
//               DIR/pattern.png and DIR/summary.json.
//
// --epsilon here is the twin-boundary energy (default 1e-3), not the step of
// `transport`; --height is the domain height H.
#include <gflags/gflags.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "shellspace/geometry/mesh.h"
#include "shellspace/problems/branching/construction_optimizer.h"
#include "shellspace/problems/branching/field_output.h"
#include "shellspace/problems/branching/km_family.h"
#include "shellspace/problems/branching/simulation.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/png_writer.h"
#include "shellspace/tools/common_flags.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/tools/verb.h"

DEFINE_double(length, 1.0, "branching: domain length L");
DEFINE_int32(nx, 64, "branching simulate: number of x-cells");
DEFINE_int32(ny, 128, "branching simulate: number of y-nodes");
DEFINE_string(init, "km", "branching simulate: initial guess");
DEFINE_double(delta, 0.0, "branching simulate: interface width");
DEFINE_double(grading, 2.0, "branching simulate: x-grading exponent");
DEFINE_int32(continuation, 3, "branching simulate: continuation stages");
DEFINE_int32(periods, 0, "branching simulate: periods of the initial pattern");
DEFINE_int32(init_seed, 1, "branching simulate: seed of --init random");
DEFINE_int32(lm_iterations, 200, "branching simulate: LM iterations per stage");
DEFINE_string(family, "km", "branching construct: km|lens");
DEFINE_bool(optimize, false, "branching construct: optimise the parameters");

namespace shellspace {
namespace {

using namespace branching;

FlagTable CommonFlags() {
  return {
      RealFlag("epsilon", "twin-boundary (interfacial) energy per length",
               0, End::kOpen)
          .Default("0.001"),
      RealFlag("length", "domain length L (distance from the austenite)", 0,
               End::kOpen),
      TextFlag("output", "output directory").Required(),
      TextFlag("json", "print the summary JSON on stdout"),
      TextFlag("quiet", "suppress progress output"),
  };
}

FlagTable SimulateFlags() {
  return Flags(
      {CommonFlags(),
       {
           RealFlag("height", "domain height H (0: 0.5)", 0, End::kClosed),
           IntegerFlag("nx", "number of x-cells", 2, 4096),
           IntegerFlag("ny", "number of y-nodes (periodic)", 8, 8192),
           TextFlag("init", "initial guess laminate|random|km|lens"),
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
       }});
}

FlagTable ConstructFlags() {
  return Flags(
      {CommonFlags(),
       {
           TextFlag("family", "km|lens"),
           TextFlag("optimize",
                    "optimise h0, theta (and the lens shape) by LM"),
           RealFlag("height", "height of the picture (0: 2 h0)", 0,
                    End::kClosed),
       }});
}

double BranchingHeight() { return FLAGS_height > 0 ? FLAGS_height : 0.5; }

std::string PrepareOutput() {
  std::error_code error;
  if (std::filesystem::exists(FLAGS_output, error) &&
      !std::filesystem::is_directory(FLAGS_output, error)) {
    throw InputError("--output exists and is not a directory: " + FLAGS_output);
  }
  return FLAGS_output;
}

void MakeOutputDirectory(const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw InputError("cannot create directory " + dir);
}

JsonObject EnergyJson(double elastic, double interfacial) {
  JsonObject e;
  e.Add("elastic", elastic).Add("interfacial", interfacial)
      .Add("total", elastic + interfacial);
  return e;
}

int RunSimulate() {
  if (FLAGS_init != "laminate" && FLAGS_init != "random" &&
      FLAGS_init != "km" && FLAGS_init != "lens") {
    throw InputError("--init must be laminate, random, km or lens, got '" +
                     FLAGS_init + "'");
  }
  if (FLAGS_delta > 0 && BranchingHeight() / FLAGS_ny > FLAGS_delta / 2.0) {
    throw InputError("--delta is not resolved: need --height / --ny <= "
                     "--delta / 2");
  }
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
  CheckSimulationSettings(s);
  const std::string dir = PrepareOutput();
  if (!FLAGS_quiet) {
    std::cerr << "branching simulate: eps " << s.epsilon << ", L " << s.length
              << ", H " << s.height << ", grid " << s.nx << " x " << s.ny
              << ", delta " << s.Delta() << ", init " << s.init << "\n";
    s.progress = [](double delta, int iteration, double energy) {
      if (iteration % 10 == 0) {
        std::cerr << "  delta " << delta << "  iteration " << iteration
                  << "  energy " << energy << "\n";
      }
    };
  }
  const SimulationResult result = RunSimulation(s);
  const double scale = std::pow(s.epsilon, 2.0 / 3.0) * std::cbrt(s.length);

  JsonObject summary;
  summary.Add("command", "branching simulate")
      .Add("epsilon", s.epsilon).Add("length", s.length)
      .Add("height", s.height).Add("nx", s.nx).Add("ny", s.ny)
      .Add("grading", s.grading).Add("delta", result.delta)
      .Add("init", s.init).Add("periods", result.periods)
      .Add("energy", EnergyJson(result.energy.elastic,
                                result.energy.interfacial()))
      .Add("energy_over_eps23_L13", result.energy.total() / scale)
      .Add("km_constant", KmClosedFormConstant())
      .Add("iterations", result.iterations).Add("seconds", result.seconds);
  std::string stages = "[";
  for (size_t k = 0; k < result.stages.size(); ++k) {
    const RelaxedStage& st = result.stages[k];
    JsonObject o;
    o.Add("delta", st.delta).Add("iterations", st.iterations)
        .Add("energy", st.energy.total()).Add("seconds", st.seconds)
        .Add("termination", st.termination);
    stages += (k ? ", " : "") + o.str();
  }
  summary.Raw("stages", stages + "]");
  std::vector<double> x, counts;
  for (size_t k = 0; k < result.interfaces.size(); ++k) {
    x.push_back(result.field.grid.x(static_cast<int>(k) + 1));
    counts.push_back(result.interfaces[k]);
  }
  summary.Add("x", x).Add("interfaces", counts);

  MakeOutputDirectory(dir);
  const int width_px = 800;
  const int height_px = std::clamp(
      static_cast<int>(std::lround(width_px * s.height / s.length)), 200, 1600);
  AtomicFileSet files;
  files.Add(dir + "/uy.png",
            EncodePng(RenderSlope(result.field, width_px, height_px)));
  files.Add(dir + "/u.csv", FieldCsv(result.field));
  files.Add(dir + "/interfaces.csv",
            InterfaceCsv(result.field, result.interfaces));
  files.Add(dir + "/summary.json", summary.str() + "\n");
  files.Commit();
  if (FLAGS_json) std::cout << summary.str() << "\n";
  if (!FLAGS_quiet) {
    std::cerr << "energy " << result.energy.total() << " (elastic "
              << result.energy.elastic << ", interfacial "
              << result.energy.interfacial() << "), E / (eps^2/3 L^1/3) = "
              << result.energy.total() / scale << "; interfaces at x = L: "
              << result.interfaces.back() << ", near x = 0: "
              << result.interfaces.front() << "; wrote " << dir << "\n";
  }
  return 0;
}

int RunConstruct() {
  if (FLAGS_family != "km" && FLAGS_family != "lens") {
    throw InputError("--family must be km or lens, got '" + FLAGS_family +
                     "'");
  }
  const double epsilon = FLAGS_epsilon;
  const std::string dir = PrepareOutput();
  ConstructionResult result;
  if (FLAGS_family == "km") {
    result = DefaultKm(epsilon, FLAGS_length);
    if (FLAGS_optimize) {
      result = OptimizeKm(epsilon, FLAGS_length, 0.5 * result.h0, 0.3);
    }
  } else {
    result = DefaultLens(epsilon, FLAGS_length);
    if (FLAGS_optimize) {
      result = OptimizeLens(epsilon, FLAGS_length, result.h0, result.theta,
                            LensShape{0.2, 0.0, 0.0});
    }
  }
  JsonObject params;
  params.Add("r", result.r).Add("h0", result.h0).Add("theta", result.theta);
  if (result.family == "lens") {
    params.Add("tau", result.shape.tau).Add("a1", result.shape.a1)
        .Add("a2", result.shape.a2);
  }
  JsonObject summary;
  summary.Add("command", "branching construct").Add("family", result.family)
      .Add("optimized", FLAGS_optimize).Add("epsilon", epsilon)
      .Add("length", FLAGS_length).Add("constant", result.constant)
      .Add("parameters", params).Add("A", result.A).Add("B", result.B)
      .Add("energy", EnergyJson(result.elastic, result.interfacial))
      .Add("km_constant_closed_form", KmClosedFormConstant())
      .Add("ratio_to_km", result.constant / KmClosedFormConstant());
  if (FLAGS_optimize) {
    summary.Add("iterations", result.iterations)
        .Add("seconds", result.seconds)
        .Add("termination", result.termination);
  }
  const double height = FLAGS_height > 0 ? FLAGS_height : 2.0 * result.h0;
  const int width_px = 900;
  const int height_px = std::clamp(
      static_cast<int>(std::lround(width_px * height / FLAGS_length)), 100,
      1800);
  const RgbImage image = RenderConstruction(
      result.ToConstruction(FLAGS_length), height, width_px, height_px);
  MakeOutputDirectory(dir);
  AtomicFileSet files;
  files.Add(dir + "/pattern.png", EncodePng(image));
  files.Add(dir + "/summary.json", summary.str() + "\n");
  files.Commit();
  if (FLAGS_json) {
    std::cout << summary.str() << "\n";
  } else if (!FLAGS_quiet) {
    std::cout << result.family << ": constant " << result.constant
              << " (C_KM closed form " << KmClosedFormConstant() << ", ratio "
              << result.constant / KmClosedFormConstant() << "), h0 "
              << result.h0 << ", theta " << result.theta << "\n";
  }
  return 0;
}

}  // namespace

SHELLSPACE_REGISTER_VERB(
    "branching simulate",
    "branching simulate [--epsilon E --length L --height H --nx N --ny M "
    "--init laminate|random|km|lens] --output DIR [--json]: relaxed "
    "diffuse-interface simulation",
    SimulateFlags(), RunSimulate);
SHELLSPACE_REGISTER_VERB(
    "branching construct",
    "branching construct [--epsilon E --length L --family km|lens "
    "--optimize] --output DIR [--json]: the sharp-interface constructions",
    ConstructFlags(), RunConstruct);

}  // namespace shellspace
