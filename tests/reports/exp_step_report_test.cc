// The words a shot's report gives each EXP step: "solved" only for a step
// whose residual met the acceptance, whatever the last solver's own
// termination says (an LM fallback that stops at its function tolerance
// ends with Ceres' CONVERGENCE without solving F = 0).
#include <gtest/gtest.h>

#include <string>

#include "shellspace/reports/path_reports.h"

namespace shellspace {
namespace {

bool StartsWith(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

TEST(ExpStepReportTest, AnUnsolvedStepIsNotSolvedThoughLmConverged) {
  ExpStepResult step;
  step.solved = false;
  step.method = ExpStepResult::Method::kLevenbergMarquardt;
  step.summary.termination_type = ceres::CONVERGENCE;
  step.summary.message = "Function tolerance reached.";
  const std::string words = ExpStepTermination(step);
  EXPECT_EQ(words,
            "not solved (levenberg-marquardt: Function tolerance reached.)");
  ShootResult shot;
  shot.exp_steps = {step};
  const std::string json = ExpStepStages(shot).front().str();
  EXPECT_EQ(json.find("CONVERGENCE"), std::string::npos) << json;
  EXPECT_NE(json.find("\"termination\": \"not solved ("), std::string::npos)
      << json;
}

TEST(ExpStepReportTest, ASolvedStepSaysSolvedAndHow) {
  ExpStepResult step;
  step.solved = true;
  step.method = ExpStepResult::Method::kNewton;
  step.summary.message = "Newton on F: residual below the tolerance";
  EXPECT_TRUE(StartsWith(ExpStepTermination(step), "solved (newton: Newton"))
      << ExpStepTermination(step);
}

}  // namespace
}  // namespace shellspace
