// The Python module `shellspace`: the library's functions on NumPy arrays.
//
// A mesh is a pair (V, F): V a #V x 3 float64 array of vertex positions, F a
// #F x 3 integer array of counter-clockwise triangles; every shape of one
// call shares F. A path is a (K + 1) x #V x 3 array. Each function of a CLI
// verb takes that verb's options as keyword arguments with the verb's
// defaults (`shellspace VERB --help`), calls the library functions the verb
// calls, and returns its results and the verb's --json summary as a dict
// (reports/: the same objects the CLI prints; `output` and `seconds` as the
// CLI has them). Bad input raises shellspace.InputError (a ValueError) with
// the library's message; other library errors RuntimeError. Every array
// argument is checked by python/array_arguments.h. The functions that
// solve take time_limit and allow_unconverged, stop at KeyboardInterrupt,
// and raise shellspace.NotConvergedError for a result that missed its
// stopping criterion (python/solve_control.h); their steps are bounded up
// front by the CLI's memory estimates (tools/run/memory_limits.h).
#include <glog/logging.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <dlfcn.h>
#include <pybind11/stl.h>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/runtime/openmp_threads.h"
#include "shellspace/geometry/rigid_alignment.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/gltf_writer.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/io/png_writer.h"
#include "shellspace/problems/branching/construction_optimizer.h"
#include "shellspace/problems/branching/general_construction.h"
#include "shellspace/problems/branching/simulation.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/problems/calculus/parallel_transport.h"
#include "shellspace/problems/calculus/shape_comparison.h"
#include "shellspace/problems/splines/ltheta_spline.h"
#include "shellspace/problems/splines/spline.h"
#include "shellspace/problems/splines/spline_initial_path.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/problems/statistics/leave_one_out.h"
#include "shellspace/problems/statistics/procrustes_pca.h"
#include "shellspace/problems/statistics/shell_pca.h"
#include "shellspace/solvers/gauge_reduced_solve.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/reports/branching_reports.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/reports/shape_reports.h"
#include "shellspace/reports/solve_choices.h"
#include "python/array_arguments.h"
#include "python/solve_control.h"
// The CLI's memory bounds of --steps (compiled into the module,
// python/CMakeLists.txt).
#include "tools/run/memory_limits.h"

namespace py = pybind11;

namespace shellspace {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// ---- Arrays -------------------------------------------------------------
// Every array argument is read by python/array_arguments.h (dtype, shape,
// finite values, indices in range, any strides); results are new arrays.

py::array_t<double> FromPositions(const Positions& positions) {
  py::array_t<double> out({static_cast<py::ssize_t>(positions.rows()),
                           static_cast<py::ssize_t>(3)});
  std::copy(positions.data(), positions.data() + positions.size(),
            out.mutable_data());
  return out;
}

py::array_t<long long> FromFaces(const Faces& faces) {
  py::array_t<long long> out(
      {static_cast<py::ssize_t>(faces.rows()), static_cast<py::ssize_t>(3)});
  for (Eigen::Index i = 0; i < faces.size(); ++i) {
    out.mutable_data()[i] = faces.data()[i];
  }
  return out;
}

// A path as a (K + 1) x #V x 3 array.
py::array_t<double> FromPath(const std::vector<Positions>& path) {
  const py::ssize_t n = path.empty() ? 0 : path[0].rows();
  py::array_t<double> out(
      {static_cast<py::ssize_t>(path.size()), n, static_cast<py::ssize_t>(3)});
  double* data = out.mutable_data();
  for (const Positions& shape : path) {
    std::copy(shape.data(), shape.data() + shape.size(), data);
    data += shape.size();
  }
  return out;
}

py::object ToDict(const JsonObject& json) {
  return py::module_::import("json").attr("loads")(json.str());
}

// ---- Inputs -------------------------------------------------------------

// A validated shell (V, F) and its topology.
struct Shell {
  Mesh mesh;
  Topology topology;
};

// The shell of checked positions and the faces F (indices in [0, #V)).
Shell MakeShell(Positions positions, const py::object& F,
                const std::string& name) {
  Shell shell;
  const int num_vertices = static_cast<int>(positions.rows());
  shell.mesh = Mesh{std::move(positions), FacesArgument(F, "F", num_vertices)};
  shell.topology = ValidateShell(shell.mesh, name);
  return shell;
}

Shell MakeShell(const py::object& V, const py::object& F,
                const std::string& name) {
  return MakeShell(PositionsArgument(V, name), F, name);
}

// Positions of a pose of `like` (same vertex count), validated.
Positions CompatiblePositions(const Positions& positions, const Shell& like,
                              const std::string& name) {
  if (positions.rows() != like.mesh.positions.rows()) {
    throw InputError(name + " has " + std::to_string(positions.rows()) +
                     " vertices, expected " +
                     std::to_string(like.mesh.positions.rows()));
  }
  ValidateShellPositions(Mesh{positions, like.mesh.faces}, like.topology, name);
  return positions;
}

Positions CompatiblePositions(const py::object& V, const Shell& like,
                              const std::string& name) {
  return CompatiblePositions(PositionsArgument(V, name), like, name);
}

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
// bending model (the CLI's --bending).
struct MaterialArgs {
  double mu = 1;
  double lambda = 1;
  std::optional<double> eta;
  double relative_eta = kDefaultRelativeEta;
  std::string bending = "discrete-shells";  // the CLI's --bending
};

ShellMaterial Material(const MaterialArgs& args, const Mesh& reference) {
  ShellMaterial material;
  if (!ParseBendingModel(args.bending, &material.bending_model)) {
    throw InputError("bending: unknown bending model '" + args.bending +
                     "' (discrete-shells or shape-operator; the edge-angle "
                     "variant is evaluated only by the `energy` verb of the "
                     "CLI)");
  }
  material.mu = args.mu;
  material.lambda = args.lambda;
  material.eta = args.eta ? *args.eta
                          : EtaFromRelative(args.relative_eta, reference);
  material.Validate();
  return material;
}

// The material as resolved for `reference` (the CLI's "material" record).
std::string MaterialRecord(const ShellSpace& space, const Mesh& reference,
                           const MaterialArgs& args) {
  return MaterialJson(space.material, reference, args.eta.has_value()).str();
}

ShellPair MakeShellPair(const py::object& first, const py::object& second,
                        const py::object& F, const std::string& first_name,
                        const std::string& second_name,
                        const MaterialArgs& material_args) {
  ShellPair pair;
  pair.first = MakeShell(first, F, first_name);
  pair.second = CompatiblePositions(second, pair.first, second_name);
  pair.space = ShellSpace(pair.first.mesh, pair.first.topology,
                          Material(material_args, pair.first.mesh));
  return pair;
}

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
    settings.stop = control->Poll();
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
JsonObject& AddStopFields(JsonObject& json, const SolveControl& control) {
  return json.Add("partial", control.stopped())
      .Add("stop_reason", control.stop_reason());
}

void CheckAtLeast(const std::string& name, long value, long min) {
  if (value < min) {
    throw InputError(name + " must be >= " + std::to_string(min) + ", got " +
                     std::to_string(value));
  }
}

// `steps` of a solve the CLI bounds up front: in [min, kMaxSteps] and its
// memory estimate `bytes` (tools/run/memory_limits.h, the model `model`)
// within half the physical memory.
void CheckSteps(const std::string& name, long steps, long min, double bytes,
                int vertices, const std::string& model) {
  CheckAtLeast(name, steps, min);
  if (steps > kMaxSteps) {
    throw InputError(name + " must be <= " + std::to_string(kMaxSteps) +
                     ", got " + std::to_string(steps));
  }
  CheckMemory(bytes,
              name + " " + std::to_string(steps) + " on " +
                  std::to_string(vertices) + " vertices",
              model);
}

// The memory models of tools/run/memory_limits.h, as the CLI words them.
const char* const kGeodesicModel = "64 MB + 1500 B x #V x K^2";
const char* const kPathModel = "64 MB + 200 B x #V x (K + 1)";

// ---- Outputs ------------------------------------------------------------

// What a path verb writes: `output` (a directory of shape_000.ply ...),
// `png` (a film strip) and `gltf` (a .glb morph animation,
// io/gltf_writer.h), each if given (not None).
void WritePath(const std::optional<std::string>& output,
               const std::optional<std::string>& png,
               const std::optional<std::string>& gltf, const Faces& faces,
               const std::vector<Positions>& path) {
  RenderOptions options;
  if (png) ValidateRenderOptions(options);
  AtomicFileSet files;  // all together or none, as the CLI
  if (gltf) files.Add(*gltf, EncodeGltfMorphAnimation(path, faces));
  if (png) files.Add(*png, EncodePng(RenderFilmStrip(path, faces, options)));
  if (output) AddFrames(*output, faces, path, &files);
  files.Commit();
}

JsonObject& AddOutput(JsonObject& json,
                      const std::optional<std::string>& output) {
  if (output) json.Add("output", *output);
  return json;
}

ShellSide Side(const std::string& side, const std::string& name) {
  if (side == "reference") return ShellSide::kReference;
  if (side == "deformed") return ShellSide::kDeformed;
  throw InputError(name + " must be 'reference' or 'deformed', got '" + side +
                   "'");
}

// ---- The functions ------------------------------------------------------

py::tuple ReadMeshPy(const std::string& path) {
  const Mesh mesh = ReadMesh(path);
  return py::make_tuple(FromPositions(mesh.positions), FromFaces(mesh.faces));
}

void WriteMeshPy(const std::string& path, const py::object& V,
                 const py::object& F) {
  Positions positions = PositionsArgument(V, "V");
  const int num_vertices = static_cast<int>(positions.rows());
  const Mesh mesh{std::move(positions), FacesArgument(F, "F", num_vertices)};
  ValidateMeshStructure(mesh, path);
  WriteMesh(mesh, path);
}

py::object EnergyPy(const py::object& reference, const py::object& deformed,
                    const py::object& F, const MaterialArgs& material_args) {
  const auto [shell, d, space] =
      MakeShellPair(reference, deformed, F, "reference", "deformed",
                    material_args);
  const DeformationEnergy e =
      EvaluateDeformationEnergy(space, shell.mesh.positions, d);
  return ToDict(EnergyJson(e, space.material));
}

py::array_t<double> GradientPy(const py::object& reference,
                               const py::object& deformed, const py::object& F,
                               const std::string& side, const MaterialArgs& material_args) {
  const auto [shell, d, space] =
      MakeShellPair(reference, deformed, F, "reference", "deformed",
                    material_args);
  const Eigen::VectorXd g =
      EnergyGradient(space, shell.mesh.positions, d, Side(side, "side"));
  Positions out(shell.mesh.num_vertices(), 3);
  std::copy(g.data(), g.data() + g.size(), out.data());
  return FromPositions(out);
}

py::tuple HessianPy(const py::object& reference, const py::object& deformed,
                    const py::object& F, const std::string& rows,
                    const std::string& cols, const MaterialArgs& material_args) {
  const auto [shell, d, space] =
      MakeShellPair(reference, deformed, F, "reference", "deformed",
                    material_args);
  const SparseMatrix H = EnergyHessian(space, shell.mesh.positions, d,
                                       Side(rows, "rows"), Side(cols, "cols"));
  const py::ssize_t nnz = H.nonZeros();
  py::array_t<long long> r(nnz), c(nnz);
  py::array_t<double> v(nnz);
  py::ssize_t i = 0;
  for (int k = 0; k < H.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(H, k); it; ++it, ++i) {
      r.mutable_data()[i] = it.row();
      c.mutable_data()[i] = it.col();
      v.mutable_data()[i] = it.value();
    }
  }
  return py::make_tuple(r, c, v);
}

