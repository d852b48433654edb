// The solving functions' results as Python classes: GeodesicResult,
// LogResult, ShootResult, TransportResult, SplineResult, RegressResult,
// MeanResult and PcaResult, each holding its workflow's result
// (shellspace/workflows/, the C++ struct the CLI prints from) with its
// numbers as read-only attributes, the status (SolveStatus) and energy
// split (EnergySplit) as objects, repr() and to_dict() (the summary dict,
// the CLI's --json keys). For the scripts written against the earlier
// functions a result still unpacks as the pair (value, summary):
//   path, summary = shellspace.geodesic(V0, V1, F)      # as before
//   run = shellspace.geodesic(V0, V1, F); run.path_energy, run.status
// as os.stat_result and time.struct_time are tuples with named fields. A
// result pickles as that pair (a plain tuple: what crosses to another
// process is what the functions returned before).
#ifndef SHELLSPACE_PYTHON_MODULE_RESULTS_H_
#define SHELLSPACE_PYTHON_MODULE_RESULTS_H_

#include <pybind11/pybind11.h>

#include <string>
#include <utility>
#include <vector>

#include "python/module_common.h"
#include "python/strict_numbers.h"
#include "shellspace/workflows/geodesic.h"
#include "shellspace/workflows/mean.h"
#include "shellspace/workflows/pca.h"
#include "shellspace/workflows/regress.h"
#include "shellspace/workflows/shoot.h"
#include "shellspace/workflows/spline.h"
#include "shellspace/workflows/transport.h"

namespace shellspace {
namespace pymodule {

namespace py = pybind11;

// A workflow's result with what its Python function returns: `value` (the
// path, the log, the mean, the shapes) and the summary dict.
template <class Run>
struct BoundResult {
  Run run;
  py::object value;
  py::dict summary;
};

// The Python object of a result (its class registered by RegisterResults).
template <class Run>
py::object MakeResult(Run run, py::object value, py::object summary) {
  return py::cast(BoundResult<Run>{std::move(run),
                                   ReadOnlyArrays(std::move(value)),
                                   py::dict(std::move(summary))},
                  py::return_value_policy::move);
}

// The status of a workflow's result (the log's is its geodesic's).
template <class Run>
const workflows::SolveStatus& StatusOfRun(const Run& run) {
  return run.status;
}
inline const workflows::SolveStatus& StatusOfRun(
    const workflows::LogResult& run) {
  return run.geodesic.status;
}

// The end of a workflow function: the result object of (value, summary)
// returned, or raised by solver.Finish (NotConvergedError with it attached)
// for the failures of its status, under `verb`.
template <class Run>
py::object FinishResult(const SolverOptions& solver, const char* verb, Run run,
                        py::object value, const py::object& summary) {
  std::vector<std::string> failures = FailuresOf(StatusOfRun(run));
  return solver.Finish(MakeResult(std::move(run), std::move(value), summary),
                       summary, verb, std::move(failures));
}

// Registers SolveStatus, EnergySplit, Material and the eight result
// classes.
void RegisterResults(py::module_& m);

}  // namespace pymodule
}  // namespace shellspace

#endif  // SHELLSPACE_PYTHON_MODULE_RESULTS_H_
