#include "tools/run/shell_inputs.h"

#include <gflags/gflags.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/io/atomic_file.h"
#include "shellspace/io/mesh_io.h"
#include "tools/run/common_flags.h"
#include "tools/run/stop_request.h"

namespace shellspace {

Shell LoadShell(const std::string& path) {
  Shell shell;
  shell.path = path;
  shell.mesh = ReadMesh(path, ReadStopToken());
  shell.topology = ValidateShell(shell.mesh, path);
  return shell;
}

Mesh LoadCompatibleShell(const std::string& path, const Shell& like) {
  Mesh mesh = ReadMesh(path, ReadStopToken());
  CheckCompatible(like.mesh, like.path, mesh, path);
  mesh.faces = like.mesh.faces;
  ValidateShellPositions(mesh, like.topology, path);
  return mesh;
}

ShellSet LoadShellList(const std::string& list, const std::string& flag) {
  return LoadShellFiles(SplitList(list, flag));
}

ShellSet LoadShellFiles(const std::vector<std::string>& paths, const Shell* like) {
  ShellSet set;
  set.paths = paths;
  size_t next = 0;
  if (like != nullptr) {
    set.first = *like;
  } else {
    set.first = LoadShell(set.paths[0]);
    set.shapes.push_back(set.first.mesh.positions);
    next = 1;
  }
  for (size_t i = next; i < set.paths.size(); ++i) {
    set.shapes.push_back(LoadCompatibleShell(set.paths[i], set.first).positions);
  }
  return set;
}

ShellPair LoadShellPair(const std::string& first, const std::string& second) {
  ShellPair pair;
  pair.first = LoadShell(first);
  pair.second = LoadCompatibleShell(second, pair.first);
  return pair;
}

BendingModel BendingModelFromFlags() {
  BendingModel model;
  if (!ParseBendingModel(FLAGS_bending, &model)) {
    if (FLAGS_bending == "shape-operator-edge-angles") {
      throw InputError(
          "--bending shape-operator-edge-angles: the edge-angle variant is "
          "evaluated only by `shellspace energy` (no problem differentiates "
          "through its angle fit); use shape-operator here");
    }
    throw InputError("--bending: unknown bending model '" + FLAGS_bending +
                     "' (discrete-shells or shape-operator)");
  }
  return model;
}

namespace {

bool Given(const char* flag) {
  gflags::CommandLineFlagInfo info;
  return gflags::GetCommandLineFlagInfo(flag, &info) && !info.is_default;
}

}  // namespace

workflows::MaterialChoice MaterialChoiceFromFlags(const Mesh& reference) {
  workflows::MaterialChoice choice;
  ShellMaterial& material = choice.material;
  material.bending_model = BendingModelFromFlags();
  if (!ParseMembraneLaw(FLAGS_membrane, &material.membrane_law)) {
    throw InputError("--membrane: unknown membrane law '" + FLAGS_membrane +
                     "' (" + MembraneLawNames() + ")");
  }
  material.mu = FLAGS_mu;
  material.lambda = FLAGS_lambda;
  choice.eta_absolute = Given("eta");
  if (choice.eta_absolute && Given("relative_eta")) {
    throw InputError(
        "--eta and --relative_eta: give one of them (--eta is absolute, "
        "--relative_eta is multiplied by the reference's area)");
  }
  material.eta = choice.eta_absolute
                     ? FLAGS_eta
                     : EtaFromRelative(FLAGS_relative_eta, reference);
  material.Validate();
  return choice;
}

std::vector<int> MaskFromFlags(int num_vertices) {
  return FLAGS_mask.empty() ? std::vector<int>{}
                            : ReadMask(FLAGS_mask, num_vertices,
                                       ReadStopToken());
}

SolverSettings SettingsFromFlags(const std::string& label) {
  SolverSettings settings =
      UserSolverSettings(FLAGS_tolerance, FLAGS_max_iterations, FLAGS_threads,
                         FLAGS_quiet, label);
  settings.stop = SolveStopToken();
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
  if (list.back() == ',') {
    throw InputError("--" + flag + " has an empty item (a trailing comma)");
  }
  return items;
}

}  // namespace shellspace