// The step of a Newton iteration on a rigidly invariant energy of one
// shell, for a client that sums the Hessian and gradient itself
// (shellspace.collections.elastic_mean): p = T q with T =
// RigidGaugeBasis(shape) (solvers/gauge_reduced_solve.h) and
// (T^T H T + shift I) q = T^T rhs by sparse LDL^T. Returns (p #V x 3,
// positive_definite: every pivot of the reduced matrix > 0).
py::tuple SolveModuloRigidMotionsPy(const py::object& rows_object,
                                    const py::object& cols_object,
                                    const py::object& vals_object,
                                    const py::object& rhs_object,
                                    const py::object& shape_object,
                                    double shift) {
  const Positions shape = PositionsArgument(shape_object, "shape");
  const Positions rhs = PositionsArgument(rhs_object, "rhs");
  const long long n = 3 * static_cast<long long>(shape.rows());
  if (rhs.rows() != shape.rows()) {
    throw InputError("rhs: " + std::to_string(rhs.rows()) +
                     " rows, expected " + std::to_string(shape.rows()));
  }
  const IndexValues rows = CheckedIndexArray(rows_object, "rows", {{"nnz"}});
  const IndexValues cols =
      CheckedIndexArray(cols_object, "cols", {{"nnz", static_cast<py::ssize_t>(rows.values.size())}});
  const RealValues vals = CheckedRealArray(
      vals_object, "vals", {{"nnz", static_cast<py::ssize_t>(rows.values.size())}});
  if (!(shift >= 0) || !std::isfinite(shift)) {
    throw InputError("shift must be finite and >= 0");
  }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(rows.values.size());
  for (size_t k = 0; k < rows.values.size(); ++k) {
    const long long r = rows.values[k], c = cols.values[k];
    if (r < 0 || r >= n || c < 0 || c >= n) {
      throw InputError("rows/cols: index outside 0.." + std::to_string(n - 1));
    }
    triplets.emplace_back(static_cast<int>(r), static_cast<int>(c),
                          vals.values[k]);
  }
  SparseMatrix h(n, n);
  h.setFromTriplets(triplets.begin(), triplets.end());
  const SparseMatrix basis = RigidGaugeBasis(shape);
  SparseMatrix reduced = SparseMatrix(basis.transpose() * h * basis);
  if (shift > 0) {
    SparseMatrix identity(reduced.rows(), reduced.cols());
    identity.setIdentity();
    reduced += shift * identity;
  }
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(reduced);
  const bool factorised = ldlt.info() == Eigen::Success;
  const bool positive = factorised && ldlt.vectorD().minCoeff() > 0;
  Positions p = Positions::Zero(shape.rows(), 3);
  if (factorised) {
    const Eigen::VectorXd flat_rhs =
        Eigen::Map<const Eigen::VectorXd>(rhs.data(), rhs.size());
    const Eigen::VectorXd step = basis * ldlt.solve(basis.transpose() * flat_rhs);
    std::copy(step.data(), step.data() + step.size(), p.data());
  }
  return py::make_tuple(FromPositions(p), positive && p.allFinite());
}

