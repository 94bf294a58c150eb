// nextFloatUp and nextFloatDown, the spawned rays' last ulp: bit for bit what
// std::nextafter towards +inf and -inf returns, over the special values (zeros of
// both signs, the smallest subnormals, the largest floats, infinities) and a million
// random bit patterns; a NaN stays a NaN.
#include "core/math.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <cmath>
#include <cstring>
#include <vector>

namespace penumbra {
namespace {

uint32_t bitsOf(float v) {
  uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}
float fromBits(uint32_t b) {
  float v;
  std::memcpy(&v, &b, sizeof v);
  return v;
}

void expectAsNextafter(float v) {
  const float up = nextFloatUp(v), down = nextFloatDown(v);
  if (std::isnan(v)) {
    EXPECT_TRUE(std::isnan(up) && std::isnan(down)) << "bits " << bitsOf(v);
    return;
  }
  EXPECT_EQ(bitsOf(up), bitsOf(std::nextafter(v, kInf))) << "up from bits " << bitsOf(v);
  EXPECT_EQ(bitsOf(down), bitsOf(std::nextafter(v, -kInf))) << "down from bits " << bitsOf(v);
}

TEST(NextFloat, SpecialValuesStepAsNextafter) {
  const float big = std::numeric_limits<float>::max(), tiny = std::numeric_limits<float>::denorm_min();
  for (float v : {0.0f, -0.0f, tiny, -tiny, std::numeric_limits<float>::min(), -std::numeric_limits<float>::min(),
                  big, -big, kInf, -kInf, 1.0f, -1.0f, std::numeric_limits<float>::quiet_NaN()})
    expectAsNextafter(v);
}

TEST(NextFloat, RandomBitPatternsStepAsNextafter) {
  Rng rng(41);
  for (int i = 0; i < 1000000; ++i) expectAsNextafter(fromBits(rng.nextU32()));
}

}  // namespace
}  // namespace penumbra
