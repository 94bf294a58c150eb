// Colour helpers shared by image I/O, procedural textures, texture lookups and
// the photon pass: the sRGB transfer curve and how to tell encoded files apart.
#pragma once
#include "core/math.h"
#include <string>

namespace penumbra {

// The IEC 61966-2-1 piecewise curve, in double so that 8-bit rounding is decided
// by the standard and not by float error near the .5 boundaries.
inline double srgbEncode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}
inline double srgbDecode(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}
inline Color srgbToLinear(const Color& c) {
  return {static_cast<float>(srgbDecode(c.r)), static_cast<float>(srgbDecode(c.g)),
          static_cast<float>(srgbDecode(c.b))};
}

// Whether an image's stored values are sRGB-encoded: its colour-space tag says
// so, or it has no tag and integer pixels (what 8- and 16-bit images almost always are).
inline bool isSrgbEncoded(const std::string& colorSpace, bool integerPixels) {
  if (colorSpace.empty()) return integerPixels;
  if (colorSpace.size() != 4) return false;
  std::string lower;
  for (char ch : colorSpace) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return lower == "srgb";
}

inline float meanOf(const Color& c) { return (c.r + c.g + c.b) / 3.0f; }

}  // namespace penumbra