void CheckGeodesic(const GeodesicResult& result) {
  if (!result.failure.empty()) {
    throw InputError("solver failed: " + result.failure);
  }
}

// The geodesic between two arrays of one mesh (geodesic, log): the start
// shell and the (multiresolution) solve.
struct GeodesicPySolve {
  Shell start;
  ShellSpace space;
  MultiresolutionResult multi;
};

GeodesicPySolve SolveGeodesicPy(const py::object& start_v,
                                const py::object& end_v, const py::object& F,
                                int steps, const py::object& mask,
                                const std::string& multires,
                                const std::string& linear_solver,
                                const std::string& lm, const std::string& init,
                                const MaterialArgs& material_args,
                                const SolverSettings& settings,
                                SolveControl& control) {
  CheckAtLeast("steps", steps, 1);
  ShellPair pair =
      MakeShellPair(start_v, end_v, F, "start", "end", material_args);
  const int vertices = pair.first.mesh.num_vertices();
  CheckSteps("steps", steps, 1, GeodesicBytes(vertices, steps), vertices,
             kGeodesicModel);
  GeodesicInput input;
  input.start = pair.first.mesh.positions;
  input.end = pair.second;
  input.steps = steps;
  input.fixed_vertices = MaskArgument(mask, vertices);
  input.linear_solver = ParsePathLinearSolver(linear_solver, "linear_solver");
  input.lm = ParseGeodesicLm(lm, "lm");
  input.init = ParseGeodesicInit(init, "init");
  const MultiresolutionSettings levels =
      ParseMultiresolution(multires, vertices, "multires");
  GeodesicPySolve solve;
  {
    SolveControl::Solving solving(control);
    solve.multi =
        SolveGeodesicMultiresolution(pair.space, input, settings, levels);
  }
  solve.start = std::move(pair.first);
  solve.space = std::move(pair.space);
  return solve;
}

// What an unconverged geodesic missed (the CLI's text).
std::vector<std::string> GeodesicFailures(const GeodesicResult& result,
                                          const std::string& what) {
  if (result.converged) return {};
  return {what + ": |grad| " + Short(result.final_gradient) +
          " above the target " + Short(result.gradient_target) +
          " (tolerance x max(1, |grad_0|)) after " +
          std::to_string(result.iterations) + " iterations (" +
          (result.stages.empty() ? std::string("no stages")
                                 : result.stages.back().termination) +
          ")"};
}

py::object GeodesicPy(const py::object& start_v, const py::object& end_v,
                      const py::object& F, int steps, const py::object& mask,
                      const std::string& multires,
                      const std::string& linear_solver, const std::string& lm,
                      const std::string& init,
                      bool report, const std::optional<std::string>& output,
                      const std::optional<std::string>& png,
                      const std::optional<std::string>& gltf,
                      const MaterialArgs& material_args,
                      const SolverOptions& solver) {
  const auto clock = Clock::now();
  const auto [start, space, multi] = SolveGeodesicPy(
      start_v, end_v, F, steps, mask, multires, linear_solver, lm, init,
      material_args, solver.Settings("geodesic"), *solver.control);
  const GeodesicResult& result = multi.geodesic;
  CheckGeodesic(result);
  if (report)
    py::print(result.summary.FullReport(),
              py::arg("file") = py::module_::import("sys").attr("stderr"));
  WritePath(output, png, gltf, start.mesh.faces, result.path);
  JsonObject json = GeodesicJson(result);
  json.Raw("multires_levels", MultiresolutionJson(multi))
      .Add("prolongation", ProlongationJson(multi.prolongation))
      .Raw("energy_split", PathEnergySplitJson(space, result.path))
      .Raw("material", MaterialRecord(space, start.mesh, material_args))
      .Add("seconds", Seconds(clock));
  AddStopFields(json, *solver.control);
  const py::object summary = ToDict(AddOutput(json, output));
  return solver.Finish(py::make_tuple(FromPath(result.path), summary), summary,
                       "geodesic", GeodesicFailures(result, "geodesic"));
}

py::object LogPy(const py::object& start_v, const py::object& end_v,
                 const py::object& F, int steps, const py::object& mask,
                 const std::string& multires, const std::string& linear_solver,
                 const std::string& lm, const std::string& init,
                 const std::optional<std::string>& output,
                 const MaterialArgs& material_args,
                 const SolverOptions& solver) {
  const auto clock = Clock::now();
  const auto [start, space, multi] = SolveGeodesicPy(
      start_v, end_v, F, steps, mask, multires, linear_solver, lm, init,
      material_args, solver.Settings("log"), *solver.control);
  const GeodesicResult& geodesic = multi.geodesic;
  const Positions log = LogOfGeodesic(geodesic.path);
  if (output) {
    WriteMesh(Mesh{start.mesh.positions + log, start.mesh.faces}, *output);
  }
  JsonObject json = GeodesicJson(geodesic);
  json.Raw("multires_levels", MultiresolutionJson(multi))
      .Add("prolongation", ProlongationJson(multi.prolongation))
      .Raw("energy_split", PathEnergySplitJson(space, geodesic.path))
      .Raw("material", MaterialRecord(space, start.mesh, material_args))
      .Add("log_max_norm", log.cwiseAbs().maxCoeff())
      .Add("seconds", Seconds(clock));
  AddStopFields(json, *solver.control);
  const py::object summary = ToDict(AddOutput(json, output));
  return solver.Finish(py::make_tuple(FromPositions(log), summary), summary,
                       "log", GeodesicFailures(geodesic, "log: the geodesic"));
}

py::object ShootPy(const py::object& first_v, const py::object& second_v,
                   const py::object& F, int steps, bool backward,
                   const py::object& mask,
                   const std::optional<std::string>& output,
                   const std::optional<std::string>& png,
                   const std::optional<std::string>& gltf,
                   const MaterialArgs& material_args,
                   const SolverOptions& solver) {
  const auto clock = Clock::now();
  CheckAtLeast("steps", steps, 1);
  const auto [first, second, space] = MakeShellPair(
      first_v, second_v, F, "first", "second", material_args);
  const int vertices = first.mesh.num_vertices();
  CheckSteps("steps", steps, 1, PathBytes(vertices, steps + 1), vertices,
             kPathModel);
  const std::vector<int> fixed = MaskArgument(mask, vertices);
  const SolverSettings settings = solver.Settings("shoot");
  ShootResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = ShootWithReport(
        space, first.mesh.positions, second, steps,
        backward ? StepDirection::kBackward : StepDirection::kForward, fixed,
        settings);
  }
  // An EXP step without a root is the CLI's unsolved step (exit 4).
  std::vector<std::string> failures;
  for (size_t i = 0; i < result.exp_steps.size(); ++i) {
    const ExpStepResult& step = result.exp_steps[i];
    if (step.solved) continue;
    failures.push_back("EXP step " + std::to_string(i + 1) +
                       " not solved: relative residual " +
                       Short(step.relative_residual) + " > " +
                       Short(kExpStepAcceptance));
  }
  WritePath(output, png, gltf, first.mesh.faces, result.path);
  JsonObject json = ShootJson(result);
  json.Raw("energy_split", PathEnergySplitJson(space, result.path))
      .Raw("material", MaterialRecord(space, first.mesh, material_args))
      .Add("seconds", Seconds(clock));
  AddStopFields(json, *solver.control);
  const py::object summary = ToDict(AddOutput(json, output));
  return solver.Finish(py::make_tuple(FromPath(result.path), summary), summary,
                       "shoot", std::move(failures));
}

