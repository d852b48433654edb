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

#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/deformation_energy.h"
#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/gltf_writer.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/exponential_map.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/problems/calculus/multiresolution.h"
#include "shellspace/problems/calculus/parallel_transport.h"
#include "shellspace/problems/splines/ltheta_spline.h"
#include "shellspace/problems/splines/spline.h"
#include "shellspace/problems/statistics/elastic_mean.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/reports/path_reports.h"
#include "shellspace/reports/shape_reports.h"
#include "shellspace/reports/solve_choices.h"

namespace py = pybind11;

namespace shellspace {
namespace {

using Clock = std::chrono::steady_clock;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
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
  py::array_t<long long> out({static_cast<py::ssize_t>(faces.rows()),
                              static_cast<py::ssize_t>(3)});
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
      py::array(object.cast<py::array>()).ndim() == 3) {
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
  ValidateShellPositions(Mesh{positions, like.mesh.faces}, like.topology,
                         name);
  return positions;
}

Positions CompatiblePositions(const DoubleArray& V, const Shell& like,
                              const std::string& name) {
  return CompatiblePositions(ToPositions(V, name), like, name);
}

ShellMaterial Material(double mu, double lambda, double eta) {
  ShellMaterial material;
  material.mu = mu;
  material.lambda = lambda;
  material.eta = eta;
  material.Validate();
  return material;
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

// The CLI's solver options (SolverFlags: the same ranges).
struct SolverOptions {
  double tolerance = 1e-8;
  int max_iterations = 200;
  int threads = 2;
  bool quiet = false;

  SolverSettings Settings(const std::string& label) const {
    if (!(tolerance > 0 && tolerance < 1)) {
      throw InputError("tolerance must be in (0, 1), got " +
                       std::to_string(tolerance));
    }
    if (max_iterations < 1) {
      throw InputError("max_iterations must be >= 1, got " +
                       std::to_string(max_iterations));
    }
    if (threads < 1 || threads > 1024) {
      throw InputError("threads must be in [1, 1024], got " +
                       std::to_string(threads));
    }
    SolverSettings settings;
    settings.progress = !quiet;
    settings.progress_label = label;
    settings.gradient_tolerance = tolerance;
    settings.max_iterations = max_iterations;
    settings.num_threads = threads;
    return settings;
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
  const std::string glb = gltf ? EncodeGltfMorphAnimation(path, faces) : "";
  if (output) WriteFrames(*output, faces, path);
  if (png) WriteFilmStrip(path, faces, options, *png);
  if (gltf) WriteFileAtomically(*gltf, glb);
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
                    const IndexArray& F, double mu, double lambda,
                    double eta) {
  const Shell shell = MakeShell(reference, F, "reference");
  const Positions d = CompatiblePositions(deformed, shell, "deformed");
  const ShellSpace space(shell.mesh, shell.topology,
                         Material(mu, lambda, eta));
  const DeformationEnergy e =
      EvaluateDeformationEnergy(space, shell.mesh.positions, d);
  return ToDict(EnergyJson(e, space.material));
}

py::array_t<double> GradientPy(const DoubleArray& reference,
                               const DoubleArray& deformed,
                               const IndexArray& F, const std::string& side,
                               double mu, double lambda, double eta) {
  const Shell shell = MakeShell(reference, F, "reference");
  const Positions d = CompatiblePositions(deformed, shell, "deformed");
  const ShellSpace space(shell.mesh, shell.topology,
                         Material(mu, lambda, eta));
  const Eigen::VectorXd g =
      EnergyGradient(space, shell.mesh.positions, d, Side(side, "side"));
  Positions out(shell.mesh.num_vertices(), 3);
  std::copy(g.data(), g.data() + g.size(), out.data());
  return FromPositions(out);
}

py::tuple HessianPy(const DoubleArray& reference, const DoubleArray& deformed,
                    const IndexArray& F, const std::string& rows,
                    const std::string& cols, double mu, double lambda,
                    double eta) {
  const Shell shell = MakeShell(reference, F, "reference");
  const Positions d = CompatiblePositions(deformed, shell, "deformed");
  const ShellSpace space(shell.mesh, shell.topology,
                         Material(mu, lambda, eta));
  const SparseMatrix H =
      EnergyHessian(space, shell.mesh.positions, d, Side(rows, "rows"),
                    Side(cols, "cols"));
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
  if (result.summary.termination_type == ceres::FAILURE) {
    throw InputError("solver failed: " + result.summary.message);
  }
}

MultiresolutionResult SolveGeodesicPy(const Shell& start, const Positions& end,
                                      int steps, const py::object& mask,
                                      const ShellSpace& space,
                                      const std::string& multires,
                                      const std::string& linear_solver,
                                      const SolverSettings& settings) {
  CheckAtLeast("steps", steps, 1);
  GeodesicInput input;
  input.start = start.mesh.positions;
  input.end = end;
  input.steps = steps;
  input.fixed_vertices = Mask(mask, start.mesh.num_vertices());
  input.linear_solver = ParsePathLinearSolver(linear_solver, "linear_solver");
  const MultiresolutionSettings levels = ParseMultiresolution(
      multires, start.mesh.num_vertices(), "multires");
  py::gil_scoped_release release;
  return SolveGeodesicMultiresolution(space, input, settings, levels);
}

py::tuple GeodesicPy(const DoubleArray& start_v, const DoubleArray& end_v,
                     const IndexArray& F, int steps, const py::object& mask,
                     const std::string& multires,
                     const std::string& linear_solver, bool report,
                     const std::optional<std::string>& output,
                     const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf, double mu,
                     double lambda, double eta, const SolverOptions& solver) {
  const auto clock = Clock::now();
  const Shell start = MakeShell(start_v, F, "start");
  const Positions end = CompatiblePositions(end_v, start, "end");
  const ShellSpace space(start.mesh, start.topology,
                         Material(mu, lambda, eta));
  const MultiresolutionResult multi =
      SolveGeodesicPy(start, end, steps, mask, space, multires, linear_solver,
                      solver.Settings("geodesic"));
  const GeodesicResult& result = multi.geodesic;
  CheckGeodesic(result);
  if (report) py::print(result.summary.FullReport(), py::arg("file") =
                            py::module_::import("sys").attr("stderr"));
  WritePath(output, png, gltf, start.mesh.faces, result.path);
  JsonObject json = GeodesicJson(result);
  json.Raw("multires_levels", MultiresolutionJson(multi))
      .Add("seconds", Seconds(clock));
  return py::make_tuple(FromPath(result.path), ToDict(AddOutput(json, output)));
}

py::tuple LogPy(const DoubleArray& start_v, const DoubleArray& end_v,
                const IndexArray& F, int steps, const py::object& mask,
                const std::string& multires, const std::string& linear_solver,
                const std::optional<std::string>& output, double mu,
                double lambda, double eta, const SolverOptions& solver) {
  const auto clock = Clock::now();
  const Shell start = MakeShell(start_v, F, "start");
  const Positions end = CompatiblePositions(end_v, start, "end");
  const ShellSpace space(start.mesh, start.topology,
                         Material(mu, lambda, eta));
  const MultiresolutionResult multi =
      SolveGeodesicPy(start, end, steps, mask, space, multires, linear_solver,
                      solver.Settings("log"));
  const GeodesicResult& geodesic = multi.geodesic;
  const Positions log = LogOfGeodesic(geodesic.path);
  if (output) {
    WriteMesh(Mesh{start.mesh.positions + log, start.mesh.faces}, *output);
  }
  JsonObject json = GeodesicJson(geodesic);
  json.Raw("multires_levels", MultiresolutionJson(multi))
      .Add("log_max_norm", log.cwiseAbs().maxCoeff())
      .Add("seconds", Seconds(clock));
  return py::make_tuple(FromPositions(log), ToDict(AddOutput(json, output)));
}

py::tuple ShootPy(const DoubleArray& first_v, const DoubleArray& second_v,
                  const IndexArray& F, int steps, bool backward,
                  const py::object& mask,
                  const std::optional<std::string>& output,
                  const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf, double mu,
                  double lambda, double eta, const SolverOptions& solver) {
  const auto clock = Clock::now();
  CheckAtLeast("steps", steps, 1);
  const Shell first = MakeShell(first_v, F, "first");
  const Positions second = CompatiblePositions(second_v, first, "second");
  const ShellSpace space(first.mesh, first.topology,
                         Material(mu, lambda, eta));
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
  json.Add("seconds", Seconds(clock));
  return py::make_tuple(FromPath(result.path), ToDict(AddOutput(json, output)));
}

py::tuple TransportPy(const py::object& path_object,
                      const DoubleArray& variation_v, const IndexArray& F,
                      double epsilon, const py::object& mask,
                      const std::optional<std::string>& output,
                      const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf, double mu,
                      double lambda, double eta, const SolverOptions& solver) {
  const auto clock = Clock::now();
  if (!(epsilon > 0) || !std::isfinite(epsilon)) {
    throw InputError("epsilon must be > 0, got " + std::to_string(epsilon));
  }
  const std::vector<Positions> frames = ToShapes(path_object, "path");
  if (frames.size() < 2) throw InputError("path: need at least 2 frames");
  const Shell first = MakeShell(DoubleArray(FromPositions(frames[0])), F,
                                "path[0]");
  ShellPath path = {first.mesh.positions};
  for (size_t k = 1; k < frames.size(); ++k) {
    path.push_back(CompatiblePositions(frames[k], first,
                                       "path[" + std::to_string(k) + "]"));
  }
  const Positions varied = CompatiblePositions(variation_v, first, "variation");
  const ShellSpace space(first.mesh, first.topology,
                         Material(mu, lambda, eta));
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
  json.Add("seconds", Seconds(clock));
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
                   int steps, const std::string& method, bool periodic,
                   const std::optional<std::string>& output,
                   const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf, double mu,
                   double lambda, double eta, const SolverOptions& solver) {
  if (method != "nonlinear" && method != "ltheta") {
    throw InputError("method must be nonlinear or ltheta");
  }
  CheckAtLeast("steps", steps, 2);
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(keyframes_object, F, "keyframes");
  const std::vector<int> at = Indices(at_list, set.shapes.size(), "keyframes");
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(mu, lambda, eta));
  SolverSettings ltheta_settings = solver.Settings("ltheta");
  ltheta_settings.progress = false;
  SplineSettings settings = SplineSettingsOf(solver, "spline");
  if (method == "ltheta") settings.max_iterations = 0;
  SplineResult result;
  double ltheta_seconds = 0;
  {
    py::gil_scoped_release release;
    const ShellPath ltheta = LThetaSpline(space, set.shapes, at, steps,
                                          periodic, ltheta_settings);
    ltheta_seconds = Seconds(clock);
    result = SolveSpline(space, set.shapes, at, steps, periodic, ltheta,
                         settings);
  }
  WritePath(output, png, gltf, set.first.mesh.faces, result.path);
  JsonObject head;
  head.Add("method", method).Add("ltheta_seconds", ltheta_seconds);
  JsonObject json = SplineJson(head, result, Seconds(clock));
  return py::make_tuple(FromPath(result.path), ToDict(AddOutput(json, output)));
}

py::tuple RegressPy(const py::object& inputs_object,
                    const std::vector<long long>& at_list,
                    const IndexArray& F, int steps, double sigma,
                    const std::optional<std::string>& output,
                    const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf, double mu,
                    double lambda, double eta, const SolverOptions& solver) {
  CheckAtLeast("steps", steps, 2);
  if (!(sigma >= 0) || !std::isfinite(sigma)) {
    throw InputError("sigma must be >= 0, got " + std::to_string(sigma));
  }
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  const std::vector<int> at = Indices(at_list, set.shapes.size(), "inputs");
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(mu, lambda, eta));
  const SplineSettings settings = SplineSettingsOf(solver, "regress");
  SplineResult result;
  {
    py::gil_scoped_release release;
    result = SolveRegression(space, set.shapes, at, steps, sigma, {}, settings);
  }
  WritePath(output, png, gltf, set.first.mesh.faces, result.path);
  JsonObject head;
  head.Add("sigma", sigma);
  JsonObject json = SplineJson(head, result, Seconds(clock));
  return py::make_tuple(FromPath(result.path), ToDict(AddOutput(json, output)));
}

py::tuple MeanPy(const py::object& inputs_object, const IndexArray& F,
                 bool report, const std::optional<std::string>& output,
                 double mu, double lambda, double eta,
                 const SolverOptions& solver) {
  const auto clock = Clock::now();
  const ShapeSet set = MakeShapeSet(inputs_object, F, "inputs");
  const ShellSpace space(set.first.mesh, set.first.topology,
                         Material(mu, lambda, eta));
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
  if (report) py::print(result.summary.FullReport(), py::arg("file") =
                            py::module_::import("sys").attr("stderr"));
  if (output) WriteMesh(Mesh{result.mean, set.first.mesh.faces}, *output);
  JsonObject json =
      MeanJson(result, static_cast<int>(set.shapes.size()), far);
  json.Add("seconds", Seconds(clock));
  return py::make_tuple(FromPositions(result.mean),
                        ToDict(AddOutput(json, output)));
}

void WriteGltfPy(const std::string& path, const py::object& frames_object,
                 const IndexArray& F, double fps,
                 const std::string& interpolation) {
  GltfAnimationOptions options;
  options.frames_per_second = fps;
  if (interpolation == "linear") {
    options.interpolation = GltfAnimationOptions::Interpolation::kLinear;
  } else if (interpolation == "step") {
    options.interpolation = GltfAnimationOptions::Interpolation::kStep;
  } else {
    throw InputError("interpolation must be linear or step, got '" +
                     interpolation + "'");
  }
  WriteGltfMorphAnimation(path, ToShapes(frames_object, "frames"), ToFaces(F),
                          options);
}

}  // namespace
}  // namespace shellspace

