// The module's branching (Kohn-Mueller) functions: branching_simulate,
// branching_construct.
#include <optional>
#include <string>

#include "python/module_common.h"
#include "python/parameter_docs.h"
#include "shellspace/workflows/branching.h"

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
  SolveControl control(time_limit);
  workflows::BranchingSimulateOptions options;
  branching::SimulationSettings& s = options.settings;
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
  s.stop = control.Token();
  options.delta_extrapolation = delta_extrapolation;
  workflows::CheckBranchingSimulate(options);
  std::optional<workflows::BranchingSimulateResult> run;
  {
    SolveControl::Solving solving(control);
    run.emplace(workflows::RunBranchingSimulate(options));
  }
  JsonObject summary = run->summary;
  AddStopFields(summary, control);
  // What the summary's converged judges, as the CLI's exit 4: raised as
  // NotConvergedError unless allow_unconverged (a stopped run: partial).
  const branching::RelaxedField& field = run->simulation.field;
  const branching::RelaxedGrid& g = field.grid;
  py::array_t<double> u(
      {static_cast<py::ssize_t>(g.nx + 1), static_cast<py::ssize_t>(g.ny)});
  for (int i = 0; i <= g.nx; ++i) {
    for (int j = 0; j < g.ny; ++j) u.mutable_at(i, j) = field.at(i, j);
  }
  const py::object dict = ToDict(summary);
  return control.Finish(py::make_tuple(ReadOnlyArrays(u), dict), dict,
                        "branching simulate", run->status.failures,
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
  workflows::BranchingConstructOptions options;
  options.epsilon = epsilon;
  options.length = length;
  options.family = family;
  options.optimize = optimize;
  options.search = search;
  options.search_ratios = search_ratios;
  options.search_pairs = search_pairs;
  options.subintervals = subintervals;
  options.search_starts = search_starts;
  options.search_filter = search_filter;
  options.search_threads = search_threads;
  std::optional<workflows::BranchingConstructResult> run;
  {
    py::gil_scoped_release release;
    run.emplace(workflows::RunBranchingConstruct(options));
  }
  return ToDict(run->summary);
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