py::object TransportPy(const py::object& path_object,
                       const py::object& variation_v, const py::object& F,
                       double epsilon, const py::object& mask,
                       const std::optional<std::string>& output,
                       const std::optional<std::string>& png,
                       const std::optional<std::string>& gltf,
                       const MaterialArgs& material_args,
                       const SolverOptions& solver) {
  const auto clock = Clock::now();
  if (!(epsilon > 0) || !std::isfinite(epsilon)) {
    throw InputError("epsilon must be > 0, got " + std::to_string(epsilon));
  }
  const std::vector<Positions> frames = ShapeListArgument(path_object, "path");
  if (frames.size() < 2) throw InputError("path: need at least 2 frames");
  const Shell first = MakeShell(frames[0], F, "path[0]");
  ShellPath path = {first.mesh.positions};
  for (size_t k = 1; k < frames.size(); ++k) {
    path.push_back(CompatiblePositions(frames[k], first,
                                       "path[" + std::to_string(k) + "]"));
  }
  const Positions varied = CompatiblePositions(variation_v, first, "variation");
  const ShellSpace space(first.mesh, first.topology, Material(material_args, first.mesh));
  const std::vector<int> fixed = MaskArgument(mask, first.mesh.num_vertices());
  const SolverSettings settings = solver.Settings("transport");
  TransportResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = ParallelTransport(space, path, varied - first.mesh.positions,
                               epsilon, fixed, settings);
  }
  std::vector<std::string> failures;
  for (size_t k = 0; k < result.rungs.size(); ++k) {
    const TransportResult::Rung& rung = result.rungs[k];
    if (rung.solved) continue;
    failures.push_back("rung " + std::to_string(k + 1) +
                       " not solved: EXP residual " +
                       Short(rung.relative_residual) + " > " +
                       Short(kExpStepAcceptance) + " (also at epsilon / " +
                       std::to_string(rung.divisor) + ")");
  }
  WritePath(output, png, gltf, first.mesh.faces, result.shapes);
  JsonObject json = TransportJson(result, epsilon);
  json.Raw("energy_split", PathEnergySplitJson(space, result.shapes))
      .Raw("material", MaterialRecord(space, first.mesh, material_args))
      .Add("seconds", Seconds(clock));
  AddStopFields(json, *solver.control);
  const py::object summary = ToDict(AddOutput(json, output));
  return solver.Finish(py::make_tuple(FromPath(result.shapes), summary),
                       summary, "transport", std::move(failures));
}

// The shapes of a list (keyframes, inputs) with the connectivity F.
struct ShapeSet {
  Shell first;
  std::vector<Positions> shapes;
};

ShapeSet MakeShapeSet(const py::object& list, const py::object& F,
                      const std::string& name) {
  const std::vector<Positions> shapes = ShapeListArgument(list, name);
  ShapeSet set;
  set.first = MakeShell(shapes[0], F, name + "[0]");
  set.shapes.push_back(set.first.mesh.positions);
  for (size_t i = 1; i < shapes.size(); ++i) {
    set.shapes.push_back(CompatiblePositions(
        shapes[i], set.first, name + "[" + std::to_string(i) + "]"));
  }
  return set;
}

// The keyframe indices `at` (integers in [0, steps], strictly increasing;
// the library checks them against steps and periodicity), one per shape.
std::vector<int> Indices(const py::object& at_object, int steps, size_t shapes,
                         const std::string& name) {
  const std::vector<int> at = IndexListArgument(at_object, "at", 0, steps);
  for (size_t i = 1; i < at.size(); ++i) {
    if (at[i] <= at[i - 1]) throw InputError("at must be strictly increasing");
  }
  if (at.size() != shapes) {
    throw InputError("at gives " + std::to_string(at.size()) +
                     " indices for " + std::to_string(shapes) + " " + name);
  }
  return at;
}

// The outer L-BFGS polls the call's stop; the midpoint solves do not, so
// that every evaluation of F_K used stays exact (as the CLI).
SplineSettings SplineSettingsOf(const SolverOptions& solver,
                                const std::string& label) {
  SplineSettings settings;
  settings.inner = solver.Settings(label + " midpoint");
  settings.inner.progress = false;
  settings.inner.gradient_tolerance = 1e-10;
  settings.stop = settings.inner.stop;
  settings.inner.stop = nullptr;
  settings.max_iterations = solver.max_iterations;
  settings.gradient_tolerance = solver.tolerance;
  settings.progress = !solver.quiet;
  settings.progress_label = label;
  return settings;
}

// What an unconverged spline or regression missed (the CLI's text).
std::vector<std::string> SplineFailures(const SplineResult& result,
                                        const std::string& verb,
                                        double tolerance) {
  if (result.converged) return {};
  if (!result.evaluated) {
    return {verb + ": stopped before the first evaluation of F_K finished"};
  }
  return {verb + ": relative gradient " + Short(result.relative_gradient_norm) +
          " above the tolerance " + Short(tolerance) + " after " +
          std::to_string(result.iterations) + " L-BFGS iterations (" +
          ceres::TerminationTypeToString(result.summary.termination_type) +
          ")"};
}

// The path verbs' (spline, regress) bound of steps: kMaxSteps and the
// path's memory (tools/run/memory_limits.h's PathBytes).
void CheckPathSteps(int steps, int min, int vertices) {
  CheckSteps("steps", steps, min, PathBytes(vertices, steps + 1), vertices,
             kPathModel);
}

py::object SplinePy(const py::object& keyframes_object,
                    const py::object& at_object, const py::object& F,
                    int steps, const std::string& method,
                    const std::string& init, bool periodic,
                    const std::optional<std::string>& output,
                    const std::optional<std::string>& png,
                    const std::optional<std::string>& gltf,
                    const MaterialArgs& material_args,
                    const SolverOptions& solver) {
  if (method != "nonlinear" && method != "ltheta") {
    throw InputError("method must be nonlinear or ltheta");
  }
  CheckAtLeast("steps", steps, 2);
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(keyframes_object, F, "keyframes");
  CheckPathSteps(steps, 2, set.first.mesh.num_vertices());
  const std::vector<int> at =
      Indices(at_object, steps, set.shapes.size(), "keyframes");
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(material_args, set.first.mesh));
  const SplineInit initial_path = ParseSplineInit(init);
  if (method == "ltheta" && initial_path != SplineInit::kLTheta) {
    throw InputError("init " + init +
                     " needs method nonlinear (method ltheta is the LΘA "
                     "spline itself)");
  }
  SolverSettings init_settings = solver.Settings(init);
  init_settings.progress = false;
  SplineSettings settings = SplineSettingsOf(solver, "spline");
  if (method == "ltheta") settings.max_iterations = 0;
  SplineResult result;
  SplineInitialPath initial;
  {
    SolveControl::Solving solving(*solver.control);
    initial = MakeSplineInitialPath(initial_path, space, set.shapes, at, steps,
                                    periodic, init_settings);
    result = SolveSpline(space, set.shapes, at, steps, periodic, initial.path,
                         settings);
  }
  std::vector<std::string> failures;
  if (method == "ltheta") {
    // The LΘA spline alone converged if every frame's reconstruction did.
    const std::vector<int> frames = initial.ltheta.unconverged_frames();
    result.converged = frames.empty();
    std::string list;
    for (size_t i = 0; i < frames.size(); ++i) {
      list += (i ? ", " : "") + std::to_string(frames[i]);
    }
    if (!frames.empty()) {
      failures.push_back("spline: the LΘA reconstruction of frame(s) " + list +
                         " stopped short of the tolerance " +
                         Short(solver.tolerance));
    }
  } else {
    failures = SplineFailures(result, "spline", solver.tolerance);
  }
  WritePath(output, png, gltf, set.first.mesh.faces, result.path);
  JsonObject head;
  head.Add("method", method);
  AddSplineInitJson(head, initial);
  head.Raw("energy_split", PathEnergySplitJson(space, result.path))
      .Raw("material", MaterialRecord(space, set.first.mesh, material_args));
  JsonObject json = SplineJson(head, result, Seconds(clock));
  AddStopFields(json, *solver.control);
  const py::object summary = ToDict(AddOutput(json, output));
  return solver.Finish(py::make_tuple(FromPath(result.path), summary), summary,
                       "spline", std::move(failures));
}

