// Load-time validation of textures: an image file is decoded whole once, so a
// truncated or corrupt one fails at load with the scene's JSON path, before any
// photon or pixel work (the texture cache would only notice mid-render).
#pragma once
#include <string>

namespace penumbra {

// "" when `path` is an image OpenImageIO can decode completely, every channel
// value finite; otherwise the problem, one line, for JsonNode::fail.
std::string textureFileProblem(const std::string& path);

// "" when `spec` is "builtin:NAME" or "builtin:NAME@WIDTH" with a known NAME and
// WIDTH in [2, 16384] (what builtinTexturePath accepts), else the problem. Does
// not generate the texture: the pipeline does that, once, from the cache.
std::string builtinTextureProblem(const std::string& spec);

}  // namespace penumbra
