// Load-time validation of textures: an image file is decoded whole once, so a
// truncated or corrupt one fails at load with the scene's JSON path, before any
// photon or pixel work (the texture cache would only notice mid-render).
#pragma once
#include <cstdint>
#include <string>

namespace penumbra {

// "" when `path` is an image OpenImageIO can decode completely, every channel
// value finite; otherwise the problem, one line, for JsonNode::fail.
std::string textureFileProblem(const std::string& path);
// The largest texture: by pixels (decoding every one at load must stay seconds) and
// by file size (judged before the file is opened).
inline constexpr uint64_t kMaxTexturePixels = 16384ull * 16384ull;
// A texture's widest row: a 2:1 lat-long earth of 21600x10800 fits, a 33554432x1 strip
// (whose one row OpenEXR would allocate whole) does not.
inline constexpr int kMaxTextureSide = 65536;
inline constexpr uint64_t kMaxTextureFileBytes = 1ull << 30;

// "" when `spec` is "builtin:NAME" or "builtin:NAME@WIDTH" with a known NAME and
// WIDTH in [2, 16384] (what builtinTexturePath accepts), else the problem. Does
// not generate the texture: the pipeline does that, once, from the cache.
std::string builtinTextureProblem(const std::string& spec);

}  // namespace penumbra