py::object RegressPy(const py::object& inputs_object,
                     const py::object& at_object, const py::object& F,
                     int steps, double sigma,
                     const std::optional<std::string>& output,
                     const std::optional<std::string>& png,
                     const std::optional<std::string>& gltf,
                     const MaterialArgs& material_args,
                     const SolverOptions& solver) {
  CheckAtLeast("steps", steps, 2);
  if (!(sigma >= 0) || !std::isfinite(sigma)) {
    throw InputError("sigma must be >= 0, got " + std::to_string(sigma));
  }
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  CheckPathSteps(steps, 2, set.first.mesh.num_vertices());
  const std::vector<int> at =
      Indices(at_object, steps, set.shapes.size(), "inputs");
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(material_args, set.first.mesh));
  const SplineSettings settings = SplineSettingsOf(solver, "regress");
  SplineResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = SolveRegression(space, set.shapes, at, steps, sigma, {}, settings);
  }
  WritePath(output, png, gltf, set.first.mesh.faces, result.path);
  JsonObject head;
  head.Add("sigma", sigma);
  head.Raw("energy_split", PathEnergySplitJson(space, result.path))
      .Raw("material", MaterialRecord(space, set.first.mesh, material_args));
  JsonObject json = SplineJson(head, result, Seconds(clock));
  AddStopFields(json, *solver.control);
  const py::object summary = ToDict(AddOutput(json, output));
  return solver.Finish(py::make_tuple(FromPath(result.path), summary), summary,
                       "regress",
                       SplineFailures(result, "regress", solver.tolerance));
}

// What an unconverged elastic mean missed (the CLI's text).
std::vector<std::string> MeanFailures(const ElasticMeanResult& mean,
                                      const std::string& what) {
  if (mean.converged) return {};
  return {what + ": |grad| " + Short(mean.gradient_norm) +
          " above the target " + Short(mean.gradient_target) + " after " +
          std::to_string(mean.lm_iterations) + " LM + " +
          std::to_string(mean.newton_iterations) + " Newton iterations (" +
          mean.termination + ")"};
}

py::object MeanPy(const py::object& inputs_object, const py::object& F,
                  bool report, const std::optional<std::string>& output,
                  const MaterialArgs& material_args,
                  const SolverOptions& solver) {
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(material_args, set.first.mesh));
  const SolverSettings settings = solver.Settings("mean");
  ElasticMeanResult result;
  {
    SolveControl::Solving solving(*solver.control);
    result = ComputeElasticMean(space, set.shapes, settings);
  }
  if (result.summary.termination_type == ceres::FAILURE) {
    throw InputError("elastic mean failed: " + result.summary.message);
  }
  std::vector<std::string> far;
  for (int i : FarInputs(result.energies)) {
    far.push_back("inputs[" + std::to_string(i) + "]");
  }
  if (report)
    py::print(result.summary.FullReport(),
              py::arg("file") = py::module_::import("sys").attr("stderr"));
  if (output) WriteMesh(Mesh{result.mean, set.first.mesh.faces}, *output);
  JsonObject json = MeanJson(result, static_cast<int>(set.shapes.size()), far);
  json.Raw("energy_split", MeanEnergySplitJson(space, result.mean, set.shapes))
      .Raw("material", MaterialRecord(space, set.first.mesh, material_args))
      .Add("seconds", Seconds(clock));
  AddStopFields(json, *solver.control);
  const py::object summary = ToDict(AddOutput(json, output));
  return solver.Finish(py::make_tuple(FromPositions(result.mean), summary),
                       summary, "mean", MeanFailures(result, "elastic mean"));
}

