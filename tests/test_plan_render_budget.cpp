// The budget's stop rule: two passes always run (and an overrun of the limit by them is
// said with its size); a target error stops at the first pass whose noise and bias
// together reach it, of the lighting or of the image; a time limit stops once it has
// passed, or before a pass expected to overrun it by more than kTimeLimitOverrun; bad
// limits are refused.
#include "plan/render_budget.h"
#include "core/error.h"
#include <gtest/gtest.h>
#include <limits>
#include <string>

namespace penumbra {
namespace {

// An estimate whose lighting has this noise and bias (< 0: not measured), and whose
// image has ten times each (a visible emitter's edges).
ErrorEstimate estimate(double noise, double bias) {
  ErrorEstimate e;
  e.source = ErrorSource::Passes;
  e.lightingNoiseRmse = noise;
  e.lightingBiasRmse = bias;
  e.noiseRmse = 10.0 * noise;
  e.biasRmse = bias < 0.0 ? bias : 10.0 * bias;
  return e;
}

BudgetState state(int passes, double elapsed, double lastPass, const ErrorEstimate& e = estimate(0.1, 0.1)) {
  return {passes, elapsed, lastPass, e};
}

TEST(RenderBudget, TwoPassesAlwaysRunAndAnOverrunIsSaidWithItsSize) {
  const RenderBudget b{1.0, 0.5};
  EXPECT_EQ(budgetStop(b, state(1, 100.0, 50.0, estimate(0.0, 0.0))), "");
  EXPECT_EQ(budgetStop(b, state(2, 3.5, 1.7, estimate(1.0, -1.0))),
            "time limit: the 2-pass minimum overran it by 2.5 s (250%)");
  EXPECT_EQ(budgetStop({1.0, 0.0}, state(3, 3.5, 1.2)), "time limit reached") << "the minimum was met before";
}

TEST(RenderBudget, TargetErrorCountsNoiseAndBiasTogether) {
  const RenderBudget b{0.0, 0.05};
  EXPECT_EQ(budgetStop(b, state(4, 1.0, 0.1, estimate(0.04, 0.031))), "") << "sqrt(0.04^2 + 0.031^2) = 0.0506";
  EXPECT_EQ(budgetStop(b, state(5, 1.0, 0.1, estimate(0.04, 0.03))),
            "target error reached: lighting noise 0.04 and bias 0.03, together 0.05 <= 0.05");
  EXPECT_EQ(budgetStop(b, state(3, 1.0, 0.1, estimate(0.01, -1.0))), "") << "the bias is not measured before 4 passes";
  EXPECT_EQ(budgetStop(b, state(5, 1.0, 0.1, estimate(-1.0, 0.0))), "") << "an unknown estimate reaches nothing";
  EXPECT_EQ(budgetStop(b, state(kBudgetMaxPasses, 1.0, 0.1, estimate(1.0, 1.0))), "pass limit reached");
}

TEST(RenderBudget, TheImagesFigureIsSelectable) {
  RenderBudget b{0.0, 0.05};
  b.figure = ErrorFigure::Image;
  EXPECT_EQ(budgetStop(b, state(5, 1.0, 0.1, estimate(0.004, 0.003))),
            "target error reached: image noise 0.04 and bias 0.03, together 0.05 <= 0.05");
  EXPECT_EQ(budgetStop(b, state(5, 1.0, 0.1, estimate(0.04, 0.03))), "") << "the image's is ten times the lighting's";
  EXPECT_EQ(parseErrorFigure("image"), ErrorFigure::Image);
  EXPECT_EQ(parseErrorFigure("lighting"), ErrorFigure::Lighting);
  EXPECT_THROW(parseErrorFigure("noise"), InputError);
}

TEST(RenderBudget, TheBiasBoundIsSelectableAndSaidWhereItStops) {
  ErrorEstimate e = estimate(0.003, 0.0);
  e.lightingBiasBound = 0.006;
  RenderBudget b{0.0, 0.005};
  EXPECT_EQ(budgetStop(b, state(6, 1.0, 0.1, e)),
            "target error reached: lighting noise 0.003 and bias 0, together 0.003 <= 0.005");
  b.bias = parseBiasFigure("bound");
  EXPECT_EQ(budgetStop(b, state(6, 1.0, 0.1, e)), "") << "noise and the bound together are 0.0067";
  e.lightingBiasBound = 0.004;
  EXPECT_EQ(budgetStop(b, state(6, 1.0, 0.1, e)),
            "target error reached: lighting noise 0.003 and bias bound 0.004, together 0.005 <= 0.005");
  // A frame without probes has no bound: the counted bias stands in.
  e.lightingBiasBound = -1.0;
  EXPECT_NE(budgetStop(b, state(6, 1.0, 0.1, e)), "");
  EXPECT_NE(describeBudget(b).find("(lighting, bias bound)"), std::string::npos) << describeBudget(b);
  EXPECT_THROW(parseBiasFigure("most"), InputError);
}

TEST(RenderBudget, TimeLimitRunsUntilMetUnlessTheNextPassWouldOverrunIt) {
  const RenderBudget b{10.0, 0.0};
  EXPECT_EQ(budgetStop(b, state(8, 9.5, 0.5)), "") << "ends at 10.0: within the limit";
  EXPECT_EQ(budgetStop(b, state(8, 9.9, 1.0)), "") << "ends at 10.9: past it by less than 10%";
  EXPECT_EQ(budgetStop(b, state(8, 10.0, 0.5)), "time limit reached");
  EXPECT_EQ(budgetStop(b, state(8, 9.0, 2.5)), "time limit: the next pass would overrun it") << "would end at 11.5";
}

TEST(RenderBudget, BadLimitsAreRefusedAndBothAreDescribed) {
  EXPECT_THROW(checkBudget({-1.0, 0.0}), InputError);
  EXPECT_THROW(checkBudget({0.0, std::numeric_limits<double>::quiet_NaN()}), InputError);
  EXPECT_NO_THROW(checkBudget({0.0, 0.0}));
  EXPECT_FALSE(RenderBudget{}.any());
  EXPECT_EQ(describeBudget({10.0, 0.03}), "--time-limit 10 s, --target-error 0.03 (lighting)");
}

}  // namespace
}  // namespace penumbra
