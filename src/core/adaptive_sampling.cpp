// The per-pixel sample counts of adaptive pixel sampling, in pixel order.
#include "core/adaptive_sampling.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

bool adaptiveSampling(const RenderSettings& render) {
  return render.adaptive.value_or(false);
}

AdaptiveRule adaptiveRule(const RenderSettings& render, int spp) {
  return {render.adaptiveThreshold, spp, render.adaptiveMaxSpp};
}

uint64_t adaptiveExtras(const Image& standardError, double imageRmse, const AdaptiveRule& rule,
                        std::vector<uint16_t>& extra) {
  extra.assign(standardError.pixels.size(), 0);
  const double unit = rule.threshold * imageRmse;
  const int top = std::min(rule.maxSpp, kAdaptiveSppLimit);
  if (!(unit > 0.0) || top <= rule.spp) return 0;
  uint64_t total = 0;
  for (size_t i = 0; i < extra.size(); ++i) {
    const Color& se = standardError.pixels[i];
    const double e = std::sqrt((double(se.r) * se.r + double(se.g) * se.g + double(se.b) * se.b) / 3.0);
    if (!(e > unit)) continue;
    const double want = std::ceil(rule.spp * std::min(e / unit, double(top)));
    extra[i] = static_cast<uint16_t>(std::min<double>(want, top) - rule.spp);
    total += extra[i];
  }
  return total;
}

}  // namespace penumbra
