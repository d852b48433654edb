// The module's mesh files: read_mesh, write_mesh, read_mask, write_gltf.
#include <string>
#include <utility>
#include <vector>

#include "python/array_arguments.h"
#include "python/module_common.h"
#include "python/parameter_docs.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/io/gltf_writer.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/io/output_paths.h"

namespace shellspace {
namespace pymodule {
namespace {

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

using NamedPaths = std::vector<std::pair<std::string, std::string>>;

// The library's output-path policy (io/output_paths.h) for the Python
// front ends that write their own files (shellspace.collections).
void CheckOutputPathsPy(const NamedPaths& inputs, const NamedPaths& files,
                        const NamedPaths& directories,
                        const NamedPaths& input_lists) {
  OutputPaths paths;
  for (const auto& [name, path] : inputs) paths.InputFile(name, path);
  for (const auto& [name, list] : input_lists) paths.InputList(name, list);
  for (const auto& [name, path] : files) {
    if (path.empty()) throw InputError(name + ": an empty path");
    paths.OutputFile(name, path);
  }
  for (const auto& [name, path] : directories) {
    if (path.empty()) throw InputError(name + ": an empty path");
    paths.OutputDirectory(name, path);
  }
  paths.Check();
}

}  // namespace

void RegisterIo(py::module_& m) {
  m.def("_check_output_paths", &CheckOutputPathsPy, py::arg("inputs"),
        py::arg("output_files"), py::arg("output_directories") = NamedPaths{},
        py::arg("input_lists") = NamedPaths{},
        "The output-path policy of every front end, checked before any work: "
        "lists of (name, path), input_lists of (name, comma-separated "
        "paths); raises InputError (one line) for an empty item of a list, "
        "an output "
        "that is an input under any spelling, two outputs naming one file, "
        "an output that cannot be written or named.");
  m.def("read_mesh", &ReadMeshPy, py::arg("path"),
        WithParameters(
            "read_mesh",
            "Reads a PLY, OBJ or OFF mesh (strict readers): returns (V, F).")
            .c_str());
  m.def("write_mesh", &WriteMeshPy, py::arg("path"), py::arg("V"), py::arg("F"),
        WithParameters(
            "write_mesh",
            "Writes (V, F) as PLY, OBJ or OFF (by the extension), atomically.")
            .c_str());
  m.def("write_gltf", &WriteGltfPy, py::arg("path"), py::arg("frames"),
        py::arg("F"), py::arg("fps") = 4.0, py::arg("interpolation") = "linear",
        WithParameters(
            "write_gltf",
            "Writes frames (a path) as one glTF 2.0 morph animation (.glb), as "
            "`shellspace export` does.")
            .c_str());
  m.def(
      "read_mask",
      [](const std::string& path, int num_vertices) {
        return ReadMask(path, num_vertices);
      },
      py::arg("path"), py::arg("num_vertices"),
      WithParameters("read_mask",
                     "Reads a vertex mask file: sorted unique 0-based indices.")
          .c_str());
}

}  // namespace pymodule
}  // namespace shellspace
