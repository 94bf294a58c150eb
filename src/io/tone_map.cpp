// Tone curves; +Inf (the writer clamps it, never NaN) maps to white on every curve.
#include "io/tone_map.h"
#include "core/error.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

ToneMap parseToneMap(const std::string& name) {
  if (name == "clamp") return ToneMap::Clamp;
  if (name == "reinhard") return ToneMap::Reinhard;
  if (name == "filmic") return ToneMap::Filmic;
  throw InputError("--tonemap: unknown curve '" + name + "' (use clamp, reinhard or filmic)");
}

const char* toneMapName(ToneMap tone) {
  switch (tone) {
    case ToneMap::Reinhard: return "reinhard";
    case ToneMap::Filmic: return "filmic";
    default: return "clamp";
  }
}

float displayValue(float linear, const DisplayOptions& o) {
  if (!(linear > 0.0f)) return 0.0f;
  const float x = o.exposure == 0.0f ? linear : linear * std::exp2(o.exposure);
  if (std::isinf(x)) return 1.0f;
  switch (o.tone) {
    case ToneMap::Reinhard: return x / (1.0f + x);
    case ToneMap::Filmic: return std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
    default: return std::min(x, 1.0f);
  }
}

}  // namespace penumbra
