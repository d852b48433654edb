// The --json summary and frame output shared by the path-producing verbs.
#ifndef SHELLSPACE_TOOLS_PATH_SUMMARY_H_
#define SHELLSPACE_TOOLS_PATH_SUMMARY_H_

#include <ceres/solver.h>

#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/problems/calculus/geodesic.h"
#include "shellspace/io/json_writer.h"

namespace shellspace {

// JSON with path_energy, step_energies, iterations, final_gradient_norm
// (max norm), termination, seconds, frames. With a Newton stage (`newton`,
// geodesic interpolation) its steps count as iterations, its final gradient
// is reported if it converged, and newton_steps, newton_seconds,
// factorizations and cg_iterations are added.
JsonObject PathSummary(const ShellSpace& space, const ShellPath& path,
                       const std::vector<ceres::Solver::Summary>& summaries,
                       double seconds,
                       const PathNewtonReport* newton = nullptr);

// Writes DIR/shape_000.ply ... and, if --png is set, a film strip.
void WritePathOutputs(const std::string& dir, const Faces& faces,
                      const ShellPath& path);

}  // namespace shellspace

#endif  // SHELLSPACE_TOOLS_PATH_SUMMARY_H_
