// What the files of the Python module share (python/module_<room>.cc, one
// per room of the library, each with its Register<Room>(module)): the array
// conversions, the validated inputs (shells, shell pairs, shape lists), the
// material and solver keywords gathered into structs, the checks of the
// step counts against the CLI's memory bounds, the outputs of the path
// verbs, and the keyword lists of the verbs' signatures.
#ifndef SHELLSPACE_PYTHON_MODULE_COMMON_H_
#define SHELLSPACE_PYTHON_MODULE_COMMON_H_

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "python/solve_control.h"
#include "python/strict_numbers.h"
#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/runtime/openmp_threads.h"
#include "shellspace/solvers/solver_settings.h"
#include "shellspace/workflows/common.h"
#include "shellspace/workflows/geodesic.h"
#include "shellspace/workflows/solve_choice_words.h"
#include "shellspace/workflows/solve_status.h"

namespace shellspace {
namespace pymodule {

namespace py = pybind11;

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since);

// ---- Arrays -------------------------------------------------------------
// Every array argument is read by python/array_arguments.h (dtype, shape,
// finite values, indices in range, any strides); results are new arrays.

py::array_t<double> FromPositions(const Positions& positions);
py::array_t<long long> FromFaces(const Faces& faces);
// A path as a (K + 1) x #V x 3 array.
py::array_t<double> FromPath(const std::vector<Positions>& path);
// `value` with its arrays made read-only for good: a NumPy array (returned
// as a view of immutable bytes, so setflags(write=True) raises), or each
// array value of a dict (replaced in it). The arrays of a solving function's result
// (a path, a log, a mean, the PCA's shapes, the branching field) are what
// the call computed: they are read, not written into (copy() for a
// scratch array).
py::object ReadOnlyArrays(py::object value);
// The summary tree as Python values (dict, list, float, int, bool, str,
// None for null and non-finite numbers), built directly; a raw text member
// (JsonValue::Raw) is parsed by json.loads.
py::object ToPython(const JsonValue& value);
py::object ToDict(const JsonObject& json);

// ---- Inputs -------------------------------------------------------------

// A validated shell (V, F) and its topology.
struct Shell {
  Mesh mesh;
  Topology topology;
};

// The shell of checked positions and the faces F (indices in [0, #V)).
Shell MakeShell(Positions positions, const py::object& F,
                const std::string& name);
Shell MakeShell(const py::object& V, const py::object& F,
                const std::string& name);

// Positions of a pose of `like` (same vertex count), validated.
Positions CompatiblePositions(const Positions& positions, const Shell& like,
                              const std::string& name);
Positions CompatiblePositions(const py::object& V, const Shell& like,
                              const std::string& name);

// Two poses of one shell and the shell space of the first: the input of
// every verb between two shapes (energy, geodesic, log, shoot).
struct ShellPair {
  Shell first;
  Positions second;
  ShellSpace space;
};

// The material keywords of every verb: mu, lambda_, and eta (absolute) or,
// when eta is None, relative_eta x the reference's area (the CLI's --eta /
// --relative_eta, cost_functions/shell/relative_bending_weight.h), and the
// bending model (the CLI's --bending) and the membrane law (--membrane).
struct MaterialArgs {
  double mu = 1;
  double lambda = 1;
  std::optional<double> eta;
  double relative_eta = kDefaultRelativeEta;
  std::string bending = "discrete-shells";  // the CLI's --bending
  std::string membrane = "neo-hookean";     // the CLI's --membrane
};

ShellMaterial Material(const MaterialArgs& args, const Mesh& reference);

// The relative_eta keyword as the functions receive it: its value and
// whether the caller gave it. Its default in every signature is the one
// float object DefaultRelativeEtaObject() (SHELLSPACE_MATERIAL_ARGS; the
// options classes keep that object as their default too), so that a value
// passed, even one equal to the default, is told from the default.
struct RelativeEtaArg {
  double value = kDefaultRelativeEta;
  bool given = false;
};
const py::object& DefaultRelativeEtaObject();

// The material keywords gathered; eta together with a given relative_eta
// is an InputError (as the CLI's --eta with --relative_eta: one of them).
MaterialArgs MakeMaterialArgs(double mu, double lambda,
                              std::optional<double> eta,
                              const RelativeEtaArg& relative_eta,
                              const std::string& bending,
                              const std::string& membrane);

// The material of the keywords for `reference`, as the workflows take it.
workflows::MaterialChoice MaterialChoiceOf(const MaterialArgs& args,
                                           const Mesh& reference);

// What a workflow's status raises as NotConvergedError's failures: its
// failures, or the one line of a solve that could not run.
std::vector<std::string> FailuresOf(const workflows::SolveStatus& status);

ShellPair MakeShellPair(const py::object& first, const py::object& second,
                        const py::object& F, const std::string& first_name,
                        const std::string& second_name,
                        const MaterialArgs& material_args);

// The shapes of a list (keyframes, inputs) with the connectivity F.
struct ShapeSet {
  Shell first;
  std::vector<Positions> shapes;
};

ShapeSet MakeShapeSet(const py::object& list, const py::object& F,
                      const std::string& name);

// The solver keywords of every call (the CLI's SolverFlags), checked by
// UserSolverSettings, and how the call stops and says unconverged
// (time_limit, allow_unconverged; python/solve_control.h).
struct SolverOptions {
  double tolerance = 1e-8;
  int max_iterations = 200;
  int threads = 2;
  bool quiet = false;
  bool allow_unconverged = false;
  std::shared_ptr<SolveControl> control;

