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
// the library's message; other library errors RuntimeError.
#include <glog/logging.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

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
#include "shellspace/geometry/openmp_threads.h"
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
#include "shellspace/render/film_strip.h"
#include "shellspace/reports/branching_reports.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/reports/shape_reports.h"
#include "shellspace/reports/solve_choices.h"

namespace py = pybind11;

namespace shellspace {
namespace {

using Clock = std::chrono::steady_clock;
using DoubleArray =
    py::array_t<double, py::array::c_style | py::array::forcecast>;
using IndexArray =
    py::array_t<long long, py::array::c_style | py::array::forcecast>;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// ---- Arrays -------------------------------------------------------------

Positions ToPositions(const DoubleArray& array, const std::string& name) {
  if (array.ndim() != 2 || array.shape(1) != 3) {
    throw InputError(name + " must be a #V x 3 array, got " +
                     std::to_string(array.ndim()) + " dimensions");
  }
  Positions positions(array.shape(0), 3);
  std::copy(array.data(), array.data() + array.size(), positions.data());
  return positions;
}

Faces ToFaces(const IndexArray& array) {
  if (array.ndim() != 2 || array.shape(1) != 3) {
    throw InputError("F must be a #F x 3 array of vertex indices");
  }
  Faces faces(array.shape(0), 3);
  for (py::ssize_t i = 0; i < array.size(); ++i) {
    const long long v = array.data()[i];
    if (v < 0 || v > std::numeric_limits<int>::max()) {
      throw InputError("F: face " + std::to_string(i / 3) +
                       " has the vertex index " + std::to_string(v));
    }
    faces.data()[i] = static_cast<int>(v);
  }
  return faces;
}

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

// A list of shapes: a K x #V x 3 array or a sequence of #V x 3 arrays.
std::vector<Positions> ToShapes(const py::object& object,
                                const std::string& name) {
  std::vector<Positions> shapes;
  if (py::isinstance<py::array>(object) &&
      object.cast<py::array>().ndim() == 3) {
    const DoubleArray array = object.cast<DoubleArray>();
    for (py::ssize_t k = 0; k < array.shape(0); ++k) {
      Positions shape(array.shape(1), 3);
      std::copy(array.data(k, 0, 0), array.data(k, 0, 0) + shape.size(),
                shape.data());
      shapes.push_back(shape);
    }
  } else {
    int k = 0;
    for (const py::handle item : object) {
      shapes.push_back(ToPositions(item.cast<DoubleArray>(),
                                   name + "[" + std::to_string(k++) + "]"));
    }
  }
  if (shapes.empty()) throw InputError(name + " is empty");
  return shapes;
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

Shell MakeShell(const DoubleArray& V, const IndexArray& F,
                const std::string& name) {
  Shell shell;
  shell.mesh = Mesh{ToPositions(V, name), ToFaces(F)};
  shell.topology = ValidateShell(shell.mesh, name);
  return shell;
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

Positions CompatiblePositions(const DoubleArray& V, const Shell& like,
                              const std::string& name) {
  return CompatiblePositions(ToPositions(V, name), like, name);
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

ShellPair MakeShellPair(const DoubleArray& first, const DoubleArray& second,
                        const IndexArray& F, const std::string& first_name,
                        const std::string& second_name,
                        const MaterialArgs& material_args) {
  ShellPair pair;
  pair.first = MakeShell(first, F, first_name);
  pair.second = CompatiblePositions(second, pair.first, second_name);
  pair.space = ShellSpace(pair.first.mesh, pair.first.topology,
                          Material(material_args, pair.first.mesh));
  return pair;
}

// The vertex mask: None, a mask file's path, or a sequence of 0-based
// vertex indices (sorted and made unique, as ReadMask returns them).
std::vector<int> Mask(const py::object& mask, int num_vertices) {
  if (mask.is_none()) return {};
  if (py::isinstance<py::str>(mask)) {
    return ReadMask(mask.cast<std::string>(), num_vertices);
  }
  std::vector<int> indices;
  for (const py::handle item : mask) {
    const long long v = item.cast<long long>();
    if (v < 0 || v >= num_vertices) {
      throw InputError("mask: vertex index " + std::to_string(v) +
                       " outside [0, " + std::to_string(num_vertices) + ")");
    }
    indices.push_back(static_cast<int>(v));
  }
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  return indices;
}

// The solver keywords of every call (the CLI's SolverFlags), checked by
// UserSolverSettings.
struct SolverOptions {
  double tolerance = 1e-8;
  int max_iterations = 200;
  int threads = 2;
  bool quiet = false;

  SolverSettings Settings(const std::string& label) const {
    return UserSolverSettings(tolerance, max_iterations, threads, quiet,
                              label);
  }
};

void CheckAtLeast(const std::string& name, long value, long min) {
  if (value < min) {
    throw InputError(name + " must be >= " + std::to_string(min) + ", got " +
                     std::to_string(value));
  }
}

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

void WriteMeshPy(const std::string& path, const DoubleArray& V,
                 const IndexArray& F) {
  const Mesh mesh{ToPositions(V, "V"), ToFaces(F)};
  ValidateMeshStructure(mesh, path);
  WriteMesh(mesh, path);
}

py::object EnergyPy(const DoubleArray& reference, const DoubleArray& deformed,
                    const IndexArray& F, const MaterialArgs& material_args) {
  const auto [shell, d, space] =
      MakeShellPair(reference, deformed, F, "reference", "deformed",
                    material_args);
  const DeformationEnergy e =
      EvaluateDeformationEnergy(space, shell.mesh.positions, d);
  return ToDict(EnergyJson(e, space.material));
}

py::array_t<double> GradientPy(const DoubleArray& reference,
                               const DoubleArray& deformed, const IndexArray& F,
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

py::tuple HessianPy(const DoubleArray& reference, const DoubleArray& deformed,
                    const IndexArray& F, const std::string& rows,
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

GeodesicPySolve SolveGeodesicPy(const DoubleArray& start_v,
                                const DoubleArray& end_v, const IndexArray& F,
                                int steps, const py::object& mask,
                                const std::string& multires,
                                const std::string& linear_solver,
                                const std::string& lm,
                                const MaterialArgs& material_args,
                                const SolverSettings& settings) {
  CheckAtLeast("steps", steps, 1);
  ShellPair pair =
      MakeShellPair(start_v, end_v, F, "start", "end", material_args);
  GeodesicInput input;
  input.start = pair.first.mesh.positions;
  input.end = pair.second;
  input.steps = steps;
  input.fixed_vertices = Mask(mask, pair.first.mesh.num_vertices());
  input.linear_solver = ParsePathLinearSolver(linear_solver, "linear_solver");
  input.lm = ParseGeodesicLm(lm, "lm");
  const MultiresolutionSettings levels = ParseMultiresolution(
      multires, pair.first.mesh.num_vertices(), "multires");
  GeodesicPySolve solve;
  {
    py::gil_scoped_release release;
    solve.multi =
        SolveGeodesicMultiresolution(pair.space, input, settings, levels);
  }
  solve.start = std::move(pair.first);
  solve.space = std::move(pair.space);
  return solve;
}

py::tuple GeodesicPy(const DoubleArray& start_v, const DoubleArray& end_v,
                     const IndexArray& F, int steps, const py::object& mask,
                     const std::string& multires,
                     const std::string& linear_solver, const std::string& lm,
                     bool report, const std::optional<std::string>& output,
                     const std::optional<std::string>& png,
                     const std::optional<std::string>& gltf, const MaterialArgs& material_args, const SolverOptions& solver) {
  const auto clock = Clock::now();
  const auto [start, space, multi] = SolveGeodesicPy(
      start_v, end_v, F, steps, mask, multires, linear_solver, lm,
      material_args, solver.Settings("geodesic"));
  const GeodesicResult& result = multi.geodesic;
  CheckGeodesic(result);
  if (report)
    py::print(result.summary.FullReport(),
              py::arg("file") = py::module_::import("sys").attr("stderr"));
  WritePath(output, png, gltf, start.mesh.faces, result.path);
  JsonObject json = GeodesicJson(result);
  json.Raw("multires_levels", MultiresolutionJson(multi))
      .Raw("energy_split", PathEnergySplitJson(space, result.path))
      .Raw("material", MaterialRecord(space, start.mesh, material_args))
      .Add("seconds", Seconds(clock));
  return py::make_tuple(FromPath(result.path), ToDict(AddOutput(json, output)));
}

py::tuple LogPy(const DoubleArray& start_v, const DoubleArray& end_v,
                const IndexArray& F, int steps, const py::object& mask,
                const std::string& multires, const std::string& linear_solver,
                const std::string& lm, const std::optional<std::string>& output,
                const MaterialArgs& material_args, const SolverOptions& solver) {
  const auto clock = Clock::now();
  const auto [start, space, multi] = SolveGeodesicPy(
      start_v, end_v, F, steps, mask, multires, linear_solver, lm,
      material_args, solver.Settings("log"));
  const GeodesicResult& geodesic = multi.geodesic;
  const Positions log = LogOfGeodesic(geodesic.path);
  if (output) {
    WriteMesh(Mesh{start.mesh.positions + log, start.mesh.faces}, *output);
  }
  JsonObject json = GeodesicJson(geodesic);
  json.Raw("multires_levels", MultiresolutionJson(multi))
      .Raw("energy_split", PathEnergySplitJson(space, geodesic.path))
      .Raw("material", MaterialRecord(space, start.mesh, material_args))
      .Add("log_max_norm", log.cwiseAbs().maxCoeff())
      .Add("seconds", Seconds(clock));
  return py::make_tuple(FromPositions(log), ToDict(AddOutput(json, output)));
}

py::tuple ShootPy(const DoubleArray& first_v, const DoubleArray& second_v,
                  const IndexArray& F, int steps, bool backward,
                  const py::object& mask,
                  const std::optional<std::string>& output,
                  const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf, const MaterialArgs& material_args, const SolverOptions& solver) {
  const auto clock = Clock::now();
  CheckAtLeast("steps", steps, 1);
  const auto [first, second, space] = MakeShellPair(
      first_v, second_v, F, "first", "second", material_args);
  const std::vector<int> fixed = Mask(mask, first.mesh.num_vertices());
  const SolverSettings settings = solver.Settings("shoot");
  ShootResult result;
  {
    py::gil_scoped_release release;
    result = ShootWithReport(
        space, first.mesh.positions, second, steps,
        backward ? StepDirection::kBackward : StepDirection::kForward, fixed,
        settings);
  }
  for (const ExpStepResult& step : result.exp_steps) {
    if (step.summary.termination_type == ceres::FAILURE) {
      throw InputError("EXP step failed: " + step.summary.message);
    }
  }
  WritePath(output, png, gltf, first.mesh.faces, result.path);
  JsonObject json = ShootJson(result);
  json.Raw("energy_split", PathEnergySplitJson(space, result.path))
      .Raw("material", MaterialRecord(space, first.mesh, material_args))
      .Add("seconds", Seconds(clock));
  return py::make_tuple(FromPath(result.path), ToDict(AddOutput(json, output)));
}

py::tuple TransportPy(const py::object& path_object,
                      const DoubleArray& variation_v, const IndexArray& F,
                      double epsilon, const py::object& mask,
                      const std::optional<std::string>& output,
                      const std::optional<std::string>& png,
                      const std::optional<std::string>& gltf, const MaterialArgs& material_args, const SolverOptions& solver) {
  const auto clock = Clock::now();
  if (!(epsilon > 0) || !std::isfinite(epsilon)) {
    throw InputError("epsilon must be > 0, got " + std::to_string(epsilon));
  }
  const std::vector<Positions> frames = ToShapes(path_object, "path");
  if (frames.size() < 2) throw InputError("path: need at least 2 frames");
  const Shell first =
      MakeShell(DoubleArray(FromPositions(frames[0])), F, "path[0]");
  ShellPath path = {first.mesh.positions};
  for (size_t k = 1; k < frames.size(); ++k) {
    path.push_back(CompatiblePositions(frames[k], first,
                                       "path[" + std::to_string(k) + "]"));
  }
  const Positions varied = CompatiblePositions(variation_v, first, "variation");
  const ShellSpace space(first.mesh, first.topology, Material(material_args, first.mesh));
  const std::vector<int> fixed = Mask(mask, first.mesh.num_vertices());
  const SolverSettings settings = solver.Settings("transport");
  TransportResult result;
  {
    py::gil_scoped_release release;
    result = ParallelTransport(space, path, varied - first.mesh.positions,
                               epsilon, fixed, settings);
  }
  WritePath(output, png, gltf, first.mesh.faces, result.shapes);
  JsonObject json = TransportJson(result, epsilon);
  json.Raw("energy_split", PathEnergySplitJson(space, result.shapes))
      .Raw("material", MaterialRecord(space, first.mesh, material_args))
      .Add("seconds", Seconds(clock));
  return py::make_tuple(FromPath(result.shapes),
                        ToDict(AddOutput(json, output)));
}

// The shapes of a list (keyframes, inputs) with the connectivity F.
struct ShapeSet {
  Shell first;
  std::vector<Positions> shapes;
};

ShapeSet MakeShapeSet(const py::object& list, const IndexArray& F,
                      const std::string& name) {
  const std::vector<Positions> shapes = ToShapes(list, name);
  ShapeSet set;
  set.first = MakeShell(DoubleArray(FromPositions(shapes[0])), F, name + "[0]");
  set.shapes.push_back(set.first.mesh.positions);
  for (size_t i = 1; i < shapes.size(); ++i) {
    set.shapes.push_back(CompatiblePositions(
        shapes[i], set.first, name + "[" + std::to_string(i) + "]"));
  }
  return set;
}

std::vector<int> Indices(const std::vector<long long>& at, size_t shapes,
                         const std::string& name) {
  std::vector<int> out;
  for (long long v : at) {
    if (!out.empty() && v <= out.back()) {
      throw InputError("at must be strictly increasing");
    }
    out.push_back(static_cast<int>(v));
  }
  if (out.size() != shapes) {
    throw InputError("at gives " + std::to_string(out.size()) +
                     " indices for " + std::to_string(shapes) + " " + name);
  }
  return out;
}

SplineSettings SplineSettingsOf(const SolverOptions& solver,
                                const std::string& label) {
  SplineSettings settings;
  settings.inner = solver.Settings(label + " midpoint");
  settings.inner.progress = false;
  settings.inner.gradient_tolerance = 1e-10;
  settings.max_iterations = solver.max_iterations;
  settings.gradient_tolerance = solver.tolerance;
  settings.progress = !solver.quiet;
  settings.progress_label = label;
  return settings;
}

py::tuple SplinePy(const py::object& keyframes_object,
                   const std::vector<long long>& at_list, const IndexArray& F,
                   int steps, const std::string& method,
                   const std::string& init, bool periodic,
                   const std::optional<std::string>& output,
                   const std::optional<std::string>& png,
                   const std::optional<std::string>& gltf, const MaterialArgs& material_args, const SolverOptions& solver) {
  if (method != "nonlinear" && method != "ltheta") {
    throw InputError("method must be nonlinear or ltheta");
  }
  CheckAtLeast("steps", steps, 2);
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(keyframes_object, F, "keyframes");
  const std::vector<int> at = Indices(at_list, set.shapes.size(), "keyframes");
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
    py::gil_scoped_release release;
    initial = MakeSplineInitialPath(initial_path, space, set.shapes, at, steps,
                                    periodic, init_settings);
    result = SolveSpline(space, set.shapes, at, steps, periodic, initial.path,
                         settings);
  }
  // The LΘA spline alone converged if every frame's reconstruction did.
  if (method == "ltheta") {
    result.converged = initial.ltheta.unconverged_frames().empty();
  }
  WritePath(output, png, gltf, set.first.mesh.faces, result.path);
  JsonObject head;
  head.Add("method", method);
  AddSplineInitJson(head, initial);
  head.Raw("energy_split", PathEnergySplitJson(space, result.path))
      .Raw("material", MaterialRecord(space, set.first.mesh, material_args));
  JsonObject json = SplineJson(head, result, Seconds(clock));
  return py::make_tuple(FromPath(result.path), ToDict(AddOutput(json, output)));
}

py::tuple RegressPy(const py::object& inputs_object,
                    const std::vector<long long>& at_list, const IndexArray& F,
                    int steps, double sigma,
                    const std::optional<std::string>& output,
                    const std::optional<std::string>& png,
                    const std::optional<std::string>& gltf, const MaterialArgs& material_args, const SolverOptions& solver) {
  CheckAtLeast("steps", steps, 2);
  if (!(sigma >= 0) || !std::isfinite(sigma)) {
    throw InputError("sigma must be >= 0, got " + std::to_string(sigma));
  }
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  const std::vector<int> at = Indices(at_list, set.shapes.size(), "inputs");
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(material_args, set.first.mesh));
  const SplineSettings settings = SplineSettingsOf(solver, "regress");
  SplineResult result;
  {
    py::gil_scoped_release release;
    result = SolveRegression(space, set.shapes, at, steps, sigma, {}, settings);
  }
  WritePath(output, png, gltf, set.first.mesh.faces, result.path);
  JsonObject head;
  head.Add("sigma", sigma);
  head.Raw("energy_split", PathEnergySplitJson(space, result.path))
      .Raw("material", MaterialRecord(space, set.first.mesh, material_args));
  JsonObject json = SplineJson(head, result, Seconds(clock));
  return py::make_tuple(FromPath(result.path), ToDict(AddOutput(json, output)));
}

py::tuple MeanPy(const py::object& inputs_object, const IndexArray& F,
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
    py::gil_scoped_release release;
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
  return py::make_tuple(FromPositions(result.mean),
                        ToDict(AddOutput(json, output)));
}

// The `pca` verb: elastic mean, shell PCA modes shot by EXP_K, optionally
// the Procrustes baseline and the leave-one-out table. Returns ({name:
// shape} with the names of the CLI's files without ".ply", summary).
py::tuple PcaPy(const py::object& inputs_object, const IndexArray& F, int modes,
                const std::string& baseline, bool loo, double amplitude,
                int log_steps, int exp_steps, int max_exp_steps,
                const std::string& displacement,
                const std::optional<std::string>& output,
                const std::optional<std::string>& png, const MaterialArgs& material_args, const SolverOptions& solver) {
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
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(material_args, set.first.mesh));
  const SolverSettings settings = solver.Settings("pca");
  SolverSettings inner = settings;
  inner.progress = false;

  std::vector<std::pair<std::string, Positions>> shapes;
  std::vector<Positions> strip;
  std::vector<std::string> failed_shapes, far;
  JsonObject json;
  {
    py::gil_scoped_release release;
    const ElasticMeanResult mean =
        ComputeElasticMean(space, set.shapes, settings);
    if (mean.summary.termination_type == ceres::FAILURE) {
      throw InputError("elastic mean failed: " + mean.summary.message);
    }
    for (int i : FarInputs(mean.energies)) {
      far.push_back("inputs[" + std::to_string(i) + "]");
    }
    const ShellPcaModel shell =
        ComputeShellPca(space, mean.mean, set.shapes, options, inner);
    const int shell_modes =
        std::min<int>(modes, static_cast<int>(shell.modes.size()));
    shapes.emplace_back("mean", mean.mean);
    strip.push_back(mean.mean);
    for (int j = 0; j < shell_modes; ++j) {
      for (const double sign : {-1.0, 1.0}) {
        const std::string name =
            "mode_" + std::to_string(j + 1) + (sign < 0 ? "_minus" : "_plus");
        // A mode shape whose EXP shot has no solution is not returned; it
        // is listed in the summary (as the CLI does).
        Positions shape;
        if (TryShellModeShape(space, shell, j, sign * amplitude, options,
                              inner, &shape)) {
          shapes.emplace_back(name, shape);
          strip.push_back(std::move(shape));
        } else {
          failed_shapes.push_back(name + ".ply");
        }
      }
    }
    json = PcaJson(n, mean, displacement, options, shell, shell_modes,
                   failed_shapes, far, amplitude);
    json.Raw("material", MaterialRecord(space, set.first.mesh, material_args));
    if (baseline == "procrustes") {
      for (auto& shape : AddProcrustesBaseline(ComputeProcrustesPca(set.shapes),
                                               modes, amplitude, &json)) {
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
      json.Raw("leave_one_out", LeaveOneOutJson(table));
    }
  }
  json.Add("seconds", Seconds(clock));
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
  if (png) {
    WriteFilmStrip(strip, set.first.mesh.faces, RenderOptions(), *png);
  }
  py::dict out;
  for (const auto& [name, positions] : shapes) {
    out[py::str(name)] = FromPositions(positions);
  }
  return py::make_tuple(out, ToDict(json));
}

// `branching simulate`: the relaxed Kohn-Mueller simulation. Returns (u as
// an (nx + 1) x ny array, u[i, j] at node x_i, y_j; summary).
py::tuple BranchingSimulatePy(double epsilon, double length, double height,
                              int nx, int ny, const std::string& init,
                              double delta, double grading, int continuation,
                              int periods, int init_seed, int lm_iterations,
                              int delta_extrapolation) {
  using namespace branching;
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
  CheckSimulationSettings(s);
  std::optional<SimulationResult> simulation;
  JsonObject summary;
  {
    py::gil_scoped_release release;
    simulation.emplace(RunSimulation(s));
    const SimulationResult& result = *simulation;
    if (const std::string why = SimulationBreakdown(result); !why.empty()) {
      throw InputError("branching simulate: " + why);
    }
    summary = SimulationJson(s, result);
    if (delta_extrapolation >= 2) {
      summary.Add("extrapolation",
                  DeltaExtrapolationJson(ExtrapolateDelta(
                      s, ExtrapolationWidths(result.delta,
                                             delta_extrapolation))));
    }
  }
  const SimulationResult& result = *simulation;
  const RelaxedGrid& g = result.field.grid;
  py::array_t<double> u(
      {static_cast<py::ssize_t>(g.nx + 1), static_cast<py::ssize_t>(g.ny)});
  for (int i = 0; i <= g.nx; ++i) {
    for (int j = 0; j < g.ny; ++j) {
      u.mutable_at(i, j) = result.field.at(i, j);
    }
  }
  return py::make_tuple(u, ToDict(summary));
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
                     const IndexArray& F, double tolerance,
                     double energy_tolerance, const MaterialArgs& material_args) {
  for (const auto& [name, value] :
       {std::pair{"tolerance", tolerance}, {"energy_tolerance", energy_tolerance}}) {
    if (!(value >= 0) || !std::isfinite(value)) {
      throw InputError(std::string(name) + " must be >= 0, got " +
                       std::to_string(value));
    }
  }
  auto side = [](const py::object& object, const std::string& name) {
    if (py::isinstance<py::array>(object) &&
        object.cast<py::array>().ndim() == 2) {
      return std::vector<Positions>{ToPositions(object.cast<DoubleArray>(), name)};
    }
    return ToShapes(object, name);
  };
  const std::vector<Positions> a_shapes = side(a_object, "a");
  const std::vector<Positions> b_shapes = side(b_object, "b");
  const Shell first = MakeShell(DoubleArray(FromPositions(a_shapes[0])), F, "a[0]");
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

void WriteGltfPy(const std::string& path, const py::object& frames_object,
                 const IndexArray& F, double fps,
                 const std::string& interpolation) {
  GltfAnimationOptions options;
  options.frames_per_second = fps;
  options.interpolation =
      ParseGltfInterpolation(interpolation, "interpolation");
  WriteGltfMorphAnimation(path, ToShapes(frames_object, "frames"), ToFaces(F),
                          options);
}

// `shellspace render` on frames in memory: the same options, the same file.
void WriteFilmStripPy(const std::string& path, const py::object& frames_object,
                      const IndexArray& F, int width, int height,
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
  WriteFilmStrip(ToShapes(frames_object, "frames"), ToFaces(F), options, path);
}

// The Python signatures of the verb functions. A function f(args...,
// const MaterialArgs&) is bound as a function of args... followed by the
// material's keyword arguments (mu, lambda_, eta, relative_eta, bending: in
// the order of SHELLSPACE_MATERIAL_ARGS), gathered into a MaterialArgs; one
// that also ends with const SolverOptions& takes the solver's (tolerance,
// max_iterations, threads, quiet: SHELLSPACE_SOLVER_ARGS) after them.
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
             int threads, bool quiet) {
    return f(args..., MaterialArgs{mu, lambda, eta, relative_eta, bending},
             SolverOptions{tolerance, max_iterations, threads, quiet});
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
  py::arg("threads") = 2, py::arg("quiet") = false
// The first arguments of the verbs that solve a geodesic (geodesic, log).
#define SHELLSPACE_GEODESIC_ARGS                                        \
  py::arg("start"), py::arg("end"), py::arg("F"), py::arg("steps") = 8, \
      py::arg("mask") = py::none(), py::arg("multires") = "auto",       \
      py::arg("linear_solver") = "auto", py::arg("lm") = "auto"
// The files of the verbs that write a path's frames: the frames' directory,
// a film strip (PNG), a glTF 2.0 animation (.glb); none by default.
#define SHELLSPACE_FRAME_OUTPUT_ARGS                              \
  py::arg("output") = py::none(), py::arg("png") = py::none(), \
      py::arg("gltf") = py::none()

PYBIND11_MODULE(shellspace, m) {
  using namespace shellspace;
  // CHOLMOD's OpenMP regions on the importing thread alone, as in the CLI
  // (geometry/openmp_threads.h).
  SerialOpenMpInThisThread();
  // Ceres' routine warnings hidden, as in the CLI (its --minloglevel=0).
  FLAGS_minloglevel = google::GLOG_ERROR;
  FLAGS_logtostderr = true;

  m.doc() =
      "shellspace: the time-discrete geodesic calculus on discrete shells.\n"
      "Meshes are (V, F): V #V x 3 float64, F #F x 3 int; paths are\n"
      "(K + 1) x #V x 3 arrays. Each verb function takes the CLI verb's\n"
      "options as keyword arguments (lambda as lambda_) and returns its\n"
      "results and the verb's --json summary as a dict.";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
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
        "The relaxed Kohn-Mueller simulation (`branching simulate`): "
        "returns (u (nx + 1) x ny, summary). Writes no files.");
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
