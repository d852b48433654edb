// What the workflows share: the resolved material of a run, the membrane /
// bending split of an energy, the record of whether the stop token stopped
// a solve, and the numbers of the failure texts.
#ifndef SHELLSPACE_WORKFLOWS_COMMON_H_
#define SHELLSPACE_WORKFLOWS_COMMON_H_

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/geometry/mesh.h"
#include "shellspace/io/json_writer.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {
namespace workflows {

// The material of a run as its front end resolved it (the CLI's flags, the
// Python keywords): eta_absolute when eta was given rather than relative
// to the reference's area; the record names both (reports' MaterialJson).
struct MaterialChoice {
  ShellMaterial material;
  bool eta_absolute = false;
};

// The "material" record of a run's summary for `choice` resolved for
// `reference` (reports' MaterialJson): mu, lambda, eta, relative_eta,
// eta_from, reference_area, bending_model.
JsonObject MaterialChoiceJson(const MaterialChoice& choice,
                              const Mesh& reference);

// The membrane / bending split of an energy whose bending part includes
// eta: membrane + bending is the energy.
struct EnergySplit {
  double membrane = 0;
  double bending = 0;
  double total() const { return membrane + bending; }
  // bending / total (0 when both are 0).
  double bending_share() const {
    return total() > 0 ? bending / total() : 0.0;
  }
};

// E_K = K sum_k W[s_{k-1}, s_k] of `path` split (one evaluation per step).
EnergySplit PathEnergySplit(const ShellSpace& space, const std::vector<Positions>& path);
// The mean's objective sum_i W[S_i, mean] (the inputs as references, as
// ElasticMeanResult::energy) split.
EnergySplit MeanEnergySplit(const ShellSpace& space, const Positions& mean,
                            const std::vector<Positions>& shapes);
// {"membrane", "bending", "bending_share"} (reports' EnergySplitJson).
JsonObject EnergySplitJson(const EnergySplit& split);

// Whether a stop token said stop to a solve: the constructor replaces the
// token of `settings` by one that says what it says and records, in
// stopped(), that it said stop. A workflow's stop state is what its solves
// saw, without asking the token itself (which could see a time limit that
// no solve was cut by).
class StopRecorder {
 public:
  explicit StopRecorder(SolverSettings* settings)
      : StopRecorder(&settings->stop) {}
  // The same for a token of its own (SplineSettings::stop).
  explicit StopRecorder(StopToken* token);
  bool stopped() const { return flag_->load(); }

 private:
  std::shared_ptr<std::atomic<bool>> flag_;
};

// "%.3g" of a number, for the failure texts.
std::string ShortNumber(double value);

}  // namespace workflows
}  // namespace shellspace

#endif  // SHELLSPACE_WORKFLOWS_COMMON_H_
