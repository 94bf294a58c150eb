// Octahedral normal encoding for the photon records.
#include "core/photon.h"

namespace penumbra {
namespace {
Vec2 signNotZero(Vec2 v) { return {v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f}; }
uint32_t quantise(float x) {  // [-1,1] -> [0, 65535]
  return static_cast<uint32_t>(std::lround((std::clamp(x, -1.0f, 1.0f) * 0.5f + 0.5f) * 65535.0f));
}
}  // namespace

uint32_t encodeOctahedral(const Vec3& n) {
  Vec2 p = Vec2(n.x, n.y) * (1.0f / (std::abs(n.x) + std::abs(n.y) + std::abs(n.z)));
  if (n.z < 0.0f) p = (1.0f - glm::abs(Vec2(p.y, p.x))) * signNotZero(p);
  return quantise(p.x) | (quantise(p.y) << 16);
}

Vec3 decodeOctahedral(uint32_t code) {
  Vec2 p(static_cast<float>(code & 0xFFFFu) / 65535.0f * 2.0f - 1.0f,
         static_cast<float>(code >> 16) / 65535.0f * 2.0f - 1.0f);
  Vec3 n(p.x, p.y, 1.0f - std::abs(p.x) - std::abs(p.y));
  if (n.z < 0.0f) {
    Vec2 xy = (1.0f - glm::abs(Vec2(n.y, n.x))) * signNotZero(p);
    n.x = xy.x;
    n.y = xy.y;
  }
  return glm::normalize(n);
}

}  // namespace penumbra
