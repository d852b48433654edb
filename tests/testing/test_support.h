// Shared helpers of the test suite: data paths, loading shells, running the
// CLI.
#ifndef SHELLSPACE_TESTS_TESTING_TEST_SUPPORT_H_
#define SHELLSPACE_TESTS_TESTING_TEST_SUPPORT_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace::testing {

// Absolute path of a file under ../shared/data.
std::string DataPath(const std::string& relative);

// Reads and validates a mesh of ../shared/data.
Mesh LoadData(const std::string& relative);

// ShellSpace of a mesh with the given material.
ShellSpace MakeSpace(const Mesh& mesh, const ShellMaterial& material = {});

// The material the CLI uses without material flags: mu = lambda = 1 and eta
// = kDefaultRelativeEta x the surface area of `reference` (its first input;
// cost_functions/shell/relative_bending_weight.h), with `bending`.
ShellMaterial CliDefaultMaterial(
    const Mesh& reference,
    BendingModel bending = BendingModel::kDiscreteShells);

// Two meshes of ../shared/data with one connectivity and the ShellSpace of
// the first: the fixture of most calculus tests.
struct ShellPair {
  Mesh start, end;
  ShellSpace space;
};
ShellPair LoadPair(const std::string& start, const std::string& end,
                   const ShellMaterial& material = {});

// The Euler-Lagrange residual of E_K / K at the inner shape k of `path`:
// D_2 W[s_{k-1}, s_k] + D_1 W[s_k, s_{k+1}] (3n, vertex-major).
Eigen::VectorXd InteriorPathGradient(const ShellSpace& space,
                                     const std::vector<Positions>& path, int k);

// Settings of solves meant to converge to round-off: the given relative
// gradient tolerance, function and parameter tolerances 1e-16, 500 LM
// iterations.
SolverSettings TightSettings(double gradient_tolerance);

// A fresh empty temporary directory.
std::string TempDir();

// The names of the entries of `dir`, sorted.
std::vector<std::string> DirectoryListing(const std::string& dir);

// Runs `shellspace ARGS` with stdout and stderr captured; returns exit code.
int RunCli(const std::string& args, std::string* out = nullptr,
           std::string* err = nullptr);

// Runs `shellspace ARGS` in the directory `dir` (relative spellings are
// relative to it); returns the exit code, stderr in `err`.
int RunCliIn(const std::string& dir, const std::string& args,
             std::string* err);

// A run of the CLI as a child process (RunCliWithTimeout).
struct CliRun {
  int code = -1;  // exit code; -1: killed (timeout) or died of a signal
  std::string err;
  double seconds = 0;
};

// Runs `shellspace ARGS` (stdout discarded) with stderr captured; sends
// SIGTERM after `signal_after` seconds (< 0: never); kills it after
// `timeout` seconds, so that a run that would hang fails instead.
CliRun RunCliWithTimeout(const std::string& args, double timeout = 20,
                         double signal_after = -1);

// The shape-operator material with bending weight eta and weights alpha, beta
// (docs/math.md, "Bending energy: two models").
ShellMaterial ShapeOperatorMaterial(double eta, double alpha = 0,
                                    double beta = 1);

// Two curved shells of one connectivity: a 5 x 4 equilateral sheet (faces
// with 1, 2 and 3 interior edges) bent by two smooth height fields plus a
// fixed-seed noise of 0.05 (the deformed one also in the plane); mesh's
// positions are the reference's.
struct BumpySheetPair {
  Mesh mesh;
  Positions reference, deformed;
};
BumpySheetPair MakeBumpySheetPair();

// `mesh` with its vertices renamed and its faces reordered at random (fixed
// seed; each face keeps its vertices' cyclic order), as a mesh file may
// number them: the same shell, scattered over its arrays.
Mesh ShuffledNumbering(const Mesh& mesh, unsigned seed);

// A random rigid motion (rotation by a random unit quaternion, translation
// with entries in [-1, 1]) applied to `p`, with a fixed seed.
Positions RandomRigidMotion(const Positions& p, unsigned seed);

}  // namespace shellspace::testing

#endif  // SHELLSPACE_TESTS_TESTING_TEST_SUPPORT_H_
