// Part files through the image module: the data window carries the tile's place in
// the frame, so a part needs no position of its own and any EXR viewer shows it in place.
#include "io/image_part.h"
#include "core/error.h"
#include "core/image_codec.h"
#include "io/image_encode.h"
#include <algorithm>

namespace penumbra {
namespace {

[[noreturn]] void partFailed(const std::string& path, const std::string& reason) {
  std::string line = reason;
  std::replace(line.begin(), line.end(), '\n', ' ');
  while (!line.empty() && line.back() == ' ') line.pop_back();
  throw InputError(path + ": " + line);
}

}  // namespace

std::string PartHeader::attribute(const std::string& key) const {
  for (const auto& [k, v] : attributes)
    if (k == key) return v;
  return "";
}

void writeImagePart(const std::string& path, const Image& image, const PixelBounds& bounds,
                    const std::vector<std::pair<std::string, const Image*>>& layers, const ImageMetadata& metadata) {
  checkImageOutputPath(path);
  const std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  if (ext != ".exr" && ext != ".EXR") partFailed(path, "a part of a frame is written as .exr (float)");
  std::vector<std::string> names = {"R", "G", "B"};
  if (!image.coverage.empty()) names.push_back("A");
  for (const auto& [name, layer] : layers)
    for (const char* c : {"R", "G", "B"}) names.push_back(name + "." + c);
  const int n = static_cast<int>(names.size());
  EncodeSpec spec;
  spec.width = bounds.width();
  spec.height = bounds.height();
  spec.nchannels = n;
  spec.x = bounds.x0;
  spec.y = bounds.y0;
  spec.fullWidth = image.width;
  spec.fullHeight = image.height;
  spec.fileType = spec.given = PixelType::Float;
  spec.channelNames = names;
  if (!image.coverage.empty()) spec.alphaChannel = 3;
  std::vector<float> data(bounds.pixels() * static_cast<size_t>(n));
  float* out = data.data();
  for (int y = bounds.y0; y < bounds.y1; ++y) {
    for (int x = bounds.x0; x < bounds.x1; ++x) {
      const size_t i = static_cast<size_t>(y) * image.width + x;
      for (int c = 0; c < 3; ++c) *out++ = image.pixels[i][c];
      if (!image.coverage.empty()) *out++ = image.coverage[i];
      for (const auto& [name, layer] : layers)
        for (int c = 0; c < 3; ++c) *out++ = layer->pixels[i][c];
    }
  }
  spec.attributes.push_back({"oiio:ColorSpace", "Linear"});
  spec.attributes.push_back({"Software", "penumbra"});
  for (const auto& [key, value] : metadata) spec.attributes.push_back({key, value});
  writeAtomically(path, spec, data.data());
}

PartHeader readPartHeader(const std::string& path) {
  std::string error;
  const std::unique_ptr<ImageReader> in = imageCodec().open(path, error);
  if (!in) partFailed(path, "cannot read part: " + error);
  const ImageInfo& info = in->info();
  PartHeader h;
  h.path = path;
  h.frameWidth = info.fullWidth;
  h.frameHeight = info.fullHeight;
  h.bounds = {info.x, info.x + info.width, info.y, info.y + info.height};
  h.channels = info.channelNames;
  for (const auto& [name, value] : info.attributes) {
    if (name.rfind("penumbra:", 0) == 0) h.attributes.emplace_back(name, value);
  }
  return h;
}

std::vector<std::pair<std::string, Image>> pasteParts(const std::vector<PartHeader>& parts) {
  const PartHeader& first = parts.front();
  const int n = static_cast<int>(first.channels.size());
  // Each part's rows go to its data window's place in the frame.
  const size_t frameWidth = static_cast<size_t>(first.frameWidth);
  std::vector<float> data(frameWidth * first.frameHeight * n, 0.0f);
  for (const PartHeader& p : parts) {
    std::string error;
    const std::unique_ptr<ImageReader> in = imageCodec().open(p.path, error);
    if (!in) partFailed(p.path, "cannot read part: " + error);
    const PixelBounds& b = p.bounds;
    float* at = data.data() + (static_cast<size_t>(b.y0) * frameWidth + b.x0) * n;
    const std::ptrdiff_t pixel = static_cast<std::ptrdiff_t>(n * sizeof(float));
    if (!in->readFloat(b.x0, b.x1, b.y0, b.y1, 0, n, at, pixel, pixel * static_cast<std::ptrdiff_t>(frameWidth)))
      partFailed(p.path, "cannot read part: " + in->error());
  }
  // Channel c of the frame goes to its image: "" (R, G, B, A) or a layer's.
  std::vector<std::pair<std::string, Image>> images;
  std::vector<std::pair<size_t, int>> where(n);  // image index, channel (3: coverage)
  for (int c = 0; c < n; ++c) {
    const std::string& name = first.channels[c];
    const size_t dot = name.rfind('.');
    const std::string layer = dot == std::string::npos ? "" : name.substr(0, dot);
    const std::string channel = dot == std::string::npos ? name : name.substr(dot + 1);
    auto at = std::find_if(images.begin(), images.end(), [&](const auto& i) { return i.first == layer; });
    if (at == images.end()) {
      images.emplace_back(layer, Image(first.frameWidth, first.frameHeight));
      at = images.end() - 1;
    }
    const int index = channel == "R" ? 0 : channel == "G" ? 1 : channel == "B" ? 2 : 3;
    if (index == 3) at->second.coverage.assign(at->second.pixels.size(), 0.0f);
    where[c] = {static_cast<size_t>(at - images.begin()), index};
  }
  const size_t pixels = static_cast<size_t>(first.frameWidth) * first.frameHeight;
  for (size_t i = 0; i < pixels; ++i) {
    for (int c = 0; c < n; ++c) {
      Image& image = images[where[c].first].second;
      const float v = data[i * n + c];
      if (where[c].second == 3) image.coverage[i] = v;
      else image.pixels[i][where[c].second] = v;
    }
  }
  return images;
}

}  // namespace penumbra
