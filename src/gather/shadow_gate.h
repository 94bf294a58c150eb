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
  bool glassBlocks = false;   // physical model: behind glass counts as shadow, not Mixed
  bool operator==(const GateParams& o) const {
    return k == o.k && maxRadius == o.maxRadius && minNormalCos == o.minNormalCos && minVoters == o.minVoters &&
           glassBlocks == o.glassBlocks;
  }
};

// Mixed means "no confident answer": the tracer casts a real shadow ray.
enum class GateVerdict : uint8_t { Lit, Shadowed, Mixed };

// Tallies the photons photons[indices[0..count)] against the shading normal n
// (unit, facing the viewer). Stops decoding normals as soon as both kinds voted,
// since nothing after that can change a Mixed verdict.
GateVerdict voteGate(const ShadowPhoton* photons, const uint32_t* indices, size_t count,
                     const Vec3& n, const GateParams& params);

}  // namespace penumbra