// The `pca` verb: elastic mean, shell PCA modes shot by EXP_K, optionally
// the Procrustes baseline and the leave-one-out table. Returns ({name:
// shape} with the names of the CLI's files without ".ply", summary). A stop
// (time_limit, SIGINT) in any phase ends it with the mean alone, as the
// CLI: {'mean': ...} and "stopped_in" the phase, "modes": 0.
py::object PcaPy(const py::object& inputs_object, const py::object& F,
                 int modes, const std::string& baseline, bool loo,
                 double amplitude, int log_steps, int exp_steps,
                 int max_exp_steps, const std::string& displacement,
                 const std::optional<std::string>& output,
                 const std::optional<std::string>& png,
                 const MaterialArgs& material_args,
                 const SolverOptions& solver) {
  if (baseline != "" && baseline != "procrustes") {
    throw InputError("baseline must be 'procrustes' (or empty), got '" +
                     baseline + "'");
  }
  CheckAtLeast("modes", modes, 1);
  CheckAtLeast("log_steps", log_steps, 1);
  CheckAtLeast("exp_steps", exp_steps, 1);
  if (max_exp_steps < exp_steps) {
    throw InputError("max_exp_steps must be at least exp_steps");
  }
  if (!(amplitude >= 0) || !std::isfinite(amplitude)) {
    throw InputError("amplitude must be >= 0");
  }
  const ShellPcaOptions options = MakeShellPcaOptions(
      log_steps, exp_steps, max_exp_steps, displacement, "");
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  const int n = static_cast<int>(set.shapes.size());
  const int minimum = loo ? 3 : 2;
  if (n < minimum) {
    throw InputError("inputs needs at least " + std::to_string(minimum) +
                     " shells, got " + std::to_string(n));
  }
  CheckPcaModeCount(modes, n, loo, "");
  const int vertices = set.first.mesh.num_vertices();
  CheckSteps("log_steps", log_steps, 1, GeodesicBytes(vertices, log_steps),
             vertices, kGeodesicModel);
  CheckSteps("max_exp_steps", max_exp_steps, 1,
             PathBytes(vertices, max_exp_steps + 1), vertices, kPathModel);
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(material_args, set.first.mesh));
  const SolverSettings settings = solver.Settings("pca");
  SolverSettings inner = settings;
  inner.progress = false;
  SolveControl& control = *solver.control;

  std::vector<std::pair<std::string, Positions>> shapes;
  std::vector<Positions> strip;
  std::vector<std::string> failed_shapes, far;
  JsonObject json;
  ElasticMeanResult mean;
  std::string stopped_in;  // the phase a stop ended, or ""
  {
    SolveControl::Solving solving(control);
    mean = ComputeElasticMean(space, set.shapes, settings);
    if (mean.summary.termination_type == ceres::FAILURE) {
      throw InputError("elastic mean failed: " + mean.summary.message);
    }
    for (int i : FarInputs(mean.energies)) {
      far.push_back("inputs[" + std::to_string(i) + "]");
    }
    shapes.emplace_back("mean", mean.mean);
    strip.push_back(mean.mean);
    std::optional<ShellPcaModel> model;
    if (control.stopped()) {
      stopped_in = "mean";
    } else {
      model = ComputeShellPca(space, mean.mean, set.shapes, options, inner);
      if (control.stopped()) {
        stopped_in = "displacements";
        model.reset();
      }
    }
    const int shell_modes =
        model ? std::min<int>(modes, static_cast<int>(model->modes.size()))
              : 0;
    for (int j = 0; j < shell_modes; ++j) {
      for (const double sign : {-1.0, 1.0}) {
        if (control.stopped()) break;  // no new shot once stopped
        const std::string name =
            "mode_" + std::to_string(j + 1) + (sign < 0 ? "_minus" : "_plus");
        // A mode shape whose EXP shot has no solution is not returned; it
        // is listed in the summary (as the CLI does).
        Positions shape;
        if (TryShellModeShape(space, *model, j, sign * amplitude, options,
                              inner, &shape)) {
          shapes.emplace_back(name, shape);
          strip.push_back(std::move(shape));
        } else {
          failed_shapes.push_back(name + ".ply");
        }
      }
    }
    if (model && control.stopped()) stopped_in = "mode shapes";
    if (stopped_in.empty()) {
      json = PcaJson(n, mean, displacement, options, *model, shell_modes,
                     failed_shapes, far, amplitude);
      json.Raw("material",
               MaterialRecord(space, set.first.mesh, material_args));
      if (baseline == "procrustes") {
        for (auto& shape : AddProcrustesBaseline(
                 ComputeProcrustesPca(set.shapes), modes, amplitude, &json)) {
          shapes.push_back(std::move(shape));
        }
      }
      if (loo) {
        LeaveOneOutOptions loo_options;
        loo_options.max_modes = modes;
        loo_options.pca = options;
        loo_options.initial_mean = mean.mean;
        const LeaveOneOutTable table =
            EvaluateLeaveOneOut(space, set.shapes, loo_options, inner);
        if (control.stopped()) {
          stopped_in = "leave-one-out";
        } else {
          json.Raw("leave_one_out", LeaveOneOutJson(table));
        }
      }
    }
  }
  if (!stopped_in.empty()) {  // the mean alone
    shapes.resize(1);
    strip.resize(1);
    json = PcaMeanJson(n, mean);
    json.Add("modes", 0).Add("stopped_in", stopped_in);
    json.Raw("material", MaterialRecord(space, set.first.mesh, material_args));
  }
  json.Add("seconds", Seconds(clock));
  AddStopFields(json, control);
  AddOutput(json, output);
  if (output) {  // the CLI's files: the PLY set and pca.json, together
    MakeDirectory(*output);
    AtomicFileSet files;
    std::vector<Mesh> meshes;
    meshes.reserve(shapes.size());
    for (const auto& [name, positions] : shapes) {
      meshes.push_back(Mesh{positions, set.first.mesh.faces});
      const std::string path = *output + "/" + name + ".ply";
      files.Add(path, MeshWriter(meshes.back(), path));
    }
    files.Add(*output + "/pca.json", json.str() + "\n");
    files.Commit();
  }
  if (png && stopped_in.empty()) {
    WriteFilmStrip(strip, set.first.mesh.faces, RenderOptions(), *png);
  }
  py::dict out;
  for (const auto& [name, positions] : shapes) {
    out[py::str(name)] = FromPositions(positions);
  }
  const py::object summary = ToDict(json);
  return solver.Finish(py::make_tuple(out, summary), summary, "pca",
                       MeanFailures(mean, "the elastic mean"));
}

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
  JsonObject summary;
  {
    SolveControl::Solving solving(control);
    simulation.emplace(RunSimulation(s));
    const SimulationResult& result = *simulation;
    if (const std::string why = SimulationBreakdown(result); !why.empty()) {
      throw InputError("branching simulate: " + why);
    }
    summary = SimulationJson(s, result);
    if (delta_extrapolation >= 2 && !control.stopped()) {
      summary.Add("extrapolation",
                  DeltaExtrapolationJson(ExtrapolateDelta(
                      s, ExtrapolationWidths(result.delta,
                                             delta_extrapolation))));
    }
  }
  AddStopFields(summary, control);
  const SimulationResult& result = *simulation;
  const RelaxedGrid& g = result.field.grid;
  py::array_t<double> u(
      {static_cast<py::ssize_t>(g.nx + 1), static_cast<py::ssize_t>(g.ny)});
  for (int i = 0; i <= g.nx; ++i) {
    for (int j = 0; j < g.ny; ++j) {
      u.mutable_at(i, j) = result.field.at(i, j);
    }
  }
  const py::object dict = ToDict(summary);
  // The CLI judges no convergence here: only a time limit raises.
  return control.Finish(py::make_tuple(u, dict), dict, "branching simulate",
                        {}, allow_unconverged);
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

// `compare`: a and b each one #V x 3 array (a shell) or a sequence / #frames
// x #V x 3 array (a path), with the connectivity F.
py::object ComparePy(const py::object& a_object, const py::object& b_object,
                     const py::object& F, double tolerance,
                     double energy_tolerance, const MaterialArgs& material_args) {
  for (const auto& [name, value] :
       {std::pair{"tolerance", tolerance}, {"energy_tolerance", energy_tolerance}}) {
    if (!(value >= 0) || !std::isfinite(value)) {
      throw InputError(std::string(name) + " must be >= 0, got " +
                       std::to_string(value));
    }
  }
  const std::vector<Positions> a_shapes = ShapeOrListArgument(a_object, "a");
  const std::vector<Positions> b_shapes = ShapeOrListArgument(b_object, "b");
  const Shell first = MakeShell(a_shapes[0], F, "a[0]");
  ShellPath a, b;
  for (size_t k = 0; k < a_shapes.size(); ++k) {
    a.push_back(CompatiblePositions(a_shapes[k], first, "a[" + std::to_string(k) + "]"));
  }
  for (size_t k = 0; k < b_shapes.size(); ++k) {
    b.push_back(CompatiblePositions(b_shapes[k], first, "b[" + std::to_string(k) + "]"));
  }
  const ShellSpace space(first.mesh, first.topology, Material(material_args, first.mesh));
  return ToDict(ComparisonJson(CompareShapes(space, a, b), tolerance,
                               energy_tolerance));
}

// The frames of a path to draw (write_gltf, write_film_strip) and their
// faces: every frame with the first one's vertex count.
struct Frames {
  std::vector<Positions> shapes;
  Faces faces;
};

