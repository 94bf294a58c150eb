// Tone curves; +Inf (the writer clamps it, never NaN) maps to white on every curve.
// Which curve a scene's PNG gets when none is asked.
#include "io/tone_map.h"
#include "core/error.h"
#include "core/scene.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

ToneMap parseToneMap(const std::string& name) {
  if (name == "clamp") return ToneMap::Clamp;
  if (name == "reinhard") return ToneMap::Reinhard;
  if (name == "filmic") return ToneMap::Filmic;
  if (name == "neutral") return ToneMap::Neutral;
  throw InputError("--tonemap: unknown curve '" + name + "' (use clamp, reinhard, filmic or neutral)");
}

const char* toneMapName(ToneMap tone) {
  switch (tone) {
    case ToneMap::Reinhard: return "reinhard";
    case ToneMap::Filmic: return "filmic";
    case ToneMap::Neutral: return "neutral";
    default: return "clamp";
  }
}

namespace {

// Khronos PBR Neutral (the glTF Sample Viewer's reference), on exposed values >= 0.
Color pbrNeutral(Color c) {
  constexpr float kStart = 0.8f - 0.04f, kDesaturation = 0.15f;
  const float x = std::min(c.r, std::min(c.g, c.b));
  c -= x < 0.08f ? x - 6.25f * x * x : 0.04f;
  const float peak = std::max(c.r, std::max(c.g, c.b));
  if (peak < kStart) return c;
  constexpr float d = 1.0f - kStart;
  const float newPeak = 1.0f - d * d / (peak + d - kStart);
  c *= newPeak / peak;
  const float g = 1.0f - 1.0f / (kDesaturation * (peak - newPeak) + 1.0f);
  return glm::mix(c, Color(newPeak), g);
}

}  // namespace

float displayValue(float linear, const DisplayOptions& o) {
  if (!(linear > 0.0f)) return 0.0f;
  const float x = o.exposure == 0.0f ? linear : linear * std::exp2(o.exposure);
  if (std::isinf(x)) return 1.0f;
  switch (o.tone) {
    case ToneMap::Reinhard: return x / (1.0f + x);
    case ToneMap::Filmic: return std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
    case ToneMap::Neutral: return std::min(pbrNeutral(Color(x)).r, 1.0f);  // a grey's
    default: return std::min(x, 1.0f);
  }
}

Color displayColor(const Color& linear, const DisplayOptions& o) {
  if (o.tone != ToneMap::Neutral) {
    return {displayValue(linear.r, o), displayValue(linear.g, o), displayValue(linear.b, o)};
  }
  Color x;
  for (int c = 0; c < 3; ++c) {
    // Negative and NaN to 0; +Inf to a huge finite value, which the curve sends to white.
    const float v = linear[c] > 0.0f ? (o.exposure == 0.0f ? linear[c] : linear[c] * std::exp2(o.exposure)) : 0.0f;
    x[c] = std::min(v, 1e30f);
  }
  return glm::clamp(pbrNeutral(x), Color(0.0f), Color(1.0f));
}

DisplayOptions sceneDisplay(DisplayOptions asked, const Scene& scene) {
  if (!asked.toneAsked && !scene.load.modelFile.empty()) asked.tone = ToneMap::Neutral;
  return asked;
}

}  // namespace penumbra
