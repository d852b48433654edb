// Example 2: the discrete geodesic between two meshes with the problem
// builder the `geodesic` verb uses (Ceres LM, then Newton with exact
// Hessians), and what its result reports.
//
//   geodesic_of_two_meshes START.ply END.ply STEPS OUT_DIR [MASK.txt]
//
// writes OUT_DIR/shape_000.ply ... and prints E_K, the step energies and
// the iterations of each stage.
#include <shellspace/cost_functions/shell/shell_space.h>
#include <shellspace/io/frame_sequence.h>
#include <shellspace/problems/calculus/geodesic.h>

#include <cstdio>
#include <cstdlib>
#include <exception>

#include "example_inputs.h"

namespace {

int Run(int argc, char** argv) {
  const examples::TwoPoses poses = examples::ReadTwoPoses(argv[1], argv[2]);
  const shellspace::Mesh& start = poses.first;
  const shellspace::ShellSpace space(start, poses.topology,
                                     shellspace::ShellMaterial{});
  shellspace::GeodesicInput input = shellspace::GeodesicInput::Between(
      start.positions, poses.second, std::atoi(argv[3]));
  if (argc == 6) {
    input.fixed_vertices = shellspace::ReadMask(argv[5], start.num_vertices());
  }
  shellspace::SolverSettings settings;  // relative gradient 1e-8
  settings.progress = false;
  const shellspace::GeodesicResult result =
      shellspace::SolveGeodesic(space, input, settings);

  shellspace::WriteFrames(argv[4], start.faces, result.path);
  std::printf("E_K = %.12g after %d iterations (%s); step energies:",
              result.path_energy, result.iterations,
              result.converged ? "converged" : "NOT converged");
  for (double w : result.step_energies) std::printf(" %.6g", w);
  std::printf("\nwrote %zu shapes to %s\n", result.path.size(), argv[4]);
  return result.converged ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return examples::Main(Run, {4, 5, "START END STEPS OUT_DIR [MASK]"}, argc,
                        argv);
}