Frames FramesArgument(const py::object& frames_object, const py::object& F) {
  Frames frames;
  frames.shapes = ShapeListArgument(frames_object, "frames");
  const Eigen::Index vertices = frames.shapes[0].rows();
  for (size_t k = 1; k < frames.shapes.size(); ++k) {
    if (frames.shapes[k].rows() != vertices) {
      throw InputError("frames[" + std::to_string(k) + "] has " +
                       std::to_string(frames.shapes[k].rows()) +
                       " vertices, expected " + std::to_string(vertices));
    }
  }
  frames.faces = FacesArgument(F, "F", static_cast<int>(vertices));
  return frames;
}

void WriteGltfPy(const std::string& path, const py::object& frames_object,
                 const py::object& F, double fps,
                 const std::string& interpolation) {
  GltfAnimationOptions options;
  options.frames_per_second = fps;
  options.interpolation =
      ParseGltfInterpolation(interpolation, "interpolation");
  const Frames frames = FramesArgument(frames_object, F);
  WriteGltfMorphAnimation(path, frames.shapes, frames.faces, options);
}

// `shellspace render` on frames in memory: the same options, the same file.
void WriteFilmStripPy(const std::string& path, const py::object& frames_object,
                      const py::object& F, int width, int height,
                      const std::string& view, const std::string& up,
                      bool labels, const std::string& color,
                      const std::string& shading) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.view = ParseView(view);
  options.up = ParseUpAxis(up);
  options.labels = labels;
  options.color = ParseSurfaceColor(color);
  options.shading = ParseShading(shading);
  const Frames frames = FramesArgument(frames_object, F);
  WriteFilmStrip(frames.shapes, frames.faces, options, path);
}

