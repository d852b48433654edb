// `shellspace deform`: elastic deformation with prescribed vertex positions.
#include <gflags/gflags.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "shellspace/io/json_writer.h"
#include "shellspace/io/mesh_io.h"
#include "shellspace/problems/calculus/elastic_deformation.h"
#include "tools/run/common_flags.h"
#include "tools/verbs/path_summary.h"
#include "tools/run/run_output.h"
#include "tools/run/run_paths.h"
#include "tools/run/run_status.h"
#include "tools/run/shell_inputs.h"
#include "tools/verbs/verb.h"
#include "tools/run/stop_request.h"

DEFINE_string(targets, "", "deform: prescribed positions");

namespace shellspace {
namespace {

FlagTable DeformFlags() {
  return Flags(
      {{
           TextFlag("reference", "reference (undeformed) shell").Required(),
           TextFlag("mask",
                    "vertex mask file: one 0-based index per line, '#' "
                    "comments; the listed vertices are prescribed")
               .Required(),
           TextFlag("targets",
                    "mesh giving the prescribed positions of the masked "
                    "vertices (also the initial guess)")
               .Required(),
           TextFlag("output", "the deformed shell: PLY, OBJ or OFF")
               .Required(),
       },
       MaterialFlags(), SolverFlags(), JsonFlag()});
}

int RunDeform() {
  const auto start = std::chrono::steady_clock::now();
  RunPaths()
      .InputFile("reference", FLAGS_reference)
      .InputFile("targets", FLAGS_targets)
      .InputFile("mask", FLAGS_mask)
      .OutputMesh("output", FLAGS_output)
      .Check();
  const auto [reference, targets] =
      LoadShellPair(FLAGS_reference, FLAGS_targets);
  const workflows::MaterialChoice material =
      MaterialChoiceFromFlags(reference.mesh);
  const ShellSpace space(reference.mesh, reference.topology, material.material);
  ElasticDeformationInput input;
  input.reference = reference.mesh.positions;
  input.targets = targets.positions;
  input.initial = targets.positions;
  input.fixed_vertices = ReadMask(FLAGS_mask, reference.mesh.num_vertices(),
                                   ReadStopToken());
  const ElasticDeformationResult result =
      SolveElasticDeformation(space, input, SettingsFromFlags("deform"));
  if (result.summary.termination_type == ceres::FAILURE) {
    throw InputError("solver failed: " + result.summary.message);
  }
  // The relative gradient criterion of the LM solve (Ceres' gradient
  // tolerance is FLAGS_tolerance * max(1, |grad_0|), solver_settings.h).
  const auto& iterations = result.summary.iterations;
  const double g0 = iterations.empty() ? 0.0 : iterations.front().gradient_max_norm;
  const double g = iterations.empty() ? 0.0 : iterations.back().gradient_max_norm;
  const double target = FLAGS_tolerance * std::max(1.0, g0);
  const bool converged = g <= target;
  RunStatus status("deform");
  status.Require(converged, "deform: " + GradientAboveTarget(g, target) +
                                " after " +
                                std::to_string(LmIterations(result.summary)) +
                                " LM iterations (" +
                                ceres::TerminationTypeToString(
                                    result.summary.termination_type) +
                                ")");
  WriteMesh(Mesh{result.deformed, reference.mesh.faces}, FLAGS_output);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  if (FLAGS_json) {
    JsonObject json;
    json.Add("material",
             workflows::MaterialChoiceJson(material, reference.mesh))
        .Add("bending_model", FLAGS_bending);
    std::cout << AddRunFields(json)
                     .Add("membrane", result.energy.membrane)
                     .Add("bending", result.energy.bending)
                     .Add("total", result.energy.total)
                     .Add("iterations", LmIterations(result.summary))
                     .Add("initial_gradient_norm", g0)
                     .Add("final_gradient_norm", g)
                     .Add("relative_gradient_norm", g0 > 0 ? g / g0 : 0.0)
                     .Add("converged", converged)
                     .Add("termination", ceres::TerminationTypeToString(
                                             result.summary.termination_type))
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
  return status.Finish();
}

}  // namespace
}  // namespace shellspace

SHELLSPACE_REGISTER_VERB(
    "deform",
    "deform --reference R.ply --mask M.txt --targets T.ply --output OUT.ply "
    "[--mu --lambda --eta] [--json]",
    shellspace::DeformFlags(), shellspace::RunDeform);
