// Alpha masks decoded at load through the image module: the one channel that cuts out,
// as bytes (OpenImageIO's float-to-byte conversion rounds and clamps to 0..255), so the
// geometry layer reads plain memory and never an image library.
#include "io/alpha_mask_reader.h"
#include "io/load_cache.h"

#include "io/json_reader.h"
#include "io/texture_check.h"

#include "core/image_codec.h"

namespace penumbra {

namespace {

// The channel holding alpha: the one the file names, else the last of a grey+alpha
// or RGBA image; -1 when it has none.
int alphaChannel(const ImageInfo& spec) {
  if (spec.alphaChannel >= 0 && spec.alphaChannel < spec.nchannels) return spec.alphaChannel;
  if (spec.nchannels == 2 || spec.nchannels == 4) return spec.nchannels - 1;
  return -1;
}

}  // namespace

int addAlphaMask(const JsonNode& where, const std::string& path, Scene& scene, bool greyIsAlpha,
                 const TextureSampling& sampling) {
  for (size_t i = 0; i < scene.alphaMasks.size(); ++i) {
    if (scene.alphaMasks[i].source == path && scene.alphaMasks[i].sampling == sampling) return static_cast<int>(i);
  }
  // A texture already in the scene was decoded whole when it joined (texture_check);
  // any other file is judged the same way first.
  bool checked = false;
  for (const Texture& t : scene.textures) checked = checked || t.path == path;
  if (!checked) {
    const std::string problem = textureProblemFor(where.context(), path);
    if (!problem.empty()) where.fail(problem);
    scene.inputs.push_back(path);
  }
  std::string error;
  auto in = imageCodec().open(path, error);
  if (!in) where.fail("cannot read alpha of " + path + ": " + error);
  const ImageInfo spec = in->info();
  int channel = alphaChannel(spec);
  if (channel < 0 && !greyIsAlpha) return -1;  // no alpha: every texel is opaque
  if (channel < 0) channel = 0;
  AlphaMask mask;
  mask.source = path;
  mask.sampling = sampling;
  mask.width = spec.width;
  mask.height = spec.height;
  mask.alpha.resize(size_t(spec.width) * size_t(spec.height));
  if (!in->readChannelBytes(channel, mask.alpha.data())) {
    where.fail("cannot read alpha of " + path + ": " + in->error());
  }
  scene.alphaMasks.push_back(std::move(mask));
  return static_cast<int>(scene.alphaMasks.size()) - 1;
}

}  // namespace penumbra
