#include "shellspace/io/frame_set_check.h"

namespace shellspace {

void CheckFrameSet(const std::vector<Positions>& frames, const Faces& faces,
                   const std::string& what) {
  if (frames.empty()) throw InputError(what + ": no frames");
  const Eigen::Index n = frames[0].rows();
  for (size_t k = 0; k < frames.size(); ++k) {
    if (frames[k].rows() != n) {
      throw InputError(what + ": frame " + std::to_string(k) + " has " +
                       std::to_string(frames[k].rows()) +
                       " vertices, frame 0 has " + std::to_string(n));
    }
    if (!frames[k].allFinite()) {
      throw InputError(what + ": frame " + std::to_string(k) +
                       " has a non-finite coordinate");
    }
  }
  if (faces.rows() == 0) throw InputError(what + ": no faces");
  if (faces.minCoeff() < 0 || faces.maxCoeff() >= n) {
    throw InputError(what + ": a face index is outside [0, " +
                     std::to_string(n) + ")");
  }
}

}  // namespace shellspace