// The keyword arguments shared by the verbs, with the CLI's defaults.
#define SHELLSPACE_MATERIAL_ARGS                                     \
  py::arg("mu") = 1.0, py::arg("lambda_") = 1.0, py::arg("eta") = 0.01
#define SHELLSPACE_SOLVER_ARGS                                         \
  py::arg("tolerance") = 1e-8, py::arg("max_iterations") = 200,        \
      py::arg("threads") = 2, py::arg("quiet") = false

PYBIND11_MODULE(shellspace, m) {
  using namespace shellspace;
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

  m.def("read_mesh", &ReadMeshPy, py::arg("path"),
        "Reads a PLY, OBJ or OFF mesh (strict readers): returns (V, F).");
  m.def("write_mesh", &WriteMeshPy, py::arg("path"), py::arg("V"),
        py::arg("F"),
        "Writes (V, F) as PLY, OBJ or OFF (by the extension), atomically.");
  m.def("write_gltf", &WriteGltfPy, py::arg("path"), py::arg("frames"),
        py::arg("F"), py::arg("fps") = 4.0, py::arg("interpolation") = "linear",
        "Writes frames (a path) as one glTF 2.0 morph animation (.glb), as "
        "`shellspace export` does.");
  m.def("read_mask", &ReadMask, py::arg("path"), py::arg("num_vertices"),
        "Reads a vertex mask file: sorted unique 0-based indices.");

  m.def(
      "energy",
      [](const DoubleArray& reference, const DoubleArray& deformed,
         const IndexArray& F, double mu, double lambda, double eta) {
        return EnergyPy(reference, deformed, F, mu, lambda, eta);
      },
      py::arg("reference"), py::arg("deformed"), py::arg("F"),
      SHELLSPACE_MATERIAL_ARGS,
      "W[reference, deformed] = W_mem + eta W_bend: the `energy` verb's "
      "summary {membrane, bending, total, mu, lambda, eta}.");
  m.def("energy_gradient", &GradientPy, py::arg("reference"),
        py::arg("deformed"), py::arg("F"), py::arg("side") = "deformed",
        SHELLSPACE_MATERIAL_ARGS,
        "D_2 W (side='deformed') or D_1 W (side='reference') as a #V x 3 "
        "array (the derivative by vertex v, coordinate c at [v, c]).");
  m.def("energy_hessian", &HessianPy, py::arg("reference"),
        py::arg("deformed"), py::arg("F"), py::arg("rows") = "deformed",
        py::arg("cols") = "deformed", SHELLSPACE_MATERIAL_ARGS,
        "The 3#V x 3#V block d_rows d_cols W (coordinate 3 v + c) as "
        "triplets (rows, cols, vals): scipy.sparse.coo_matrix((vals, (rows, "
        "cols)), shape=(3 * nV, 3 * nV)). rows/cols: 'deformed' or "
        "'reference' ('reference', 'deformed' is the mixed D_1 D_2 W).");

  m.def(
      "geodesic",
      [](const DoubleArray& start, const DoubleArray& end, const IndexArray& F,
         int steps, const py::object& mask, const std::string& multires,
         const std::string& linear_solver, bool report,
         const std::optional<std::string>& output,
         const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf, double mu, double lambda,
         double eta, double tolerance, int max_iterations, int threads,
         bool quiet) {
        return GeodesicPy(start, end, F, steps, mask, multires, linear_solver,
                          report, output, png, gltf, mu, lambda, eta,
                          {tolerance, max_iterations, threads, quiet});
      },
      py::arg("start"), py::arg("end"), py::arg("F"), py::arg("steps") = 8,
      py::arg("mask") = py::none(), py::arg("multires") = "auto",
      py::arg("linear_solver") = "auto", py::arg("report") = false,
      py::arg("output") = py::none(), py::arg("png") = py::none(), py::arg("gltf") = py::none(),
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS,
      "Discrete geodesic from start to end in `steps` steps: returns (path, "
      "summary). mask: vertex indices or a mask file held at their linear "
      "positions. output: also write DIR/shape_000.ply ...; png: a film "
      "strip.");
  m.def(
      "log",
      [](const DoubleArray& start, const DoubleArray& end, const IndexArray& F,
         int steps, const py::object& mask, const std::string& multires,
         const std::string& linear_solver,
         const std::optional<std::string>& output, double mu, double lambda,
         double eta, double tolerance, int max_iterations, int threads,
         bool quiet) {
        return LogPy(start, end, F, steps, mask, multires, linear_solver,
                     output, mu, lambda, eta,
                     {tolerance, max_iterations, threads, quiet});
      },
      py::arg("start"), py::arg("end"), py::arg("F"), py::arg("steps") = 8,
      py::arg("mask") = py::none(), py::arg("multires") = "auto",
      py::arg("linear_solver") = "auto", py::arg("output") = py::none(),
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS,
      "LOG_K(start -> end) = K (s_1 - s_0) of the discrete geodesic: returns "
      "(log #V x 3, summary). output: write start + log (as the CLI).");
  m.def(
      "shoot",
      [](const DoubleArray& first, const DoubleArray& second,
         const IndexArray& F, int steps, bool backward, const py::object& mask,
         const std::optional<std::string>& output,
         const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf, double mu, double lambda,
         double eta, double tolerance, int max_iterations, int threads,
         bool quiet) {
        return ShootPy(first, second, F, steps, backward, mask, output, png, gltf,
                       mu, lambda, eta,
                       {tolerance, max_iterations, threads, quiet});
      },
      py::arg("first"), py::arg("second"), py::arg("F"), py::arg("steps") = 8,
      py::arg("backward") = false, py::arg("mask") = py::none(),
      py::arg("output") = py::none(), py::arg("png") = py::none(), py::arg("gltf") = py::none(),
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS,
      "Geodesic shooting (EXP steps) from (first, second): returns (path, "
      "summary).");
  m.def(
      "transport",
      [](const py::object& path, const DoubleArray& variation,
         const IndexArray& F, double epsilon, const py::object& mask,
         const std::optional<std::string>& output,
         const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf, double mu, double lambda,
         double eta, double tolerance, int max_iterations, int threads,
         bool quiet) {
        return TransportPy(path, variation, F, epsilon, mask, output, png, gltf, mu,
                           lambda, eta,
                           {tolerance, max_iterations, threads, quiet});
      },
      py::arg("path"), py::arg("variation"), py::arg("F"),
      py::arg("epsilon") = 1.0, py::arg("mask") = py::none(),
      py::arg("output") = py::none(), py::arg("png") = py::none(), py::arg("gltf") = py::none(),
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS,
      "Schild's-ladder transport of variation - path[0] along path: returns "
      "(shapes s_k + epsilon xi_k, summary).");
  m.def(
      "spline",
      [](const py::object& keyframes, const std::vector<long long>& at,
         const IndexArray& F, int steps, const std::string& method,
         bool periodic, const std::optional<std::string>& output,
         const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf, double mu, double lambda,
         double eta, double tolerance, int max_iterations, int threads,
         bool quiet) {
        return SplinePy(keyframes, at, F, steps, method, periodic, output, png, gltf,
                        mu, lambda, eta,
                        {tolerance, max_iterations, threads, quiet});
      },
      py::arg("keyframes"), py::arg("at"), py::arg("F"), py::arg("steps") = 8,
      py::arg("method") = "nonlinear", py::arg("periodic") = false,
      py::arg("output") = py::none(), py::arg("png") = py::none(), py::arg("gltf") = py::none(),
      SHELLSPACE_MATERIAL_ARGS, SHELLSPACE_SOLVER_ARGS,
      "Riemannian spline through keyframes at path indices `at`: returns "
      "(path, summary).");
  m.def(
      "regress",
      [](const py::object& inputs, const std::vector<long long>& at,
         const IndexArray& F, int steps, double sigma,
         const std::optional<std::string>& output,
         const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf, double mu, double lambda,
         double eta, double tolerance, int max_iterations, int threads,
         bool quiet) {
        return RegressPy(inputs, at, F, steps, sigma, output, png, gltf, mu, lambda,
                         eta, {tolerance, max_iterations, threads, quiet});
      },
      py::arg("inputs"), py::arg("at"), py::arg("F"), py::arg("steps") = 8,
      py::arg("sigma") = 1.0, py::arg("output") = py::none(),
      py::arg("png") = py::none(), py::arg("gltf") = py::none(), SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS,
      "Shape regression (data term + sigma spline energy): returns (path, "
      "summary).");
  m.def(
      "mean",
      [](const py::object& inputs, const IndexArray& F, bool report,
         const std::optional<std::string>& output, double mu, double lambda,
         double eta, double tolerance, int max_iterations, int threads,
         bool quiet) {
        return MeanPy(inputs, F, report, output, mu, lambda, eta,
                      {tolerance, max_iterations, threads, quiet});
      },
      py::arg("inputs"), py::arg("F"), py::arg("report") = false,
      py::arg("output") = py::none(), SHELLSPACE_MATERIAL_ARGS,
      SHELLSPACE_SOLVER_ARGS,
      "Elastic mean argmin_s sum_i W[inputs_i, s]: returns (mean #V x 3, "
      "summary).");
}
