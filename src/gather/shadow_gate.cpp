// Voting rule of the shadow gate.
#include "gather/shadow_gate.h"

namespace penumbra {

GateVerdict voteGate(const ShadowPhoton* photons, const uint32_t* indices, size_t count,
                     const Vec3& n, const GateParams& params, bool backSide) {
  GateCounts c;
  const NormalFilter filter(n, params.minNormalCos);
  for (size_t i = 0; i < count; ++i) {
    const ShadowPhoton& ph = photons[indices[i]];
    // The stored normal faces where the photon arrived from; photons on the far side
    // of a thin object face away from n and must not vote on this side's visibility.
    // So must photons that met the surface from the other side of its winding than
    // the point was seen from: a thin box's exit hits behind its front face.
    if (ph.backSide != backSide || !filter.passes(ph.normal)) continue;
    if (ph.shadow == kDirect) ++c.direct;
    else if (ph.shadow == kShadowGlass) ++c.glass;
    else ++c.opaque;
    // Early exits where verdictOf can only say Mixed, whatever the rest vote.
    if (c.glass > 0 && !params.glassBlocks) return GateVerdict::Mixed;
    if (c.direct > 0 && c.opaque + c.glass > 0) return GateVerdict::Mixed;
  }
  return verdictOf(c, params);
}

}  // namespace penumbra
