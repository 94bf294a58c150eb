// The indirect photons' shared-exponent power (Ward's RGBE, rounded): every channel
// comes back within 2^-8 of the largest, rounding is to nearest (no bias), black and
// garbage store as exact 0, and decoding a stored code re-encodes to the same bits.
#include "core/photon.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <cmath>
#include <limits>

namespace penumbra {
namespace {

constexpr float kTol = 0x1p-8f;  // the format's bound, relative to the largest channel

bool finite(const Color& c) { return isFinite(c); }

// A colour whose largest channel is log-uniform over [1e-30, 1e30] and whose other
// channels are that times a factor that is uniform, log-uniform down to 1e-6, or 1.
Color randomColour(Rng& rng) {
  const float m = std::pow(10.0f, -30.0f + 60.0f * rng.uniform());
  Color c;
  for (int i = 0; i < 3; ++i) {
    const float u = rng.uniform();
    c[i] = u < 0.4f ? m * rng.uniform() : u < 0.8f ? m * std::pow(10.0f, -6.0f * rng.uniform()) : m;
  }
  c[static_cast<int>(rng.nextU32() % 3)] = m;
  return c;
}

TEST(PackedPower, IsFourBytesAndMakesTheIndirectPhoton24) {
  EXPECT_EQ(sizeof(PackedPower), 4u);
  EXPECT_EQ(sizeof(IndirectPhoton), 24u);
}

TEST(PackedPower, RoundTripWithinTwoToMinusEightOfTheLargestChannel) {
  Rng rng(2024);
  double signedUnits = 0.0, worstLargest = 0.0;
  int counted = 0;
  for (int i = 0; i < 200000; ++i) {
    const Color c = randomColour(rng);
    const float m = maxComponent(c);
    ASSERT_GE(m, 1e-30f);
    const Color d = PackedPower(c).color();
    ASSERT_TRUE(finite(d)) << i;
    for (int ch = 0; ch < 3; ++ch) {
      ASSERT_LE(std::abs(d[ch] - c[ch]), kTol * m) << i << " ch " << ch << ": " << c[ch] << " -> " << d[ch];
      ASSERT_GE(d[ch], 0.0f);
    }
    // The largest channel relative to itself.
    const int big = c.r == m ? 0 : c.g == m ? 1 : 2;
    worstLargest = std::max(worstLargest, std::abs(double(d[big]) - m) / m);
    // Rounding, not truncation: the error in units of the last mantissa bit,
    // 2^(e - 8) with m in [2^(e-1), 2^e), averages ~0 (truncation: -0.5). Over
    // channels of >= 16 units, whose fractional parts are near uniform (smaller ones
    // that round to 0 only ever lose).
    int e;
    std::frexp(m, &e);
    const double unit = std::ldexp(1.0, e - 8);
    for (int ch = 0; ch < 3; ++ch) {
      if (ch == big || c[ch] < 16.0 * unit) continue;
      signedUnits += (double(d[ch]) - c[ch]) / unit;
      ++counted;
    }
  }
  EXPECT_LE(worstLargest, kTol);
  EXPECT_GT(worstLargest, 0.5 * kTol) << "suspiciously exact: is it really 8 bits?";
  // Uniform rounding errors in [-1/2, 1/2]: s.d. 0.29 / sqrt(n) ~ 1e-3; 0.02 is loose
  // and still far from truncation's -0.5 or a decoder's stray +0.5.
  EXPECT_NEAR(signedUnits / counted, 0.0, 0.02);
}

TEST(PackedPower, BlackAndGarbageAreExactZero) {
  EXPECT_EQ(PackedPower().bits, 0u);
  EXPECT_EQ(PackedPower().color(), Color(0.0f));
  EXPECT_EQ(PackedPower(Color(0.0f)).bits, 0u);
  EXPECT_EQ(PackedPower(Color(-0.0f)).bits, 0u);
  EXPECT_EQ(PackedPower(Color(0.0f)).color(), Color(0.0f));
  EXPECT_EQ(PackedPower(Color(-1.0f)).bits, 0u);
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(PackedPower(Color(inf, 1.0f, 1.0f)).bits, 0u);
  EXPECT_EQ(PackedPower(Color(1.0f, nan, 1.0f)).bits, 0u);
  EXPECT_EQ(PackedPower(Color(1.0f, 1.0f, -inf)).bits, 0u);
  // Below 2^-100 is black; just above it is not (and still within the bound).
  EXPECT_EQ(PackedPower(Color(0x1p-101f)).bits, 0u);
  EXPECT_EQ(PackedPower(Color(1e-35f, 0.0f, 1e-40f)).bits, 0u);
  const Color small = PackedPower(Color(1e-30f)).color();
  EXPECT_NEAR(small.r, 1e-30f, 1e-30f * kTol);
  // A negative channel beside positive ones is 0, the others unaffected.
  const Color mixed = PackedPower(Color(-2.0f, 1.0f, 0.5f)).color();
  EXPECT_EQ(mixed, Color(0.0f, 1.0f, 0.5f));
}

TEST(PackedPower, LargestRoundingUpTo256BumpsTheExponent) {
  for (int k = -90; k <= 120; k += 7) {
    const float two = std::ldexp(1.0f, k);
    const float x = 255.6f / 256.0f * two;  // mantissa 255.6 units of 2^(k - 8): rounds to 256
    const PackedPower p(Color(x, 0.5f * x, 0.01f * x));
    EXPECT_EQ(p.bits & 0xFFu, 128u) << k;
    EXPECT_EQ(p.bits >> 24, static_cast<uint32_t>(k + 1 + 128)) << k;
    const Color d = p.color();
    EXPECT_EQ(d.r, two) << k;  // 128 x 2^(k + 1 - 8)
    EXPECT_NEAR(d.g, 0.5f * x, kTol * x) << k;
    EXPECT_NEAR(d.b, 0.01f * x, kTol * x) << k;
    // One unit below the threshold stays at 255 in the lower exponent.
    const PackedPower q(Color(255.4f / 256.0f * two));
    EXPECT_EQ(q.bits & 0xFFu, 255u) << k;
    EXPECT_EQ(q.bits >> 24, static_cast<uint32_t>(k + 128)) << k;
  }
}

TEST(PackedPower, TinyChannelsBesideABigOneGoToZero) {
  const Color a = PackedPower(Color(1e20f, 1e-20f, 1e-30f)).color();
  ASSERT_TRUE(finite(a));
  EXPECT_NEAR(a.r, 1e20f, 1e20f * kTol);
  EXPECT_EQ(a.g, 0.0f);
  EXPECT_EQ(a.b, 0.0f);
  const Color b = PackedPower(Color(1e-3f, 2.0f, 0.0f)).color();  // 1e-3 < half a unit (2^-7)
  ASSERT_TRUE(finite(b));
  EXPECT_EQ(b.r, 0.0f);
  EXPECT_EQ(b.g, 2.0f);
  EXPECT_EQ(b.b, 0.0f);
  // Near the top of the range: saturates at 255 x 2^119, finite.
  const float huge = std::numeric_limits<float>::max();
  const Color h = PackedPower(Color(huge, 1.0f, 1e30f)).color();
  ASSERT_TRUE(finite(h));
  EXPECT_EQ(h.r, 255.0f * 0x1p119f);
  EXPECT_EQ(h.g, 0.0f);
  EXPECT_EQ(h.b, 0.0f);
  const Color big = PackedPower(Color(1e38f)).color();  // 1e38 < 2^127: not saturated
  EXPECT_NEAR(big.r, 1e38f, 1e38f * kTol);
}

TEST(PackedPower, EqualChannelsStayEqual) {
  Rng rng(3);
  for (int i = 0; i < 10000; ++i) {
    const Color c = randomColour(rng);
    const Color grey = PackedPower(Color(c.r)).color();
    ASSERT_EQ(grey.r, grey.g) << c.r;
    ASSERT_EQ(grey.r, grey.b) << c.r;
    const Color two = PackedPower(Color(c.r, c.g, c.r)).color();
    ASSERT_EQ(two.r, two.b) << c.r << " " << c.g;
  }
}

TEST(PackedPower, DecodingAStoredCodeReencodesToTheSameBits) {
  Rng rng(11);
  for (int i = 0; i < 200000; ++i) {
    const PackedPower p(randomColour(rng));
    ASSERT_NE(p.bits, 0u);
    const PackedPower again(p.color());
    ASSERT_EQ(again, p) << std::hex << p.bits << " -> " << again.bits;
  }
  // The special codes too: the bumped exponent, saturation, black.
  for (const Color& c : {Color(255.6f / 256.0f), Color(std::numeric_limits<float>::max()), Color(0.0f),
                         Color(1e-30f, 0.0f, 0.0f)}) {
    const PackedPower p(c);
    EXPECT_EQ(PackedPower(p.color()), p) << c.r;
  }
}

}  // namespace
}  // namespace penumbra