// The Python signatures of the verb functions. A function f(args...,
// const MaterialArgs&) is bound as a function of args... followed by the
// material's keyword arguments (mu, lambda_, eta, relative_eta, bending: in
// the order of SHELLSPACE_MATERIAL_ARGS), gathered into a MaterialArgs; one
// that also ends with const SolverOptions& takes the solver's (tolerance,
// max_iterations, threads, quiet, time_limit, allow_unconverged:
// SHELLSPACE_SOLVER_ARGS) after them.
// The Gather functions take `Own`, the tuple of f's parameter types, and
// the indices of f's own arguments (those before the structs).
template <class Own, class Result, class... Params, size_t... I>
auto GatherMaterialArgs(Result (*f)(Params...), std::index_sequence<I...>) {
  return [f](std::tuple_element_t<I, Own>... args, double mu, double lambda,
             std::optional<double> eta, double relative_eta,
             const std::string& bending) {
    return f(args..., MaterialArgs{mu, lambda, eta, relative_eta, bending});
  };
}
template <class Own, class Result, class... Params, size_t... I>
auto GatherMaterialAndSolverArgs(Result (*f)(Params...),
                                 std::index_sequence<I...>) {
  return [f](std::tuple_element_t<I, Own>... args, double mu, double lambda,
             std::optional<double> eta, double relative_eta,
             const std::string& bending, double tolerance, int max_iterations,
             int threads, bool quiet, std::optional<double> time_limit,
             bool allow_unconverged) {
    // The calling thread may not be the importing one (a thread pool's, a
    // Dask worker's): its OpenMP regions serial too, so that the digits do
    // not depend on which thread solves (runtime/openmp_threads.h).
    SerialOpenMpInThisThread();
    // The time limit counts from the call.
    auto control = std::make_shared<SolveControl>(time_limit);
    return f(args..., MaterialArgs{mu, lambda, eta, relative_eta, bending},
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

}  // namespace
}  // namespace shellspace

// The keyword arguments shared by the verbs, with the CLI's defaults.
#define SHELLSPACE_MATERIAL_ARGS \
  py::arg("mu") = 1.0, py::arg("lambda_") = 1.0, py::arg("eta") = py::none(), \
      py::arg("relative_eta") = kDefaultRelativeEta,                          \
      py::arg("bending") = "discrete-shells"
#define SHELLSPACE_SOLVER_ARGS                                  \
  py::arg("tolerance") = 1e-8, py::arg("max_iterations") = 200, \
  py::arg("threads") = 2, py::arg("quiet") = false,             \
  py::arg("time_limit") = py::none(), py::arg("allow_unconverged") = false
// The first arguments of the verbs that solve a geodesic (geodesic, log).
#define SHELLSPACE_GEODESIC_ARGS                                        \
  py::arg("start"), py::arg("end"), py::arg("F"), py::arg("steps") = 8, \
      py::arg("mask") = py::none(), py::arg("multires") = "auto",       \
      py::arg("linear_solver") = "auto", py::arg("lm") = "auto",        \
      py::arg("init") = "auto"
// The files of the verbs that write a path's frames: the frames' directory,
// a film strip (PNG), a glTF 2.0 animation (.glb); none by default.
#define SHELLSPACE_FRAME_OUTPUT_ARGS                              \
  py::arg("output") = py::none(), py::arg("png") = py::none(), \
      py::arg("gltf") = py::none()

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
      "options as keyword arguments (lambda as lambda_) and returns its\n"
      "results and the verb's --json summary as a dict. Bad arrays and\n"
      "options raise InputError. The solving functions take time_limit\n"
      "(seconds) and allow_unconverged: an unconverged or time-limited\n"
      "result raises NotConvergedError (its .result attached) unless\n"
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

  m.def("read_mesh", &ReadMeshPy, py::arg("path"),
        "Reads a PLY, OBJ or OFF mesh (strict readers): returns (V, F).");
  m.def("write_mesh", &WriteMeshPy, py::arg("path"), py::arg("V"), py::arg("F"),
        "Writes (V, F) as PLY, OBJ or OFF (by the extension), atomically.");
  m.def("compare",
        WithMaterialArgs(&ComparePy),
        py::arg("a"), py::arg("b"), py::arg("F"),
        py::arg("tolerance") = 1e-6, py::arg("energy_tolerance") = 1e-6,
        SHELLSPACE_MATERIAL_ARGS,
        "Two shells (#V x 3 arrays) or two paths (sequences of them) up to "
        "rigid motion per frame: the `compare` verb's summary (max and mean "
        "vertex distance per frame, E_K of each path or W[a, b], `equal` "
        "against the tolerances).");
  m.def("write_gltf", &WriteGltfPy, py::arg("path"), py::arg("frames"),
        py::arg("F"), py::arg("fps") = 4.0, py::arg("interpolation") = "linear",
        "Writes frames (a path) as one glTF 2.0 morph animation (.glb), as "
        "`shellspace export` does.");
  m.def("write_film_strip", &WriteFilmStripPy, py::arg("path"),
        py::arg("frames"), py::arg("F"), py::arg("width") = 0,
        py::arg("height") = 0, py::arg("view") = "front",
        py::arg("up") = "auto", py::arg("labels") = true,
        py::arg("color") = "plain", py::arg("shading") = "gouraud",
        "Writes frames as a PNG film strip, as `shellspace render` does: "
        "width the whole image (0: 320 per column), height per frame (0: "
        "square), up auto|x|y|z|-x|-y|-z, labels under the frames, color "
        "plain|displacement.");
  m.def("read_mask", &ReadMask, py::arg("path"), py::arg("num_vertices"),
        "Reads a vertex mask file: sorted unique 0-based indices.");

  m.def(
      "energy",
      WithMaterialArgs(&EnergyPy),
      py::arg("reference"), py::arg("deformed"), py::arg("F"),
      SHELLSPACE_MATERIAL_ARGS,
      "W[reference, deformed] = W_mem + eta W_bend: the `energy` verb's "
      "summary {membrane, bending, total, mu, lambda, eta}.");
  m.def("energy_gradient",
        WithMaterialArgs(&GradientPy),
        py::arg("reference"),
        py::arg("deformed"), py::arg("F"), py::arg("side") = "deformed",
        SHELLSPACE_MATERIAL_ARGS,
        "D_2 W (side='deformed') or D_1 W (side='reference') as a #V x 3 "
        "array (the derivative by vertex v, coordinate c at [v, c]).");
  m.def("energy_hessian",
        WithMaterialArgs(&HessianPy),
        py::arg("reference"), py::arg("deformed"),
        py::arg("F"), py::arg("rows") = "deformed",
        py::arg("cols") = "deformed", SHELLSPACE_MATERIAL_ARGS,
        "The 3#V x 3#V block d_rows d_cols W (coordinate 3 v + c) as "
        "triplets (rows, cols, vals): scipy.sparse.coo_matrix((vals, (rows, "
        "cols)), shape=(3 * nV, 3 * nV)). rows/cols: 'deformed' or "
        "'reference' ('reference', 'deformed' is the mixed D_1 D_2 W).");

  m.def("solve_modulo_rigid_motions", &SolveModuloRigidMotionsPy,
        py::arg("rows"), py::arg("cols"), py::arg("vals"), py::arg("rhs"),
        py::arg("shape"), py::arg("shift") = 0.0,
        "p with (H + shift) p = rhs modulo rigid motions: H the 3#V x 3#V "
        "triplets (rows, cols, vals; duplicates summed) of a rigidly "
        "invariant energy's Hessian at `shape`, p = T q with T the "
        "coordinates left by the rigid gauge of `shape` and (T^T H T + "
        "shift I) q = T^T rhs (sparse LDL^T). Returns (p #V x 3, "
        "positive_definite).");
  m.def("align_rigidly", [](const py::object& source, const py::object& target) {
          const Positions s = PositionsArgument(source, "source");
          const Positions t = PositionsArgument(target, "target");
          if (s.rows() != t.rows()) {
            throw InputError("source and target: different vertex counts");
          }
          return FromPositions(AlignRigidly(s, t));
        }, py::arg("source"), py::arg("target"),
        "source moved by the rigid motion (rotation and translation, no "
        "reflection; unweighted Kabsch) that best fits it to target.");

  m.def(
      "geodesic",
      WithMaterialAndSolverArgs(&GeodesicPy), SHELLSPACE_GEODESIC_ARGS,
      py::arg("report") = false, SHELLSPACE_FRAME_OUTPUT_ARGS,
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS,
      "Discrete geodesic from start to end in `steps` steps: returns (path, "
      "summary). mask: vertex indices or a mask file held at their linear "
      "positions. lm: who runs the LM stages, 'auto' | 'ceres' | 'engine' "
      "(as the CLI's --lm). output: also write DIR/shape_000.ply ...; png: a "
      "film strip.");
  m.def(
      "log",
      WithMaterialAndSolverArgs(&LogPy), SHELLSPACE_GEODESIC_ARGS,
      py::arg("output") = py::none(), SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS,
      "LOG_K(start -> end) = K (s_1 - s_0) of the discrete geodesic: returns "
      "(log #V x 3, summary). output: write start + log (as the CLI).");
  m.def(
      "shoot",
      WithMaterialAndSolverArgs(&ShootPy),
      py::arg("first"), py::arg("second"), py::arg("F"), py::arg("steps") = 8,
      py::arg("backward") = false, py::arg("mask") = py::none(),
      SHELLSPACE_FRAME_OUTPUT_ARGS, SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS,
      "Geodesic shooting (EXP steps) from (first, second): returns (path, "
      "summary).");
  m.def(
      "transport",
      WithMaterialAndSolverArgs(&TransportPy),
      py::arg("path"), py::arg("variation"), py::arg("F"),
      py::arg("epsilon") = 1.0, py::arg("mask") = py::none(),
      SHELLSPACE_FRAME_OUTPUT_ARGS, SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS,
      "Schild's-ladder transport of variation - path[0] along path: returns "
      "(shapes s_k + epsilon xi_k, summary).");
  m.def(
      "spline",
      WithMaterialAndSolverArgs(&SplinePy),
      py::arg("keyframes"), py::arg("at"), py::arg("F"), py::arg("steps") = 8,
      py::arg("method") = "nonlinear", py::arg("init") = "ltheta",
      py::arg("periodic") = false, SHELLSPACE_FRAME_OUTPUT_ARGS,
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS,
      "Riemannian spline through keyframes at path indices `at`, from the "
      "initial path `init` (ltheta or geodesic, as the CLI's --init): returns "
      "(path, summary).");
  m.def(
      "regress",
      WithMaterialAndSolverArgs(&RegressPy),
      py::arg("inputs"), py::arg("at"), py::arg("F"), py::arg("steps") = 8,
      py::arg("sigma") = 1.0, SHELLSPACE_FRAME_OUTPUT_ARGS,
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS,
      "Shape regression (data term + sigma spline energy): returns (path, "
      "summary).");
  m.def(
      "pca",
      WithMaterialAndSolverArgs(&PcaPy),
      py::arg("inputs"), py::arg("F"), py::arg("modes") = 3,
      py::arg("baseline") = "", py::arg("loo") = false,
      py::arg("amplitude") = 1.0, py::arg("log_steps") = 2,
      py::arg("exp_steps") = 4, py::arg("max_exp_steps") = 16,
      py::arg("displacement") = "log", py::arg("output") = py::none(),
      py::arg("png") = py::none(), SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS,
      "Shell PCA at the elastic mean (and the Procrustes baseline, "
      "leave-one-out): returns ({'mean': ..., 'mode_1_minus': ..., ...}, "
      "summary). output: the CLI's directory (PLY files and pca.json).");
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
        py::arg("delta_extrapolation") = 0,
        py::arg("time_limit") = py::none(),
        py::arg("allow_unconverged") = false,
        "The relaxed Kohn-Mueller simulation (`branching simulate`): "
        "returns (u (nx + 1) x ny, summary). Writes no files. time_limit: "
        "seconds, then the field so far, partial (NotConvergedError unless "
        "allow_unconverged).");
  m.def("branching_construct", &BranchingConstructPy,
        py::arg("epsilon") = 0.001, py::arg("length") = 1.0,
        py::arg("family") = "km", py::arg("optimize") = false,
        py::arg("search") = false, py::arg("search_ratios") = "2,3,4",
        py::arg("search_pairs") = 2, py::arg("subintervals") = 3,
        py::arg("search_starts") = 1, py::arg("search_filter") = "",
        py::arg("search_threads") = 1,
        "A self-similar construction (`branching construct`): returns the "
        "summary. Writes no files.");
  m.def(
      "mean",
      WithMaterialAndSolverArgs(&MeanPy),
      py::arg("inputs"), py::arg("F"), py::arg("report") = false,
      py::arg("output") = py::none(), SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS,
      "Elastic mean argmin_s sum_i W[inputs_i, s]: returns (mean #V x 3, "
      "summary).");
}
