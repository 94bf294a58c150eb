// glTF samplers read into TextureSampling: the spec's wrap enums one for one; the
// magnification filter picks nearest or bilinear texels, the minification filter
// whether and how MIP levels are used.
#include "io/gltf_samplers.h"

#include "io/gltf_checks.h"

namespace penumbra {

namespace {

[[noreturn]] void samplerFail(const std::string& path, int sampler, const char* key, const std::string& problem) {
  gltfFail(path, "samplers[" + std::to_string(sampler) + "]." + key, problem);
}

TextureWrap wrap(int value, const char* key, const std::string& path, int sampler) {
  switch (value) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::Repeat;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::MirroredRepeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::ClampToEdge;
    default: break;
  }
  samplerFail(path, sampler, key,
              std::to_string(value) + " is not 10497 (REPEAT), 33648 (MIRRORED_REPEAT) or 33071 (CLAMP_TO_EDGE)");
}

}  // namespace

std::optional<TextureSampling> gltfTextureSampling(const tinygltf::Model& model, int index, const std::string& path) {
  if (index < 0 || size_t(index) >= model.textures.size()) return std::nullopt;
  TextureSampling how;
  const int s = model.textures[size_t(index)].sampler;
  if (s < 0) return how;
  if (size_t(s) >= model.samplers.size()) {
    gltfFail(path, "textures[" + std::to_string(index) + "].sampler", std::to_string(s) + " does not exist");
  }
  const tinygltf::Sampler& g = model.samplers[size_t(s)];
  how.wrapS = wrap(g.wrapS, "wrapS", path, s);
  how.wrapT = wrap(g.wrapT, "wrapT", path, s);
  switch (g.magFilter) {
    case -1: break;  // absent: the texture system's choice
    case TINYGLTF_TEXTURE_FILTER_NEAREST: how.texels = TexelFilter::Nearest; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR: how.texels = TexelFilter::Linear; break;
    default: samplerFail(path, s, "magFilter", std::to_string(g.magFilter) + " is not 9728 (NEAREST) or 9729 (LINEAR)");
  }
  switch (g.minFilter) {
    case -1:  // absent, or filtered across levels: the texture system's MIP filter
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST:
    case TINYGLTF_TEXTURE_FILTER_LINEAR: how.mips = MipFilter::None; break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: how.mips = MipFilter::OneLevel; break;
    default:
      samplerFail(path, s, "minFilter", std::to_string(g.minFilter) + " is not 9728, 9729 or 9984 to 9987");
  }
  return how;
}

}  // namespace penumbra
