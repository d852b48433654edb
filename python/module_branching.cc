// The module's branching (Kohn-Mueller) functions: branching_simulate,
// branching_construct.
#include <optional>
#include <string>

#include "python/module_common.h"
#include "python/parameter_docs.h"
#include "shellspace/geometry/memory_limits.h"
#include "shellspace/problems/branching/construction_optimizer.h"
#include "shellspace/problems/branching/general_construction.h"
#include "shellspace/problems/branching/simulation.h"
#include "shellspace/reports/branching_reports.h"

namespace shellspace {
namespace pymodule {
namespace {

// `branching simulate`: the relaxed Kohn-Mueller simulation. Returns (u as
// an (nx + 1) x ny array, u[i, j] at node x_i, y_j; summary).
py::object BranchingSimulatePy(double epsilon, double length, double height,
                               int nx, int ny, const std::string& init,
                               double delta, double grading, int continuation,
                               int periods, int init_seed, int lm_iterations,
                               int delta_extrapolation,
                               std::optional<double> time_limit,
                               bool allow_unconverged) {
  using namespace branching;
  SolveControl control(time_limit);
  CheckExtrapolationCount(delta_extrapolation);
  SimulationSettings s;
  s.epsilon = epsilon;
  s.length = length;
  s.height = height > 0 ? height : 0.5;
  s.nx = nx;
  s.ny = ny;
  s.grading = grading;
  s.delta = delta;
  s.continuation = continuation;
  s.init = init;
  s.periods = periods;
  s.seed = static_cast<unsigned>(init_seed);
  s.max_iterations = lm_iterations;
  s.stop = control.Poll();
  CheckSimulationSettings(s);
  const double nodes = (static_cast<double>(s.nx) + 1) * s.ny;
  CheckMemory(BranchingBytes(nodes),
              "nx " + std::to_string(s.nx) + ", ny " + std::to_string(s.ny) +
                  " (" + std::to_string(static_cast<long>(nodes)) + " nodes)",
              "16 MB + 3 KB x (nx + 1) x ny");
  std::optional<SimulationResult> simulation;
  std::optional<DeltaExtrapolation> extrapolation;
  {
    SolveControl::Solving solving(control);
    simulation.emplace(RunSimulation(s));
    const SimulationResult& result = *simulation;
    if (const std::string why = SimulationBreakdown(result); !why.empty()) {
      throw InputError("branching simulate: " + why);
    }
    if (delta_extrapolation >= 2 && !control.stopped()) {
      extrapolation.emplace(ExtrapolateDelta(
          s, ExtrapolationWidths(result.delta, delta_extrapolation)));
    }
  }
  const SimulationResult& result = *simulation;
  const DeltaExtrapolation* ex = extrapolation ? &*extrapolation : nullptr;
  JsonObject summary = SimulationJson(s, result, ex);
  AddStopFields(summary, control);
  // What the summary's converged judges, as the CLI's exit 4: raised as
  // NotConvergedError unless allow_unconverged (a stopped run: partial).
  std::vector<std::string> failures =
      SimulationFailures(s, result, ex, "lm_iterations");
  const RelaxedGrid& g = result.field.grid;
  py::array_t<double> u(
      {static_cast<py::ssize_t>(g.nx + 1), static_cast<py::ssize_t>(g.ny)});
  for (int i = 0; i <= g.nx; ++i) {
    for (int j = 0; j < g.ny; ++j) {
      u.mutable_at(i, j) = result.field.at(i, j);
    }
  }
  const py::object dict = ToDict(summary);
  return control.Finish(py::make_tuple(ReadOnlyArrays(u), dict), dict,
                        "branching simulate", std::move(failures),
                        allow_unconverged);
}

// `branching construct`: the self-similar constructions. Returns the
// summary.
py::object BranchingConstructPy(double epsilon, double length,
                                const std::string& family, bool optimize,
                                bool search, const std::string& search_ratios,
                                int search_pairs, int subintervals,
                                int search_starts,
                                const std::string& search_filter,
                                int search_threads) {
  using namespace branching;
  if (!(epsilon > 0) || !(length > 0)) {
    throw InputError("epsilon and length must be > 0");
  }
  if (family != "km" && family != "needle" && family != "lens" &&
      family != "general") {
    throw InputError("family must be km, needle, lens or general, got '" +
                     family + "'");
  }
  py::gil_scoped_release release;
  if (family == "general") {
    const GeneralSearchOptions options = MakeGeneralSearchOptions(
        search_ratios, search_pairs, subintervals, search_starts,
        search_threads, search_filter, "");
    const GeneralConstruction construction = ConstructGeneral(options, search);
    const GeneralResult& best = construction.best;
    const FreeLengthSeries series =
        OptimalFreeLengths(best.A, best.B, best.topology.r, epsilon, length);
    const JsonObject summary =
        GeneralConstructionJson(best, series, epsilon, length, search,
                                construction.solves, construction.seconds);
    py::gil_scoped_acquire acquire;
    return ToDict(summary);
  }
  if (search) throw InputError("search needs family general");
  const ConstructionResult result =
      ConstructFamily(family, epsilon, length, optimize);
  const JsonObject summary =
      ConstructionJson(result, epsilon, length, optimize);
  py::gil_scoped_acquire acquire;
  return ToDict(summary);
}

}  // namespace

void RegisterBranching(py::module_& m) {
  // The defaults are the library's SimulationSettings (height 0: its 0.5).
  const branching::SimulationSettings simulation;
  m.def("branching_simulate", &BranchingSimulatePy,
        py::arg("epsilon") = simulation.epsilon,
        py::arg("length") = simulation.length, py::arg("height") = 0.0,
        py::arg("nx") = simulation.nx, py::arg("ny") = simulation.ny,
        py::arg("init") = simulation.init, py::arg("delta") = simulation.delta,
        py::arg("grading") = simulation.grading,
        py::arg("continuation") = simulation.continuation,
        py::arg("periods") = simulation.periods,
        py::arg("init_seed") = static_cast<int>(simulation.seed),
        py::arg("lm_iterations") = simulation.max_iterations,
        py::arg("delta_extrapolation") = 0, py::arg("time_limit") = py::none(),
        py::arg("allow_unconverged") = false,
        WithParameters(
            "branching_simulate",
            "The relaxed Kohn-Mueller simulation (`branching simulate`): "
            "returns (u (nx + 1) x ny, read-only; summary). Writes no files. "
            "A last stage short of convergence (lm_iterations per stage), or "
            "a width of the delta extrapolation that did not converge, raises "
            "NotConvergedError unless allow_unconverged (the CLI's exit 4); "
            "time_limit: seconds, then the field so far, partial (the same "
            "error unless allow_unconverged).")
            .c_str());
  m.def("branching_construct", &BranchingConstructPy,
        py::arg("epsilon") = 0.001, py::arg("length") = 1.0,
        py::arg("family") = "km", py::arg("optimize") = false,
        py::arg("search") = false, py::arg("search_ratios") = "2,3,4",
        py::arg("search_pairs") = 2, py::arg("subintervals") = 3,
        py::arg("search_starts") = 1, py::arg("search_filter") = "",
        py::arg("search_threads") = 1,
        WithParameters(
            "branching_construct",
            "A self-similar construction (`branching construct`): returns the "
            "summary. Writes no files.")
            .c_str());
}

}  // namespace pymodule
}  // namespace shellspace
