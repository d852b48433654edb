#include "tests/testing/element_samples.h"

namespace shellspace::testing {

std::vector<MeshPairNames> ElementHessianMeshPairs() {
  return {{"cactus/cactus0.ply", "cactus/cactus1.ply"},
          {"finger/finger0.ply", "finger/finger1.ply"},
          {"faces/neutral.ply", "faces/smile.ply"}};
}

}  // namespace shellspace::testing
