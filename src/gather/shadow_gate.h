// The shadow gate's vote: given the k nearest shadow-map photons of one light,
// decide lit / shadowed / ask-the-tracer. Pure function of the gathered photons.
#pragma once
#include "core/math.h"
#include "core/photon.h"
#include <cstddef>
#include <cstdint>

namespace penumbra {

struct GateParams {
  int k = 50;                 // photons gathered per light
  float maxRadius = 0.0f;     // 0 = unlimited
  float minNormalCos = 0.5f;  // a photon votes only if its normal . n > this
  int minVoters = 8;          // fewer voters than this: not enough evidence -> Mixed
  // The same for one stratum of an area light, asked only where the whole light's
  // vote is mixed: a stratum gets a sixteenth of the light's photons, and two that
  // agree, with none against, already separate its lit side from its shadowed one.
  int minStratumVoters = 2;
  bool glassBlocks = false;   // physical model: behind glass counts as shadow, not Mixed
  bool operator==(const GateParams& o) const {
    return k == o.k && maxRadius == o.maxRadius && minNormalCos == o.minNormalCos && minVoters == o.minVoters &&
           minStratumVoters == o.minStratumVoters && glassBlocks == o.glassBlocks;
  }
  // The parameters a stratum's vote runs with.
  GateParams forStratum() const {
    GateParams p = *this;
    p.minVoters = minStratumVoters < minVoters ? minStratumVoters : minVoters;
    return p;
  }
};

// Mixed means "no confident answer": the tracer casts a real shadow ray.
enum class GateVerdict : uint8_t { Lit, Shadowed, Mixed };

// The photons that voted on one light at one place: arrived directly, behind
// something opaque, behind glass.
struct GateCounts {
  uint32_t direct = 0, opaque = 0, glass = 0;
};

// The voting rule, once for exact gathers and the precomputed cells: lit or
// shadowed only when the voters agree, are at least minVoters, and (unless glass
// blocks, as in the physical model) none saw the light through glass, whose tint
// only a shadow ray can measure.
inline GateVerdict verdictOf(const GateCounts& c, const GateParams& params) {
  if (c.glass > 0 && !params.glassBlocks) return GateVerdict::Mixed;
  const uint32_t shadowed = c.opaque + (params.glassBlocks ? c.glass : 0);
  if (c.direct > 0 && shadowed > 0) return GateVerdict::Mixed;
  if (c.direct + shadowed < static_cast<uint32_t>(params.minVoters > 1 ? params.minVoters : 1)) {
    return GateVerdict::Mixed;
  }
  return c.direct > 0 ? GateVerdict::Lit : GateVerdict::Shadowed;
}

// Tallies the photons photons[indices[0..count)] against the shading normal n
// (unit, facing the viewer). Stops decoding normals as soon as both kinds voted,
// since nothing after that can change a Mixed verdict; then verdictOf decides.
// backSide: the point was seen from behind its surface's winding (only photons that
// met it from behind vote, ShadowPhoton::backSide).
GateVerdict voteGate(const ShadowPhoton* photons, const uint32_t* indices, size_t count,
                     const Vec3& n, const GateParams& params, bool backSide = false);

}  // namespace penumbra
