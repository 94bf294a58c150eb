// nextFloatUp and nextFloatDown, the spawned rays' last ulp: bit for bit what
// std::nextafter towards +inf and -inf returns, over the special values (zeros of
// both signs, the smallest subnormals, the largest floats, infinities) and a million
// random bit patterns; a NaN stays a NaN.
#include "core/math.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

void expectAsNextafter(float v) {
  const float up = nextFloatUp(v), down = nextFloatDown(v);
  if (std::isnan(v)) {
    EXPECT_TRUE(std::isnan(up) && std::isnan(down)) << "bits " << floatBits(v);
    return;
  }
  EXPECT_EQ(floatBits(up), floatBits(std::nextafter(v, kInf))) << "up from bits " << floatBits(v);
  EXPECT_EQ(floatBits(down), floatBits(std::nextafter(v, -kInf))) << "down from bits " << floatBits(v);
}

TEST(NextFloat, SpecialValuesStepAsNextafter) {
  const float big = std::numeric_limits<float>::max(), tiny = std::numeric_limits<float>::denorm_min();
  for (float v : {0.0f, -0.0f, tiny, -tiny, std::numeric_limits<float>::min(), -std::numeric_limits<float>::min(),
                  big, -big, kInf, -kInf, 1.0f, -1.0f, std::numeric_limits<float>::quiet_NaN()})
    expectAsNextafter(v);
}

TEST(NextFloat, RandomBitPatternsStepAsNextafter) {
  Rng rng(41);
  for (int i = 0; i < 1000000; ++i) expectAsNextafter(bitsToFloat(rng.nextU32()));
}

}  // namespace
}  // namespace penumbra
