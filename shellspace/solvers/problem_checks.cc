#include "shellspace/solvers/problem_checks.h"

#include <vector>

#include "shellspace/geometry/mesh.h"

namespace shellspace {

void RequireVariableResidual(const ceres::Problem& problem,
                             ceres::ResidualBlockId id, const std::string& what) {
  std::vector<double*> blocks;
  problem.GetParameterBlocksForResidualBlock(id, &blocks);
  for (double* block : blocks) {
    if (!problem.IsParameterBlockConstant(block)) return;
  }
  throw InputError(what + " acts only on constant parameter blocks (" +
                   std::to_string(blocks.size()) +
                   " block(s), all held fixed, e.g. by a mask): it cannot "
                   "move the solution");
}

}  // namespace shellspace
