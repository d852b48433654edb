// The consumer of every room (shellspace::shellspace): writes a bent 4 x 4
// grid with io/, reads it back, computes the geodesic of three steps from
// the flat grid to it (problems/calculus/ on solvers/: Ceres LM, then Newton
// with CHOLMOD) and encodes a PNG (libpng) and a glTF animation of the path
// (tinygltf), so that the private dependencies of the static rooms are
// linked and used. No data files; `whole OUT_DIR` writes OUT_DIR/bent.ply.
// Exits non-zero unless every result is sane.
#include <shellspace/cost_functions/shell/shell_space.h>
#include <shellspace/geometry/topology.h>
#include <shellspace/geometry/validation.h>
#include <shellspace/io/gltf_writer.h>
#include <shellspace/io/mesh_io.h>
#include <shellspace/io/png_writer.h>
#include <shellspace/problems/calculus/geodesic.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "grid.h"

namespace {

constexpr int kSteps = 3;

int Run(const std::string& out_dir) {
  const shellspace::Mesh flat = consumer::MakeFlatGrid();
  shellspace::Mesh bent = flat;
  for (int v = 0; v < bent.num_vertices(); ++v) {
    const double x = bent.positions(v, 0) - 0.5;
    bent.positions(v, 2) = 0.3 * x * x;
  }
  const std::string path = out_dir + "/bent.ply";
  shellspace::WriteMesh(bent, path);
  const shellspace::Mesh read = shellspace::ReadMesh(path);

  const shellspace::Topology topology = shellspace::ValidateShell(flat, "flat");
  shellspace::CheckCompatible(flat, "flat", read, path);
  const shellspace::ShellSpace space(flat, topology, shellspace::ShellMaterial{});
  shellspace::SolverSettings settings;
  settings.progress = false;
  const shellspace::GeodesicResult result = shellspace::SolveGeodesic(
      space, shellspace::GeodesicInput::Between(flat.positions, read.positions, kSteps),
      settings);

  const std::string png = shellspace::EncodePng(shellspace::RgbImage(2, 2));
  const std::string glb =
      shellspace::EncodeGltfMorphAnimation(result.path, flat.faces);

  std::vector<const char*> failures;
  if (read.num_vertices() != bent.num_vertices() ||
      !((read.positions - bent.positions).cwiseAbs().maxCoeff() <= 1e-12)) {
    failures.push_back("the mesh read back differs from the one written");
  }
  if (!result.converged) failures.push_back("the geodesic did not converge");
  if (result.path.size() != kSteps + 1) {
    failures.push_back("the geodesic has the wrong number of shapes");
  }
  if (!(std::isfinite(result.path_energy) && result.path_energy > 0)) {
    failures.push_back("the path energy is not finite and positive");
  }
  if (png.compare(0, 4, "\x89PNG") != 0) failures.push_back("not a PNG");
  if (glb.compare(0, 4, "glTF") != 0) failures.push_back("not a .glb");

  std::printf(
      "shellspace whole consumer: %s  E_K = %.10g after %d iterations (%s), "
      "%zu shapes, PNG %zu bytes, glb %zu bytes\n",
      failures.empty() ? "OK" : "FAILED", result.path_energy,
      result.iterations, result.converged ? "converged" : "NOT converged",
      result.path.size(), png.size(), glb.size());
  for (const char* failure : failures) {
    std::fprintf(stderr, "shellspace whole consumer: FAILED: %s\n", failure);
  }
  return failures.empty() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    return Run(argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shellspace whole consumer: FAILED: %s\n", e.what());
    return 1;
  }
}
