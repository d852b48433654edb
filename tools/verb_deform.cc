// `shellspace deform`: elastic deformation with prescribed vertex positions.
#include <gflags/gflags.h>

#include <chrono>
#include <cstdio>
#include <iostream>

#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/elastic_deformation.h"
#include "shellspace/tools/common_flags.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/tools/shell_inputs.h"
#include "shellspace/tools/verb.h"

DEFINE_string(targets, "",
              "mesh giving the prescribed positions of the masked vertices "
              "(also the initial guess)");

namespace shellspace {
namespace {

int RunDeform() {
  RequireFlag("reference", FLAGS_reference);
  RequireFlag("mask", FLAGS_mask);
  RequireFlag("targets", FLAGS_targets);
  RequireFlag("output", FLAGS_output);
  const auto start = std::chrono::steady_clock::now();
  const Mesh reference = LoadShell(FLAGS_reference);
  const Mesh targets =
      LoadCompatibleShell(FLAGS_targets, reference, FLAGS_reference);
  const ShellSpace space = SpaceFromFlags(reference);
  ElasticDeformationInput input;
  input.reference = reference.positions;
  input.targets = targets.positions;
  input.initial = targets.positions;
  input.fixed_vertices = ReadMask(FLAGS_mask, reference.num_vertices());
  const ElasticDeformationResult result =
      SolveElasticDeformation(space, input, SettingsFromFlags("deform"));
  if (result.summary.termination_type == ceres::FAILURE) {
    throw InputError("solver failed: " + result.summary.message);
  }
  WriteMesh(Mesh{result.deformed, reference.faces}, FLAGS_output);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  if (FLAGS_json) {
    std::cout << JsonObject()
                     .Add("membrane", result.energy.membrane)
                     .Add("bending", result.energy.bending)
                     .Add("total", result.energy.total)
                     .Add("iterations",
                          static_cast<int>(result.summary.iterations.size()))
                     .Add("converged", result.summary.IsSolutionUsable())
                     .Add("seconds", seconds)
                     .Add("output", FLAGS_output)
                     .str()
              << "\n";
  } else if (!FLAGS_quiet) {
    std::cerr << result.summary.BriefReport() << "\n";
    std::printf("W = %.12g (W_mem %.12g, W_bend %.12g); wrote %s\n",
                result.energy.total, result.energy.membrane,
                result.energy.bending, FLAGS_output.c_str());
  }
  return 0;
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "deform",
    "deform --reference R.ply --mask M.txt --targets T.ply --output OUT.ply "
    "[--mu --lambda --eta] [--json]",
    shellspace::RunDeform);
