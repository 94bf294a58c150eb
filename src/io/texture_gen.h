// Procedural equirectangular textures, so scenes and tests need no image files,
// and the "builtin:" texture paths that cache them on disk.
#pragma once
#include "core/image.h"
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace penumbra {

// Names makeTexture accepts, in the order error messages list them.
const std::vector<std::string>& builtinTextureNames();

// A width x height linear-RGB lat-long texture (2:1 is the intended aspect).
// Pixel (x, y) samples u = (x + 0.5) / width, v = (y + 0.5) / height, where
// u = longitude / 2pi left to right and v = 0 is the north pole (top row); the
// sphere direction is (sin(pi v) cos(2pi u), cos(pi v), sin(pi v) sin(2pi u)).
// Noise is sampled on that direction, so every texture is seamless across
// u = 0/1 and at the poles.
//   "checker"   8 x 4 cells; the cell containing (u, v) = (0, 0) and every cell
//               an even number of steps from it is kCheckerLight, the others
//               kCheckerDark.
//   "grid"      lines every 15 degrees on dark blue, a bright yellow meridian at u = 0.
//   "planet"    a banded gas giant with turbulent belts and a great storm oval.
//   "earthlike" fbm continents and oceans with ice caps.
// `seed` varies the noise of "planet" and "earthlike"; the same seed gives the
// same pixels. Throws InputError for an unknown name or a size outside [1, 16384].
Image makeTexture(const std::string& name, int width, int height, uint64_t seed = 1);

inline constexpr float kCheckerLight[3] = {0.80f, 0.80f, 0.80f};
inline constexpr float kCheckerDark[3] = {0.60f, 0.05f, 0.03f};

// Resolves "builtin:NAME" or "builtin:NAME@WIDTH" (height = WIDTH / 2, default
// width 2048, seed 1) to an absolute .exr path in the cache directory
// ($XDG_CACHE_HOME/penumbra/textures, else ~/.cache/penumbra/textures, else
// /tmp/penumbra-textures-<uid>),
// generating the file on first use. The file name carries name, width and a
// content version, so a changed generator never reuses stale files. Concurrent
// processes may both generate; writeImage's rename makes the last one win whole.
// Throws InputError for a malformed spec or an unwritable cache.
std::string builtinTexturePath(const std::string& spec);

// That cache directory (not created): glTF's embedded images are written there too.
std::filesystem::path textureCacheDirectory();

}  // namespace penumbra
