// Name tables of enumerations: canonical names, aliases, the list of choices
// an error message prints, and the parsers and printers built on them.
#include "shellspace/geometry/named_values.h"

#include <gtest/gtest.h>

#include <string>

#include "shellspace/cost_functions/shell/shell_space.h"
#include "shellspace/solvers/newton_solver.h"

namespace shellspace {
namespace {

enum class Axis { kX, kY, kZ, kUnnamed };

constexpr NamedValue<Axis> kAxisNames[] = {
    {Axis::kX, "x"}, {Axis::kY, "y"}, {Axis::kZ, "z"},
    {Axis::kX, "+x"}, {Axis::kY, "+y"}};

TEST(NamedValuesTest, TheFirstEntryOfAValueIsItsName) {
  EXPECT_STREQ(NameOf(kAxisNames, Axis::kX), "x");
  EXPECT_STREQ(NameOf(kAxisNames, Axis::kY), "y");
  EXPECT_STREQ(NameOf(kAxisNames, Axis::kZ), "z");
  EXPECT_STREQ(NameOf(kAxisNames, Axis::kUnnamed), "unknown");
  EXPECT_STREQ(NameOf(kAxisNames, Axis::kUnnamed, "none"), "none");
}

TEST(NamedValuesTest, EveryEntryParsesAndNothingElse) {
  EXPECT_EQ(ValueNamed(kAxisNames, "x"), Axis::kX);
  EXPECT_EQ(ValueNamed(kAxisNames, "+x"), Axis::kX);
  EXPECT_EQ(ValueNamed(kAxisNames, "+y"), Axis::kY);
  EXPECT_EQ(ValueNamed(kAxisNames, "z"), Axis::kZ);
  EXPECT_FALSE(ValueNamed(kAxisNames, "+z").has_value());
  EXPECT_FALSE(ValueNamed(kAxisNames, "X").has_value());  // exact spelling
  EXPECT_FALSE(ValueNamed(kAxisNames, "").has_value());
  EXPECT_FALSE(ValueNamed(kAxisNames, "x ").has_value());
}

TEST(NamedValuesTest, ChoicesListTheCanonicalNamesAsASentence) {
  EXPECT_EQ(NameChoices(kAxisNames), "x, y or z");
  constexpr NamedValue<Axis> kTwo[] = {{Axis::kY, "y"}, {Axis::kX, "x"}};
  EXPECT_EQ(NameChoices(kTwo), "y or x");
  constexpr NamedValue<Axis> kOne[] = {{Axis::kZ, "z"}, {Axis::kZ, "up"}};
  EXPECT_EQ(NameChoices(kOne), "z");
}

// Every name a table prints parses back to its value (the round trip the
// tables exist for), through the library's own parsers.
TEST(NamedValuesTest, LibraryNamesRoundTrip) {
  for (BendingModel model :
       {BendingModel::kDiscreteShells, BendingModel::kShapeOperator}) {
    BendingModel parsed = BendingModel::kDiscreteShells;
    ASSERT_TRUE(ParseBendingModel(BendingModelName(model), &parsed));
    EXPECT_EQ(parsed, model);
  }
  BendingModel untouched = BendingModel::kShapeOperator;
  EXPECT_FALSE(ParseBendingModel("discrete shells", &untouched));
  EXPECT_EQ(untouched, BendingModel::kShapeOperator);
  // Root finding names three stops differently from minimisation.
  EXPECT_EQ(NewtonStopText(NewtonStop::kLinearSolveFailed,
                           NewtonMode::kMinimize),
            "Hessian not positive definite");
  EXPECT_EQ(NewtonStopText(NewtonStop::kLinearSolveFailed,
                           NewtonMode::kRootFind),
            "singular Jacobian");
  EXPECT_EQ(NewtonStopText(NewtonStop::kConverged, NewtonMode::kRootFind),
            "converged");
}

}  // namespace
}  // namespace shellspace