  // The settings of the call's solves, polling its stop.
  SolverSettings Settings(const std::string& label) const {
    SolverSettings settings =
        UserSolverSettings(tolerance, max_iterations, threads, quiet, label);
    settings.stop = control->Token();
    return settings;
  }
  // `result` (a tuple whose summary is `summary`), or raised as
  // SolveControl::Finish says.
  py::object Finish(py::object result, py::object summary,
                    const std::string& verb,
                    std::vector<std::string> failures) const {
    return control->Finish(std::move(result), std::move(summary), verb,
                           std::move(failures), allow_unconverged);
  }
};

// The stop state of a call's summary, as the CLI's: "partial" (a poll
// stopped the solves: the best state so far) and "stop_reason".
JsonObject& AddStopFields(JsonObject& json, const SolveControl& control);

void CheckAtLeast(const std::string& name, long value, long min);

// `steps` of a solve the CLI bounds up front: in [min, kMaxSteps] and its
// memory estimate `bytes` (geometry/memory_limits.h, the model `model`)
// within half the physical memory.
void CheckSteps(const std::string& name, long steps, long min, double bytes,
                int vertices, const std::string& model);

// The memory models of geometry/memory_limits.h, as the CLI words them.
inline constexpr const char* kGeodesicModel = "64 MB + 1500 B x #V x K^2";
inline constexpr const char* kPathModel = "64 MB + 200 B x #V x (K + 1)";

// ---- Outputs ------------------------------------------------------------

// The outputs of a call, checked before any work by the one policy of
// every front end (io/output_paths.h): `output` a directory replaced whole,
// `png` and `gltf` files (gltf named .glb), none an existing input, no two
// naming one file, each writable and not too long a name. `inputs`: the
// files the call reads (name, path).
void CheckOutputs(const std::optional<std::string>& output,
                  const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf,
                  const std::vector<std::pair<std::string, std::string>>&
                      inputs = {});

// With `png`, the film strip of `frames` frames against the CLI's memory
// bound (render/film_strip.h CheckFilmStripMemory), before the solve.
void CheckPngMemory(const std::optional<std::string>& png, int frames);

// `output` a mesh file (.ply, .obj, .off) checked as CheckOutputs checks
// its files.
void CheckOutputFile(const std::optional<std::string>& output,
                     const std::vector<std::pair<std::string, std::string>>&
                         inputs = {});

// What a path verb writes, as the CLI: `output` (a directory of
// shape_000.ply ... and summary.json, `summary`'s text, replaced whole),
// `png` (a film strip) and `gltf` (a .glb morph animation,
// io/gltf_writer.h), each if given (not None), all together or none.
void WritePath(const std::optional<std::string>& output,
               const std::optional<std::string>& png,
               const std::optional<std::string>& gltf, const Faces& faces,
               const std::vector<Positions>& path, const JsonObject& summary);

JsonObject& AddOutput(JsonObject& json,
                      const std::optional<std::string>& output);

// A workflow's summary: its JSON, then the keys every front-end
// summary ends with: material (as resolved for `reference`), seconds (when
// given: the workflows that do not print it themselves), the stop fields,
// output. WorkflowSummary: as a dict.
JsonObject WorkflowJson(JsonObject json,
                        const workflows::MaterialChoice& material,
                        const Mesh& reference, std::optional<double> seconds,
                        const SolverOptions& solver,
                        const std::optional<std::string>& output);
py::object WorkflowSummary(JsonObject json,
                           const workflows::MaterialChoice& material,
                           const Mesh& reference, std::optional<double> seconds,
                           const SolverOptions& solver,
                           const std::optional<std::string>& output);

// The frames of a path to draw (write_gltf, write_film_strip) and their
// faces: every frame with the first one's vertex count.
struct Frames {
  std::vector<Positions> shapes;
  Faces faces;
};
Frames FramesArgument(const py::object& frames_object, const py::object& F);

// ---- Signatures ---------------------------------------------------------

// The Python signatures of the verb functions. A function f(args...,
// const MaterialArgs&) is bound as a function of args... followed by the
// material's keyword arguments (mu, lambda_, eta, relative_eta, bending,
// membrane: in
// the order of SHELLSPACE_MATERIAL_ARGS), gathered into a MaterialArgs; one
// that also ends with const SolverOptions& takes the solver's (tolerance,
// max_iterations, threads, quiet, time_limit, allow_unconverged:
// SHELLSPACE_SOLVER_ARGS) after them.
// The Gather functions take `Own`, the tuple of f's parameter types, and
// the indices of f's own arguments (those before the structs).
template <class Own, class Result, class... Params, size_t... I>
auto GatherMaterialArgs(Result (*f)(Params...), std::index_sequence<I...>) {
  return [f](std::tuple_element_t<I, Own>... args, double mu, double lambda,
             std::optional<double> eta, const RelativeEtaArg& relative_eta,
             const std::string& bending, const std::string& membrane) {
    return f(args..., MakeMaterialArgs(mu, lambda, eta, relative_eta, bending,
                                       membrane));
  };
}
template <class Own, class Result, class... Params, size_t... I>
auto GatherMaterialAndSolverArgs(Result (*f)(Params...),
                                 std::index_sequence<I...>) {
  return [f](std::tuple_element_t<I, Own>... args, double mu, double lambda,
             std::optional<double> eta, const RelativeEtaArg& relative_eta,
             const std::string& bending, const std::string& membrane,
             double tolerance, int max_iterations,
             int threads, bool quiet, std::optional<double> time_limit,
             bool allow_unconverged) {
    // The calling thread may not be the importing one (a thread pool's, a
    // Dask worker's): its OpenMP regions serial too, so that the digits do
    // not depend on which thread solves (runtime/openmp_threads.h).
    SerialOpenMpInThisThread();
    // The time limit counts from the call.
    auto control = std::make_shared<SolveControl>(time_limit);
    const MaterialArgs material =
        MakeMaterialArgs(mu, lambda, eta, relative_eta, bending, membrane);
    return f(args..., material,
             SolverOptions{tolerance, max_iterations, threads, quiet,
                           allow_unconverged, std::move(control)});
  };
}
template <class Result, class... Params>
auto WithMaterialArgs(Result (*f)(Params...)) {
  using Own = std::tuple<Params...>;
  static_assert(std::is_same_v<std::tuple_element_t<sizeof...(Params) - 1, Own>,
                               const MaterialArgs&>);
  return GatherMaterialArgs<Own>(
      f, std::make_index_sequence<sizeof...(Params) - 1>());
}
template <class Result, class... Params>
auto WithMaterialAndSolverArgs(Result (*f)(Params...)) {
  using Own = std::tuple<Params...>;
  static_assert(std::is_same_v<std::tuple_element_t<sizeof...(Params) - 2, Own>,
                               const MaterialArgs&> &&
                std::is_same_v<std::tuple_element_t<sizeof...(Params) - 1, Own>,
                               const SolverOptions&>);
  return GatherMaterialAndSolverArgs<Own>(
      f, std::make_index_sequence<sizeof...(Params) - 2>());
}

// The functions of each room, added to the module (python/module_<room>.cc).
void RegisterIo(py::module_& m);
void RegisterEnergy(py::module_& m);
void RegisterCalculus(py::module_& m);
void RegisterSplines(py::module_& m);
void RegisterStatistics(py::module_& m);
void RegisterCollections(py::module_& m);
void RegisterBranching(py::module_& m);
void RegisterRender(py::module_& m);

}  // namespace pymodule
}  // namespace shellspace

