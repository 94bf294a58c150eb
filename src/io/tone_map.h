// The display transform of 8-bit outputs: an exposure in stops, then a tone
// curve (clamp, Reinhard, a filmic ACES fit or Khronos PBR Neutral) before the sRGB
// encoding, and which curve a scene gets when none is asked. EXR outputs stay linear.
#pragma once
#include "core/math.h"
#include <string>

namespace penumbra {

struct Scene;

enum class ToneMap { Clamp, Reinhard, Filmic, Neutral };

struct DisplayOptions {
  float exposure = 0.0f;  // EV: values are multiplied by 2^exposure
  ToneMap tone = ToneMap::Clamp;
  bool toneAsked = false;  // the user chose `tone` (--tonemap): sceneDisplay keeps it
};

// "clamp", "reinhard", "filmic", "neutral"; throws InputError otherwise.
ToneMap parseToneMap(const std::string& name);
const char* toneMapName(ToneMap tone);

// The display value in [0, 1] of one linear channel value (before sRGB encoding).
// Clamp with exposure 0 is the identity on [0, 1], so default PNGs keep their bytes.
//   reinhard: x / (1 + x)
//   filmic:   x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14)   (Narkowicz's ACES fit)
//   neutral:  a grey's value under displayColor
float displayValue(float linear, const DisplayOptions& options);

// The display colour in [0, 1]^3 of one linear pixel: displayValue per channel, except
// that "neutral" is Khronos PBR Neutral, which maps the colour as a whole (it keeps
// hues, and desaturates only the brightest values towards white):
//   x = min(r, g, b); subtract x - 6.25 x^2 (x < 0.08) or 0.04; p = max channel;
//   above p = 0.76, scale to p' = 1 - 0.24^2 / (p - 0.52) and mix towards p' grey by
//   1 - 1 / (0.15 (p - p') + 1).
Color displayColor(const Color& linear, const DisplayOptions& options);

// The display transform a PNG of `scene` is written with: `asked`, and when no curve
// was asked, Khronos PBR Neutral for a glTF or OBJ model's scene (as glTF viewers show
// models), clamp (the bytes of every JSON scene so far) otherwise.
DisplayOptions sceneDisplay(DisplayOptions asked, const Scene& scene);

}  // namespace penumbra
