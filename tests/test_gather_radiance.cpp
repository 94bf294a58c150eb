// The physical radiance estimate's shrinking gathers across progressive passes:
// against the recurrence and Gamma's asymptote.
#include "gather/radiance_estimate.h"
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

TEST(PassSchedule, ShareFollowsTheRecurrenceAndItsAsymptote) {
  // r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1) from K&Z's 1-based i, pass 0 at share 1.
  for (float alpha : {0.5f, 2.0f / 3.0f, 0.7f}) {
    double share = 1.0;
    for (uint32_t pass = 0; pass < 300; ++pass) {
      if (pass > 0) share *= (pass + double(alpha)) / (pass + 1.0);
      EXPECT_NEAR(passRadiusShare(pass, alpha) / share, 1.0, 1e-9) << alpha << " pass " << pass;
    }
    // share ~ i^(alpha - 1) / Gamma(1 + alpha) for large i (relative term O(1 / i)).
    const double i = 1e5, asymptote = std::pow(i, alpha - 1.0) / std::tgamma(1.0 + alpha);
    EXPECT_NEAR(passRadiusShare(uint32_t(i), alpha) / asymptote, 1.0, 1e-3) << alpha;
  }
  EXPECT_EQ(passRadiusShare(1000, 1.0f), 1.0);  // alpha 1: the radius stays
}

TEST(PassSchedule, KShrinksByTheShareRoundedAndStaysAboveTheMinimum) {
  const float alpha = 2.0f / 3.0f;
  EXPECT_EQ(passK(100, 0, alpha), 100);  // pass 0 is the one-pass estimate
  EXPECT_EQ(passK(100, 1, alpha), 83);   // 100 x (1 + 2/3) / 2
  EXPECT_EQ(passK(100, 63, alpha), static_cast<int>(std::lround(100 * passRadiusShare(63, alpha))));
  EXPECT_NEAR(passK(100, 63, alpha), 28, 0);  // share 0.2765
  EXPECT_EQ(passK(50, 100000, alpha), kMinPassK);
  EXPECT_EQ(passK(1, 10, alpha), 1);  // a k at or below the minimum stays
  int last = 1 << 30;
  for (uint32_t pass = 0; pass < 2000; ++pass) {
    const int k = passK(200, pass, alpha);
    EXPECT_LE(k, last);
    last = k;
  }
}

}  // namespace
}  // namespace penumbra
