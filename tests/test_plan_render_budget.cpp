// The budget's stop rule: two passes always run; a target error stops at the first
// pass whose estimate reaches it; a time limit stops once it has passed, or before a
// pass expected to overrun it by more than kTimeLimitOverrun; bad limits are refused.
#include "plan/render_budget.h"
#include "core/error.h"
#include <gtest/gtest.h>
#include <limits>
#include <string>

namespace penumbra {
namespace {

TEST(RenderBudget, TwoPassesAlwaysRun) {
  const RenderBudget b{1.0, 0.5};
  EXPECT_EQ(budgetStop(b, {1, 100.0, 50.0, 0.0}), nullptr);
  EXPECT_NE(budgetStop(b, {2, 100.0, 50.0, 0.0}), nullptr);
}

TEST(RenderBudget, TargetErrorStopsAtTheFirstPassThatReachesIt) {
  const RenderBudget b{0.0, 0.03};
  EXPECT_EQ(budgetStop(b, {4, 1.0, 0.1, 0.0301}), nullptr);
  EXPECT_EQ(std::string(budgetStop(b, {5, 1.0, 0.1, 0.03})), "target error reached");
  EXPECT_EQ(budgetStop(b, {5, 1.0, 0.1, -1.0}), nullptr) << "an unknown estimate reaches nothing";
  EXPECT_EQ(std::string(budgetStop(b, {kBudgetMaxPasses, 1.0, 0.1, 1.0})), "pass limit reached");
}

TEST(RenderBudget, TimeLimitRunsUntilMetUnlessTheNextPassWouldOverrunIt) {
  const RenderBudget b{10.0, 0.0};
  EXPECT_EQ(budgetStop(b, {8, 9.5, 0.5, 0.1}), nullptr) << "ends at 10.0: within the limit";
  EXPECT_EQ(budgetStop(b, {8, 9.9, 1.0, 0.1}), nullptr) << "ends at 10.9: past it by less than 10%";
  EXPECT_EQ(std::string(budgetStop(b, {8, 10.0, 0.5, 0.1})), "time limit reached");
  EXPECT_NE(budgetStop(b, {8, 9.0, 2.5, 0.1}), nullptr) << "would end at 11.5";
}

TEST(RenderBudget, BadLimitsAreRefusedAndBothAreDescribed) {
  EXPECT_THROW(checkBudget({-1.0, 0.0}), InputError);
  EXPECT_THROW(checkBudget({0.0, std::numeric_limits<double>::quiet_NaN()}), InputError);
  EXPECT_NO_THROW(checkBudget({0.0, 0.0}));
  EXPECT_FALSE(RenderBudget{}.any());
  EXPECT_EQ(describeBudget({10.0, 0.03}), "--time-limit 10 s, --target-error 0.03");
}

}  // namespace
}  // namespace penumbra
