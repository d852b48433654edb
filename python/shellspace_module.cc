// The Python module `shellspace`: the library's functions on NumPy arrays.
//
// A mesh is a pair (V, F): V a #V x 3 float64 array of vertex positions, F a
// #F x 3 integer array of counter-clockwise triangles; every shape of one
// call shares F. A path is a (K + 1) x #V x 3 array. Each function of a CLI
// verb takes that verb's options as keyword arguments with the verb's
// defaults (`shellspace VERB --help`), calls the library functions the verb
// calls, and returns its results and the verb's --json summary as a dict
// (reports/: the same objects the CLI prints; `output` and `seconds` as the
// CLI has them) -- the workflow functions inside a result object
// (python/module_results.h). Bad input raises shellspace.InputError (a
// ValueError) with the library's message; other library errors RuntimeError.
// Every array argument is checked by python/array_arguments.h. The functions
// that solve take time_limit and allow_unconverged, stop at KeyboardInterrupt,
// and raise shellspace.NotConvergedError for a result that missed its
// stopping criterion (python/solve_control.h); their steps are bounded up
// front by the CLI's memory estimates (geometry/memory_limits.h).
//
// This file makes the module and its exceptions; the functions are added
// by one file per room of the library, python/module_<room>.cc (their
// shared helpers: python/module_common.h).
#include <dlfcn.h>
#include <glog/logging.h>
#include <pybind11/pybind11.h>

#include <string>

#include "python/module_common.h"
#include "python/module_results.h"
#include "python/solve_control.h"
#include "python/strict_numbers.h"
#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/runtime/openmp_threads.h"

namespace py = pybind11;

PYBIND11_MODULE(shellspace, m) {
  using namespace shellspace;
  // CHOLMOD's OpenMP regions on the importing thread alone, as in the CLI
  // (runtime/openmp_threads.h).
  SerialOpenMpInThisThread();
  // Ceres' routine warnings hidden, as in the CLI (its --minloglevel=0).
  FLAGS_minloglevel = google::GLOG_ERROR;
  FLAGS_logtostderr = true;

  m.doc() =
      "shellspace: the time-discrete geodesic calculus on discrete shells.\n"
      "Meshes are (V, F): V #V x 3 float64, F #F x 3 int; paths are\n"
      "(K + 1) x #V x 3 arrays. Each verb function takes the CLI verb's\n"
      "options as keyword arguments (lambda as lambda_); each workflow\n"
      "function has an options class (GeodesicOptions, ...: its keywords\n"
      "with their defaults as checked attributes, passed as **options).\n"
      "The workflow functions return result objects (GeodesicResult, ...:\n"
      "the numbers as attributes, status, energy_split, to_dict() the\n"
      "verb's --json summary) that unpack as the pair (value, summary); the\n"
      "others return their values and summary dicts. Bad arrays and options "
      "raise\n"
      "InputError. The solving functions take time_limit (seconds) and\n"
      "allow_unconverged: an unconverged or time-limited result raises\n"
      "NotConvergedError (its .result attached) unless\n"
      "allow_unconverged=True; Ctrl-C stops the solves and raises\n"
      "KeyboardInterrupt with the partial result as .result.";
  // The pure-Python submodules (shellspace.collections) are in the folder
  // shellspace/ beside this file: the extension is their package.
  Dl_info self;
  if (dladdr(reinterpret_cast<void*>(&PyInit_shellspace), &self) != 0 &&
      self.dli_fname != nullptr) {
    const std::string file = self.dli_fname;
    py::list path;
    path.append(file.substr(0, file.rfind('/') + 1) + "shellspace");
    m.attr("__path__") = path;
  }
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  RegisterNotConvergedError(m);
  // The default bending weight relative to the reference's area
  // (cost_functions/shell/relative_bending_weight.h).
  m.attr("DEFAULT_RELATIVE_ETA") = kDefaultRelativeEta;

  using namespace shellspace::pymodule;
  RegisterResults(m);
  RegisterIo(m);
  RegisterEnergy(m);
  RegisterCalculus(m);
  RegisterSplines(m);
  RegisterStatistics(m);
  RegisterCollections(m);
  RegisterBranching(m);
  RegisterRender(m);
}
