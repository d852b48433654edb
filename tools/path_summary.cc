#include "shellspace/tools/path_summary.h"

#include "shellspace/render/film_strip.h"
#include "shellspace/tools/common_flags.h"
#include "shellspace/tools/shell_inputs.h"

namespace shellspace {

JsonObject PathSummary(const ShellSpace& space, const ShellPath& path,
                       const std::vector<ceres::Solver::Summary>& summaries,
                       double seconds, const PathNewtonReport* newton) {
  std::vector<double> steps;
  const double energy = PathEnergy(space, path, &steps);
  int iterations = 0;
  double gradient = 0;
  std::string termination = "none";
  bool usable = true;
  for (const auto& s : summaries) {
    iterations += static_cast<int>(s.iterations.size());
    if (!s.iterations.empty()) {
      gradient = std::max(gradient, s.iterations.back().gradient_max_norm);
    }
    termination = ceres::TerminationTypeToString(s.termination_type);
    usable &= s.IsSolutionUsable() || s.iterations.empty();
  }
  if (newton != nullptr) {
    iterations += newton->steps;
    if (newton->converged && newton->steps > 0) {
      gradient = newton->final_gradient;
    }
  }
  JsonObject json;
  json.Add("path_energy", energy)
      .Add("step_energies", steps)
      .Add("iterations", iterations)
      .Add("final_gradient_norm", gradient)
      .Add("termination", termination)
      .Add("converged", usable)
      .Add("seconds", seconds)
      .Add("frames", static_cast<int>(path.size()));
  if (newton != nullptr) {
    json.Add("newton_steps", newton->steps)
        .Add("newton_seconds", newton->seconds)
        .Add("factorizations", newton->factorizations)
        .Add("cg_iterations", newton->cg_iterations);
  }
  return json;
}

void WritePathOutputs(const std::string& dir, const Faces& faces,
                      const ShellPath& path) {
  RenderOptions options;
  if (!FLAGS_png.empty()) ValidateRenderOptions(options);
  WriteFrames(dir, faces, path);
  if (!FLAGS_png.empty()) WriteFilmStrip(path, faces, options, FLAGS_png);
}

}  // namespace shellspace