// The keyword arguments shared by the verbs. A default that the library
// has is taken from its Options or settings struct (as the CLI's flag
// tables take theirs: one source per default).
#define SHELLSPACE_MATERIAL_ARGS                                            \
  py::arg("mu") = ShellMaterial().mu,                                       \
  py::arg("lambda_") = ShellMaterial().lambda, py::arg("eta") = py::none(), \
  py::arg("relative_eta") = DefaultRelativeEtaObject(),                     \
  py::arg("bending") =                                                      \
      std::string(BendingModelName(ShellMaterial().bending_model)),         \
  py::arg("membrane") =                                                     \
      std::string(MembraneLawName(ShellMaterial().membrane_law))
#define SHELLSPACE_SOLVER_ARGS                                                 \
  py::arg("tolerance") = SolverSettings().gradient_tolerance,                  \
  py::arg("max_iterations") = SolverSettings().max_iterations,                 \
  py::arg("threads") = SolverSettings().num_threads, py::arg("quiet") = false, \
  py::arg("time_limit") = py::none(), py::arg("allow_unconverged") = false
// The first arguments of the verbs that solve a geodesic (geodesic, log).
#define SHELLSPACE_GEODESIC_ARGS                                             \
  py::arg("start"), py::arg("end"), py::arg("F"),                            \
      py::arg("steps") = workflows::GeodesicOptions().steps,                 \
      py::arg("mask") = py::none(),                                          \
      py::arg("multires") =                                                  \
          MultiresolutionWord(workflows::GeodesicOptions().multires),        \
      py::arg("linear_solver") =                                             \
          PathLinearSolverWord(workflows::GeodesicOptions().linear_solver),  \
      py::arg("lm") = GeodesicLmWord(workflows::GeodesicOptions().lm),       \
      py::arg("init") = std::string(                                         \
          GeodesicInitName(workflows::GeodesicOptions().init))
