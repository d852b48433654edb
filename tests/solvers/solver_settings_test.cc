// UserSolverSettings: the front ends' solver keywords (CLI flags, Python
// keywords) become SolverSettings with one set of ranges.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "shellspace/geometry/mesh.h"
#include "shellspace/solvers/solver_settings.h"

namespace shellspace {
namespace {

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(UserSolverSettingsTest, CarriesTheValuesAndKeepsTheDefaults) {
  const SolverSettings s = UserSolverSettings(1e-6, 17, 3, true, "mean");
  EXPECT_EQ(s.gradient_tolerance, 1e-6);
  EXPECT_EQ(s.max_iterations, 17);
  EXPECT_EQ(s.num_threads, 3);
  EXPECT_FALSE(s.progress);
  EXPECT_EQ(s.progress_label, "mean");
  const SolverSettings defaults;
  EXPECT_EQ(s.function_tolerance, defaults.function_tolerance);
  EXPECT_EQ(s.parameter_tolerance, defaults.parameter_tolerance);
  EXPECT_EQ(s.initial_trust_region_radius,
            defaults.initial_trust_region_radius);
  EXPECT_FALSE(s.stop.stop_possible());
  EXPECT_TRUE(UserSolverSettings(0.5, 1, kMaxSolverThreads, false, "x")
                  .progress);
}

TEST(UserSolverSettingsTest, RefusesValuesOutsideTheRanges) {
  struct Case {
    double tolerance;
    int max_iterations, threads;
    const char* expected;
  };
  for (const Case& c : {
           Case{0.0, 10, 1, "tolerance must be in (0, 1), got 0"},
           Case{1.0, 10, 1, "tolerance must be in (0, 1), got 1"},
           Case{std::nan(""), 10, 1, "tolerance must be in (0, 1)"},
           Case{1e-8, 0, 1, "max_iterations must be >= 1, got 0"},
           Case{1e-8, 10, 0, "threads must be in [1, 1024], got 0"},
           Case{1e-8, 10, kMaxSolverThreads + 1,
                "threads must be in [1, 1024], got 1025"},
       }) {
    const std::string error = ErrorOf([&] {
      UserSolverSettings(c.tolerance, c.max_iterations, c.threads, true, "x");
    });
    EXPECT_NE(error.find(c.expected), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace shellspace
