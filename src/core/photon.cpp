// Octahedral normal encoding and the shared-exponent power of the photon records.
#include "core/photon.h"

namespace penumbra {
namespace {
uint32_t quantise(float x) {  // [-1,1] -> [0, 65535], to nearest
  // The value is >= 0, so adding 0.5 and truncating rounds like lround, without
  // the libm call.
  return static_cast<uint32_t>((std::clamp(x, -1.0f, 1.0f) * 0.5f + 0.5f) * 65535.0f + 0.5f);
}
}  // namespace

PackedPower::PackedPower(const Color& c) {
  if (!isFinite(c)) return;  // bits = 0: black
  // Negative power can't happen; clamp it to 0 rather than wrap the mantissa.
  const Color p = glm::max(c, Color(0.0f));
  const float m = maxComponent(p);
  if (!(m >= 0x1p-100f)) return;  // also black: keeps every stored exponent byte >= 29
  int e;
  std::frexp(m, &e);  // m = f 2^e, f in [0.5, 1): m's mantissa at 2^(e - 8) lands in [128, 256)
  uint32_t q[3];
  auto fill = [&](int exponent, uint32_t limit) {
    // 2^(8 - exponent) is exact (8 - exponent in [-119, 108]): p x scale rounds once.
    const float scale = std::ldexp(1.0f, 8 - exponent);
    for (int i = 0; i < 3; ++i)
      q[i] = std::min(limit, static_cast<uint32_t>(p[i] * scale + 0.5f));  // round to nearest
  };
  fill(e, 256u);
  // The largest rounded up to 256: one exponent up, re-rounded from the float values
  // (not halved, which would round twice); it then lands on 128.
  if (std::max(q[0], std::max(q[1], q[2])) == 256u) fill(++e, 256u);
  // Ward's exponent byte is e + 128; e = 128 (m >= 2^127) does not fit: saturate.
  if (e > 127) fill(e = 127, 255u);
  bits = q[0] | (q[1] << 8) | (q[2] << 16) | (static_cast<uint32_t>(e + 128) << 24);
}

NormalFilter::NormalFilter(const Vec3& n, float minCos) : n_(n), minCos_(minCos) {
  // A degenerate n has no code of its own: code 0 then answers as decoded, like any.
  if (isFinite(n) && std::abs(n.x) + std::abs(n.y) + std::abs(n.z) > 0.0f) ownCode_ = encodeOctahedral(n);
  ownPasses_ = cosineOf(ownCode_) > minCos_;
}

uint32_t encodeOctahedral(const Vec3& n) {
  Vec2 p = Vec2(n.x, n.y) * (1.0f / (std::abs(n.x) + std::abs(n.y) + std::abs(n.z)));
  if (n.z < 0.0f) p = (1.0f - glm::abs(Vec2(p.y, p.x))) * octahedralSigns(p);
  return quantise(p.x) | (quantise(p.y) << 16);
}

}  // namespace penumbra
