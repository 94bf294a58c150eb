// Voting rule of the shadow gate.
#include "gather/shadow_gate.h"

namespace penumbra {

GateVerdict voteGate(const ShadowPhoton* photons, const uint32_t* indices, size_t count,
                     const Vec3& n, const GateParams& params) {
  int direct = 0, shadow = 0;
  for (size_t i = 0; i < count; ++i) {
    const ShadowPhoton& ph = photons[indices[i]];
    // The stored normal faces where the photon arrived from; photons on the far side
    // of a thin object face away from n and must not vote on this side's visibility.
    if (glm::dot(decodeOctahedral(ph.normal), n) <= params.minNormalCos) continue;
    // Behind glass only, the light arrives tinted: only a shadow ray can say how much.
    if (ph.shadow == kShadowGlass && !params.glassBlocks) return GateVerdict::Mixed;
    if (ph.shadow != kDirect) ++shadow; else ++direct;
    if (direct > 0 && shadow > 0) return GateVerdict::Mixed;
  }
  int voters = direct + shadow;
  if (voters == 0 || voters < params.minVoters) return GateVerdict::Mixed;
  return direct > 0 ? GateVerdict::Lit : GateVerdict::Shadowed;
}

}  // namespace penumbra
