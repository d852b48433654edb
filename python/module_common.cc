// The helpers the files of the Python module share (python/module_common.h).
#include "python/module_common.h"

#include <algorithm>
#include <cmath>

#include "python/array_arguments.h"
#include "shellspace/geometry/memory_limits.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/frame_sequence.h"
#include "shellspace/io/gltf_writer.h"
#include "shellspace/io/output_directory.h"
#include "shellspace/io/output_paths.h"
#include "shellspace/io/png_writer.h"
#include "shellspace/render/film_strip.h"
#include "shellspace/reports/shape_reports.h"

namespace shellspace {
namespace pymodule {

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
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

py::object ReadOnlyArrays(py::object value) {
  if (py::isinstance<py::array>(value)) {
    // A view of immutable bytes: an array that owns its memory can be made
    // writable again (setflags(write=True)), this one cannot.
    const py::object numpy = py::module_::import("numpy");
    return numpy
        .attr("frombuffer")(value.attr("tobytes")(),
                            py::arg("dtype") = value.attr("dtype"))
        .attr("reshape")(value.attr("shape"));
  }
  if (py::isinstance<py::dict>(value)) {
    py::dict dict = py::reinterpret_borrow<py::dict>(value);
    for (const auto& item : py::dict(dict)) {  // a copy: values replaced
      dict[item.first] =
          ReadOnlyArrays(py::reinterpret_borrow<py::object>(item.second));
    }
  }
  return value;
}

py::object ToPython(const JsonValue& value) {
  using Kind = JsonValue::Kind;
  switch (value.kind()) {
    case Kind::kNull:
      return py::none();
    case Kind::kBool:
      return py::bool_(value.boolean());
    case Kind::kInt:
      return py::int_(value.integer());
    case Kind::kNumber:  // non-finite as JSON's null, as the CLI prints it
      return std::isfinite(value.number())
                 ? py::object(py::float_(value.number()))
                 : py::object(py::none());
    case Kind::kString:
      return py::str(value.text());
    case Kind::kRaw:
      return py::module_::import("json").attr("loads")(value.text());
    case Kind::kArray: {
      py::list list;
      for (const JsonValue& item : value.items()) list.append(ToPython(item));
      return list;
    }
    case Kind::kObject: {
      py::dict dict;
      for (const auto& [key, member] : value.members())
        dict[py::str(key)] = ToPython(member);
      return dict;
    }
  }
  return py::none();
}

py::object ToDict(const JsonObject& json) { return ToPython(json.value()); }

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

const py::object& DefaultRelativeEtaObject() {
  // Made once, with the GIL held (at the module's import), and kept for the
  // life of the process.
  static const py::object* object =
      new py::object(py::float_(kDefaultRelativeEta));
  return *object;
}

MaterialArgs MakeMaterialArgs(double mu, double lambda,
                              std::optional<double> eta,
                              const RelativeEtaArg& relative_eta,
                              const std::string& bending,
                              const std::string& membrane) {
  if (eta && relative_eta.given) {
    throw InputError(
        "eta and relative_eta: give one of them (eta is absolute, "
        "relative_eta is multiplied by the reference's area)");
  }
  return MaterialArgs{mu, lambda, eta, relative_eta.value, bending, membrane};
}

ShellMaterial Material(const MaterialArgs& args, const Mesh& reference) {
  ShellMaterial material;
  if (!ParseBendingModel(args.bending, &material.bending_model)) {
    throw InputError("bending: unknown bending model '" + args.bending +
                     "' (discrete-shells or shape-operator; the edge-angle "
                     "variant is evaluated only by the `energy` verb of the "
                     "CLI)");
  }
  if (!ParseMembraneLaw(args.membrane, &material.membrane_law)) {
    throw InputError("membrane: unknown membrane law '" + args.membrane +
                     "' (" + MembraneLawNames() + ")");
  }
  material.mu = args.mu;
  material.lambda = args.lambda;
  material.eta = args.eta ? *args.eta
                          : EtaFromRelative(args.relative_eta, reference);
  material.Validate();
  return material;
}

workflows::MaterialChoice MaterialChoiceOf(const MaterialArgs& args,
                                           const Mesh& reference) {
  return {Material(args, reference), args.eta.has_value()};
}

std::vector<std::string> FailuresOf(const workflows::SolveStatus& status) {
  if (status.failed()) return {status.message};
  return status.failures;
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
// memory estimate `bytes` (geometry/memory_limits.h, the model `model`)
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

void CheckOutputs(const std::optional<std::string>& output,
                  const std::optional<std::string>& png,
                  const std::optional<std::string>& gltf,
                  const std::vector<std::pair<std::string, std::string>>&
                      inputs) {
  OutputPaths paths;
  for (const auto& [name, path] : inputs) paths.InputFile(name, path);
  if (output) {
    if (output->empty()) throw InputError("output: an empty path");
    paths.OutputDirectory("output", *output);
  }
  if (png) {
    if (png->empty()) throw InputError("png: an empty path");
    paths.OutputPng("png", *png);
  }
  if (gltf) {
    if (gltf->empty()) throw InputError("gltf: an empty path");
    paths.OutputGlb("gltf", *gltf);
  }
  paths.Check();
}

void CheckOutputFile(const std::optional<std::string>& output,
                     const std::vector<std::pair<std::string, std::string>>&
                         inputs) {
  if (!output) return;
  if (output->empty()) throw InputError("output: an empty path");
  OutputPaths paths;
  for (const auto& [name, path] : inputs) paths.InputFile(name, path);
  paths.OutputMesh("output", *output).Check();
}

void CheckPngMemory(const std::optional<std::string>& png, int frames) {
  if (png) CheckFilmStripMemory(frames, RenderOptions(), "png");
}

void WritePath(const std::optional<std::string>& output,
               const std::optional<std::string>& png,
               const std::optional<std::string>& gltf, const Faces& faces,
               const std::vector<Positions>& path, const JsonObject& summary) {
  if (!output && !png && !gltf) return;
  RenderOptions options;
  CheckPngMemory(png, static_cast<int>(path.size()));
  // All together or none, as the CLI: the directory staged and replaced
  // whole with its summary.json, the files outside renamed with it.
  StagedRun run(output.value_or(""));
  if (gltf) run.AddOutside(*gltf, EncodeGltfMorphAnimation(path, faces));
  if (png) run.AddOutside(*png, EncodePng(RenderFilmStrip(path, faces, options)));
  if (output) WriteFrames(run.staging(), faces, path);
  run.Commit(summary.str());
}

JsonObject& AddOutput(JsonObject& json,
                      const std::optional<std::string>& output) {
  if (output) json.Add("output", *output);
  return json;
}

JsonObject WorkflowJson(JsonObject json,
                        const workflows::MaterialChoice& material,
                        const Mesh& reference, std::optional<double> seconds,
                        const SolverOptions& solver,
                        const std::optional<std::string>& output) {
  json.Add("material", workflows::MaterialChoiceJson(material, reference));
  if (seconds) json.Add("seconds", *seconds);
  AddStopFields(json, *solver.control);
  AddOutput(json, output);
  return json;
}

py::object WorkflowSummary(JsonObject json,
                           const workflows::MaterialChoice& material,
                           const Mesh& reference, std::optional<double> seconds,
                           const SolverOptions& solver,
                           const std::optional<std::string>& output) {
  return ToDict(WorkflowJson(std::move(json), material, reference, seconds,
                             solver, output));
}

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

}  // namespace pymodule
}  // namespace shellspace
