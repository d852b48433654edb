#include "shellspace/tools/shell_inputs.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "shellspace/io/mesh_io.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/tools/common_flags.h"

namespace shellspace {

void RequireFlag(const std::string& name, const std::string& value) {
  if (value.empty()) throw InputError("--" + name + " is required");
}

Mesh LoadShell(const std::string& path) {
  Mesh mesh = ReadMesh(path);
  ValidateShell(mesh, path);
  return mesh;
}

Mesh LoadCompatibleShell(const std::string& path, const Mesh& like,
                         const std::string& like_path) {
  Mesh mesh = ReadMesh(path);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (!mesh.positions.row(i).allFinite()) {
      throw InputError(path + ": vertex " + std::to_string(i) +
                       " has a non-finite coordinate");
    }
  }
  CheckCompatible(like, like_path, mesh, path);
  mesh.faces = like.faces;
  ValidateShell(mesh, path);
  return mesh;
}

ShellPair LoadStartEndFromFlags() {
  RequireFlag("start", FLAGS_start);
  RequireFlag("end", FLAGS_end);
  RequireFlag("output", FLAGS_output);
  if (FLAGS_steps < 1) throw InputError("--steps must be at least 1");
  ShellPair pair;
  pair.start = LoadShell(FLAGS_start);
  pair.end = LoadCompatibleShell(FLAGS_end, pair.start, FLAGS_start);
  return pair;
}

ShellMaterial MaterialFromFlags() {
  ShellMaterial material;
  material.mu = FLAGS_mu;
  material.lambda = FLAGS_lambda;
  material.eta = FLAGS_eta;
  material.Validate();
  return material;
}

ShellSpace SpaceFromFlags(const Mesh& mesh) {
  return ShellSpace(mesh, Topology::Build(mesh), MaterialFromFlags());
}

SolverSettings SettingsFromFlags(const std::string& label) {
  SolverSettings settings;
  settings.progress = !FLAGS_quiet;
  settings.progress_label = label;
  if (!(FLAGS_tolerance > 0 && FLAGS_tolerance < 1)) {
    throw InputError("--tolerance must lie in (0, 1)");
  }
  if (FLAGS_max_iterations < 1) {
    throw InputError("--max_iterations must be at least 1");
  }
  settings.gradient_tolerance = FLAGS_tolerance;
  settings.max_iterations = FLAGS_max_iterations;
  if (FLAGS_threads < 1) throw InputError("--threads must be at least 1");
  settings.num_threads = FLAGS_threads;
  return settings;
}

std::vector<std::string> SplitList(const std::string& list,
                                   const std::string& flag) {
  std::vector<std::string> items;
  std::stringstream stream(list);
  std::string item;
  while (std::getline(stream, item, ',')) {
    if (item.empty()) throw InputError("--" + flag + " has an empty item");
    items.push_back(item);
  }
  if (items.empty()) throw InputError("--" + flag + " is empty");
  return items;
}

void MakeDirectory(const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error || !std::filesystem::is_directory(dir)) {
    throw InputError("cannot create output directory " + dir);
  }
}

void WriteFrames(const std::string& dir, const Faces& faces,
                 const std::vector<Positions>& frames) {
  MakeDirectory(dir);
  std::vector<std::string> names;
  for (size_t k = 0; k < frames.size(); ++k) {
    char name[64];
    std::snprintf(name, sizeof(name), "shape_%03zu.ply", k);
    names.push_back(dir + "/" + name);
  }
  for (size_t k = 0; k < frames.size(); ++k) {
    Mesh mesh{frames[k], faces};
    WriteMesh(mesh, names[k] + ".part.ply");
  }
  for (const std::string& name : names) {
    if (std::rename((name + ".part.ply").c_str(), name.c_str()) != 0) {
      throw InputError("cannot write " + name);
    }
  }
}

}  // namespace shellspace