// The files of the verbs that write a path's frames: the frames' directory,
// a film strip (PNG), a glTF 2.0 animation (.glb); none by default.
#define SHELLSPACE_FRAME_OUTPUT_ARGS                              \
  py::arg("output") = py::none(), py::arg("png") = py::none(), \
      py::arg("gltf") = py::none()

// relative_eta: a float (strict_numbers.h), shown as one in signatures,
// given unless it is the default object itself.
namespace pybind11 {
namespace detail {
template <>
struct type_caster<shellspace::pymodule::RelativeEtaArg> {
  PYBIND11_TYPE_CASTER(shellspace::pymodule::RelativeEtaArg,
                       const_name("float"));
  bool load(handle src, bool convert) {
    make_caster<double> number;
    if (!number.load(src, convert)) return false;
    value.value = cast_op<double>(number);
    value.given = !src.is(shellspace::pymodule::DefaultRelativeEtaObject());
    return true;
  }
  static handle cast(const shellspace::pymodule::RelativeEtaArg& arg,
                     return_value_policy /* policy */, handle /* parent */) {
    return arg.given
               ? PyFloat_FromDouble(arg.value)
               : shellspace::pymodule::DefaultRelativeEtaObject().inc_ref();
  }
};
}  // namespace detail
}  // namespace pybind11

#endif  // SHELLSPACE_PYTHON_MODULE_COMMON_H_
