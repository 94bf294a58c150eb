// The part file's keys: key lists keep the merged header's order (a PNG's text chunks
// are written in order), hex floats keep the tile's sums exact.
#include "plan/frame_part.h"
#include "plan/frame_tiles.h"
#include "plan/batch/job_state.h"
#include "io/image_part.h"
#include <fmt/format.h>
#include <filesystem>

namespace penumbra {
namespace {

std::string keyList(const ImageMetadata& m) {
  std::string out;
  for (const auto& kv : m) out += (out.empty() ? "" : ",") + kv.first;
  return out;
}

const char* contentName(ImageContent c) {
  return c == ImageContent::Depth ? "depth" : c == ImageContent::Normal ? "normal" : "radiance";
}

}  // namespace

Image emitterLayer(const EmitterMask& mask, int width, int height) {
  Image out(width, height);
  for (size_t i = 0; i < mask.size(); ++i) out.pixels[i] = Color(float(mask[i]));
  return out;
}

EmitterMask emitterMaskOf(const Image& layer) {
  EmitterMask mask(layer.pixels.size());
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = layer.pixels[i].r > 0.5f ? 1 : 0;
  return mask;
}

std::string tilePartPath(const std::string& output, int index, int count) {
  std::filesystem::path p(output);
  p.replace_extension(fmt::format(".tile{}of{}.exr", index, count));
  return p.string();
}

std::string renderFrameStamp(const std::string& scenePath, const std::vector<std::string>& overrides,
                             const std::vector<std::string>& options, const std::string& view) {
  return jobStamp(JobDefinition{scenePath, overrides, {{view, ""}}, options});
}

void writeFramePart(const std::string& path, const RenderResult& result, const PixelBounds& bounds,
                    const std::string& frameStamp, const ImageMetadata& exr, const ImageMetadata& png,
                    const ImageMetadata& own) {
  const Image& image = result.image;
  const TileError& e = result.tileError;
  ImageMetadata m = exr;
  m.emplace_back(kPartJob, frameStamp);
  m.emplace_back(kPartFrame, fmt::format("{}x{}", image.width, image.height));
  m.emplace_back(kPartBounds, boundsText(bounds));
  m.emplace_back(kPartContent, contentName(image.content));
  m.emplace_back(kPartError, fmt::format("{} {} {}", static_cast<int>(e.source), e.count,
                                         result.stats.error.sharedMaps ? 1 : 0));
  std::vector<std::pair<std::string, const Image*>> layers;
  if (e.source == ErrorSource::Samples) layers.push_back({"se", &e.standardError});
  if (e.source == ErrorSource::Passes) {
    layers.push_back({"even", &e.even});
    layers.push_back({"odd", &e.odd});
    const PassCheckpoint& c = e.checkpoint;
    m.emplace_back(kPartBias, fmt::format("{} {}", c.passes, c.half));
    if (c.half > 0) {
      for (const auto& [name, layer] : {std::pair{"bias_first_even", &c.firstEven}, {"bias_first_odd", &c.firstOdd},
                                        {"bias_even", &c.even}, {"bias_odd", &c.odd}})
        layers.push_back({name, layer});
    }
    for (int g = 0; g < e.smoothing.filled(); ++g) layers.push_back({kSmoothingLayers[g], &e.smoothing.groups[g]});
  }
  Image emitters;
  if (!e.emitters.empty()) {
    emitters = emitterLayer(e.emitters, image.width, image.height);
    layers.push_back({kEmitterLayer, &emitters});
  }
  if (e.source == ErrorSource::Probes) m.emplace_back(kPartProbes, fmt::format("{:a} {}", e.probeSquareSum, e.probed));
  m.emplace_back(kPartExrKeys, keyList(exr));
  m.emplace_back(kPartPngKeys, keyList(png));
  for (const auto& kv : own) m.push_back(kv);
  writeImagePart(path, image, bounds, layers, m);
}

}  // namespace penumbra
