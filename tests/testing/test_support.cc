#include "tests/testing/test_support.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>

#include "shellspace/cost_functions/shell/energy_derivatives.h"
#include "shellspace/cost_functions/shell/relative_bending_weight.h"
#include "shellspace/geometry/procedural_shapes.h"
#include "shellspace/geometry/validation.h"
#include "shellspace/io/mesh_io.h"
#include "tests/testing/cli_output.h"

namespace shellspace::testing {

// The environment variable SHELLSPACE_DATA first (CTest sets it: the data
// folder for data tests, a folder that does not exist for unit tests), else
// the folder configured in tests/CMakeLists.txt (SHELLSPACE_DATA, default
// ../shared/data).
std::string DataPath(const std::string& relative) {
  const char* dir = std::getenv("SHELLSPACE_DATA");
  return std::string(dir && *dir ? dir : SHELLSPACE_DATA_DIR) + "/" + relative;
}

Mesh LoadData(const std::string& relative) {
  Mesh mesh = ReadMesh(DataPath(relative));
  ValidateShell(mesh, relative);
  return mesh;
}

ShellSpace MakeSpace(const Mesh& mesh, const ShellMaterial& material) {
  return ShellSpace(mesh, Topology::Build(mesh), material);
}

Mesh ShuffledNumbering(const Mesh& mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<int> label(mesh.num_vertices()), order(mesh.num_faces());
  std::iota(label.begin(), label.end(), 0);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(label.begin(), label.end(), rng);
  std::shuffle(order.begin(), order.end(), rng);
  Mesh out;
  out.positions.resize(mesh.num_vertices(), 3);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    out.positions.row(label[v]) = mesh.positions.row(v);
  }
  out.faces.resize(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c)
      out.faces(f, c) = label[mesh.faces(order[f], c)];
  }
  return out;
}

ShellMaterial CliDefaultMaterial(const Mesh& reference, BendingModel bending) {
  ShellMaterial material;
  material.eta = EtaFromRelative(kDefaultRelativeEta, reference);
  material.bending_model = bending;
  return material;
}

ShellPair LoadPair(const std::string& start, const std::string& end,
                   const ShellMaterial& material) {
  ShellPair pair;
  pair.start = LoadData(start);
  pair.end = LoadData(end);
  pair.space = MakeSpace(pair.start, material);
  return pair;
}

Eigen::VectorXd InteriorPathGradient(const ShellSpace& space,
                                     const std::vector<Positions>& path,
                                     int k) {
  return EnergyGradient(space, path[k - 1], path[k], ShellSide::kDeformed) +
         EnergyGradient(space, path[k], path[k + 1], ShellSide::kReference);
}

SolverSettings TightSettings(double gradient_tolerance) {
  SolverSettings settings;
  settings.gradient_tolerance = gradient_tolerance;
  settings.function_tolerance = 1e-16;
  settings.parameter_tolerance = 1e-16;
  settings.max_iterations = 500;
  return settings;
}

std::string TempDir() {
  char pattern[] = "/tmp/shellspace_test_XXXXXX";
  const char* dir = mkdtemp(pattern);
  return dir ? dir : "/tmp";
}

int RunCli(const std::string& args, std::string* out, std::string* err) {
  const std::string dir = TempDir();
  const std::string command = std::string(SHELLSPACE_CLI) + " " + args + " > " +
                              dir + "/out 2> " + dir + "/err";
  const int status = std::system(command.c_str());
  if (out) *out = Slurp(dir + "/out");
  if (err) *err = Slurp(dir + "/err");
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int RunCliIn(const std::string& dir, const std::string& args,
             std::string* err) {
  const std::string log = TempDir();
  const std::string command = "cd '" + dir + "' && " + SHELLSPACE_CLI + " " +
                              args + " > " + log + "/out 2> " + log + "/err";
  const int status = std::system(command.c_str());
  *err = Slurp(log + "/err");
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

CliRun RunCliWithTimeout(const std::string& args, double timeout,
                         double signal_after) {
  CliRun run;
  int fds[2];
  if (pipe(fds) != 0) return run;
  const std::string command =
      std::string("exec ") + SHELLSPACE_CLI + " " + args + " > /dev/null";
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], 2);
    close(fds[0]);
    close(fds[1]);
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  bool signalled = signal_after < 0;
  char chunk[4096];
  while (true) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    if (elapsed > timeout) {
      kill(pid, SIGKILL);
      run.err += "[killed after the timeout]";
      break;
    }
    if (!signalled && elapsed >= signal_after) {
      kill(pid, SIGTERM);
      signalled = true;
    }
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, 20) <= 0) continue;
    const ssize_t n = read(fds[0], chunk, sizeof(chunk));
    if (n <= 0) break;  // EOF: the child exited
    run.err.append(chunk, static_cast<size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  run.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

Positions RandomRigidMotion(const Positions& p, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(-1, 1);
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  q.normalize();
  const Eigen::Matrix3d r = q.toRotationMatrix();
  const Eigen::RowVector3d t(uniform(rng), uniform(rng), uniform(rng));
  Positions out = p * r.transpose();
  out.rowwise() += t;
  return out;
}

std::vector<std::string> DirectoryListing(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

ShellMaterial ShapeOperatorMaterial(double eta, double alpha, double beta) {
  ShellMaterial material;
  material.eta = eta;
  material.bending_model = BendingModel::kShapeOperator;
  material.shape_operator_alpha = alpha;
  material.shape_operator_beta = beta;
  return material;
}

BumpySheetPair MakeBumpySheetPair() {
  BumpySheetPair s;
  s.mesh = MakeEquilateralSheet(5, 4, 1.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.05, 0.05);
  s.reference = s.mesh.positions;
  s.deformed = s.mesh.positions;
  for (int v = 0; v < s.mesh.num_vertices(); ++v) {
    const double x = s.mesh.positions(v, 0), y = s.mesh.positions(v, 1);
    s.reference(v, 2) = 0.3 * std::sin(0.8 * x) * std::cos(0.6 * y) + noise(rng);
    s.deformed(v, 2) = 0.5 * std::cos(0.5 * x + 0.3 * y) + noise(rng);
    s.deformed(v, 0) += noise(rng);
    s.deformed(v, 1) += noise(rng);
  }
  s.mesh.positions = s.reference;
  return s;
}

}  // namespace shellspace::testing
