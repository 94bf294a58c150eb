// The display transform of 8-bit outputs: an exposure in stops, then a tone
// curve (clamp, Reinhard, or a filmic ACES fit) before the sRGB encoding. EXR
// outputs stay linear and skip it.
#pragma once
#include <string>

namespace penumbra {

enum class ToneMap { Clamp, Reinhard, Filmic };

struct DisplayOptions {
  float exposure = 0.0f;  // EV: values are multiplied by 2^exposure
  ToneMap tone = ToneMap::Clamp;
};

// "clamp", "reinhard", "filmic"; throws InputError otherwise.
ToneMap parseToneMap(const std::string& name);
const char* toneMapName(ToneMap tone);

// The display value in [0, 1] of one linear channel value (before sRGB encoding).
// Clamp with exposure 0 is the identity on [0, 1], so default PNGs keep their bytes.
//   reinhard: x / (1 + x)
//   filmic:   x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14)   (Narkowicz's ACES fit)
float displayValue(float linear, const DisplayOptions& options);

}  // namespace penumbra
