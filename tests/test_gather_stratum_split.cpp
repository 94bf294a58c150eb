// A stratum's split line against the shadow edge its photons sample: straight edges at
// every angle are never decided against the truth away from the edge and mostly
// decided beyond it, interleaved photons leave their band to rays, and a thin shadow
// (lit on both sides) decides nothing in its middle.
#include "gather/stratum_split.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

constexpr float kCell = 1.0f;          // the cell a shading point is in: [-0.5, 0.5]^2
constexpr float kWindow = 3.0f * kCell;  // photons come from the 3 x 3 cells around it
constexpr float kMargin = kSplitMarginOfWidth * kWindow;

struct Photons {
  std::vector<Vec3> lit, shadowed;
};

// n photons uniform over the window in the plane z = 0, lit where `litAt` says so.
template <class LitAt>
Photons scatter(int n, Rng& rng, LitAt&& litAt) {
  Photons out;
  for (int i = 0; i < n; ++i) {
    const Vec3 p((rng.uniform() - 0.5f) * kWindow, (rng.uniform() - 0.5f) * kWindow, 0.0f);
    (litAt(p) ? out.lit : out.shadowed).push_back(p);
  }
  return out;
}

std::optional<StratumSplit> fit(const Photons& ph) {
  return fitStratumSplit(ph.lit.data(), ph.lit.size(), ph.shadowed.data(), ph.shadowed.size(), kMargin);
}

TEST(StratumSplit, NoneWithoutBothKinds) {
  Rng rng(1);
  const Photons allLit = scatter(20, rng, [](const Vec3&) { return true; });
  EXPECT_FALSE(fit(allLit).has_value());
}

TEST(StratumSplit, StraightEdgesAtEveryAngleAreNeverContradictedAwayFromTheEdge) {
  // 20 photons over the window: what one stratum of a light gets around a cell.
  // Edges through the cell at every angle and offset; points of the central cell
  // against the truth. Wrong verdicts stay within a photon spacing of the edge (the
  // edge can run past the outermost photons between them) and are rare, and most
  // points a spacing beyond it are decided.
  Rng rng(7);
  const float spacing = kWindow / std::sqrt(20.0f);
  int decidedFar = 0, far = 0, wrongNear = 0, points = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const float angle = rng.uniform() * 2.0f * kPi;
    const Vec3 normal(std::cos(angle), std::sin(angle), 0.0f);
    const float offset = (rng.uniform() - 0.5f) * kCell;
    auto litAt = [&](const Vec3& p) { return glm::dot(p, normal) > offset; };
    const Photons ph = scatter(20, rng, litAt);
    const std::optional<StratumSplit> s = fit(ph);
    if (!s) continue;
    for (int i = 0; i < 64; ++i, ++points) {
      const Vec3 p((rng.uniform() - 0.5f) * kCell, (rng.uniform() - 0.5f) * kCell, 0.0f);
      const float distance = std::abs(glm::dot(p, normal) - offset);
      const GateVerdict v = s->at(p);
      const bool wrong = (v == GateVerdict::Lit && !litAt(p)) || (v == GateVerdict::Shadowed && litAt(p));
      if (wrong) {
        EXPECT_LT(distance, spacing) << "trial " << trial << ": wrong at " << distance << " from the edge";
        ++wrongNear;
      }
      if (distance > spacing) {
        ++far;
        if (v != GateVerdict::Mixed) ++decidedFar;
      }
    }
  }
  EXPECT_GT(decidedFar, 0.8 * far) << decidedFar << " of " << far;
  EXPECT_LT(wrongNear, 0.02 * points) << wrongNear << " of " << points;
}

TEST(StratumSplit, InterleavedPhotonsLeaveTheirBandToRays) {
  // A stratum's own penumbra: within 0.2 of x = 0 either kind, beyond it one.
  Rng rng(3);
  const Photons ph = scatter(400, rng, [&](const Vec3& p) {
    return std::abs(p.x) < 0.2f ? rng.uniform() < 0.5f : p.x > 0.0f;
  });
  const std::optional<StratumSplit> s = fit(ph);
  ASSERT_TRUE(s.has_value());
  for (float y : {-0.4f, 0.0f, 0.4f}) {
    EXPECT_EQ(s->at(Vec3(0.1f, y, 0.0f)), GateVerdict::Mixed);
    EXPECT_EQ(s->at(Vec3(-0.1f, y, 0.0f)), GateVerdict::Mixed);
    EXPECT_EQ(s->at(Vec3(0.45f, y, 0.0f)), GateVerdict::Lit);
    EXPECT_EQ(s->at(Vec3(-0.45f, y, 0.0f)), GateVerdict::Shadowed);
  }
}

TEST(StratumSplit, AThinShadowDecidesNothingInItsMiddle) {
  // A shadow 0.6 wide across the window, lit ground on both sides: no line separates
  // them, and no point more than a photon spacing inside the shadow is called lit.
  const int n = 200;
  const float spacing = kWindow / std::sqrt(static_cast<float>(n));
  for (uint64_t seed = 1; seed <= 50; ++seed) {
    Rng rng(seed);
    const Photons ph = scatter(n, rng, [](const Vec3& p) { return std::abs(p.x) > 0.3f; });
    const std::optional<StratumSplit> s = fit(ph);
    ASSERT_TRUE(s.has_value());
    for (float x = -(0.3f - spacing); x <= 0.3f - spacing; x += 0.01f)
      for (float y = -0.45f; y <= 0.45f; y += 0.05f)
        EXPECT_NE(s->at(Vec3(x, y, 0.0f)), GateVerdict::Lit) << "seed " << seed << " at " << x << ", " << y;
  }
}

}  // namespace
}  // namespace penumbra
