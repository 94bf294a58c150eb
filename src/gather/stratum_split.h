// Where one light stratum's photons around a lookup cell disagree: the line between
// its lit and its shadowed photons, so that a shading point well on one side of it
// takes that side's verdict and only points near the line cast shadow rays.
#pragma once
#include "core/math.h"
#include "gather/shadow_gate.h"
#include <algorithm>
#include <cstddef>
#include <optional>

namespace penumbra {

// How far past the outermost photon of the other kind a point must lie for a split
// to decide it, as a share of the width the photons were gathered over (an eighth
// of a cell over three cells). The edge lies between the two kinds' outermost
// photons but can curve past them between photons: a wider margin casts more rays,
// a narrower one decides more points near a curved edge wrongly (docs/photon-maps.md).
constexpr float kSplitMarginOfWidth = 1.0f / 24.0f;

struct StratumSplit {
  Vec3 dir{0.0f};              // unit, from the shadowed photons' centroid to the lit ones'
  float shadowedBelow = 0.0f;  // dot(p, dir) below this: shadowed
  float litAbove = 0.0f;       // above this: lit; in between, a ray
  GateVerdict at(const Vec3& p) const {
    const float t = glm::dot(p, dir);
    return t > litAbove ? GateVerdict::Lit : t < shadowedBelow ? GateVerdict::Shadowed : GateVerdict::Mixed;
  }
};

// The split of lit[0..nLit) and shadowed[0..nShadowed) photon positions: the direction
// between their centroids, and along it the band from the first lit photon to the last
// shadowed one (whichever comes first), widened by `margin` world units each way.
// Photons in a stratum's own penumbra interleave, so the band covers them; a shadow
// whose two kinds share a centroid (a thin shadow in the middle of lit ground) leaves
// a band as wide as the photons and decides nothing. None without both kinds.
inline std::optional<StratumSplit> fitStratumSplit(const Vec3* lit, size_t nLit, const Vec3* shadowed,
                                                   size_t nShadowed, float margin) {
  if (nLit == 0 || nShadowed == 0) return std::nullopt;
  auto centroid = [](const Vec3* p, size_t n) {
    Vec3 sum(0.0f);
    for (size_t i = 0; i < n; ++i) sum += p[i];
    return sum / static_cast<float>(n);
  };
  const Vec3 between = centroid(lit, nLit) - centroid(shadowed, nShadowed);
  const float length = glm::length(between);
  if (!(length > 0.0f)) return std::nullopt;
  StratumSplit s;
  s.dir = between / length;
  float firstLit = glm::dot(lit[0], s.dir), lastShadowed = glm::dot(shadowed[0], s.dir);
  for (size_t i = 1; i < nLit; ++i) firstLit = std::min(firstLit, glm::dot(lit[i], s.dir));
  for (size_t i = 1; i < nShadowed; ++i) lastShadowed = std::max(lastShadowed, glm::dot(shadowed[i], s.dir));
  // Separated kinds leave a gap with the edge inside it; interleaved ones, a band
  // where either can be found. Both are the stretch between the two extremes.
  s.shadowedBelow = std::min(firstLit, lastShadowed) - margin;
  s.litAbove = std::max(firstLit, lastShadowed) + margin;
  return s;
}

}  // namespace penumbra
