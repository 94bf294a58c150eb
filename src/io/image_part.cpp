// Part files through OIIO: the data window carries the tile's place in the frame,
// so a part needs no position of its own and any EXR viewer shows it in place.
#include "io/image_part.h"
#include "core/error.h"
#include "io/image_encode.h"
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/strutil.h>
#include <algorithm>

namespace penumbra {
namespace {

[[noreturn]] void partFailed(const std::string& path, const std::string& reason) {
  std::string line = reason;
  std::replace(line.begin(), line.end(), '\n', ' ');
  throw InputError(path + ": " + std::string(OIIO::Strutil::strip(line)));
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
  if (!OIIO::Strutil::iends_with(path, ".exr")) partFailed(path, "a part of a frame is written as .exr (float)");
  std::vector<std::string> names = {"R", "G", "B"};
  if (!image.coverage.empty()) names.push_back("A");
  for (const auto& [name, layer] : layers)
    for (const char* c : {"R", "G", "B"}) names.push_back(name + "." + c);
  const int n = static_cast<int>(names.size());
  OIIO::ImageSpec spec(bounds.width(), bounds.height(), n, OIIO::TypeDesc::FLOAT);
  spec.x = bounds.x0;
  spec.y = bounds.y0;
  spec.full_x = spec.full_y = 0;
  spec.full_width = image.width;
  spec.full_height = image.height;
  spec.channelnames = names;
  if (!image.coverage.empty()) spec.alpha_channel = 3;
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
  spec.attribute("oiio:ColorSpace", "Linear");
  spec.attribute("Software", "penumbra");
  for (const auto& [key, value] : metadata) spec.attribute(key, value);
  writeAtomically(path, spec, OIIO::TypeDesc::FLOAT, data.data());
}

PartHeader readPartHeader(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) partFailed(path, "cannot read part: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  PartHeader h;
  h.path = path;
  h.frameWidth = spec.full_width;
  h.frameHeight = spec.full_height;
  h.bounds = {spec.x, spec.x + spec.width, spec.y, spec.y + spec.height};
  h.channels = spec.channelnames;
  for (const OIIO::ParamValue& p : spec.extra_attribs) {
    const std::string name = p.name().string();
    if (name.rfind("penumbra:", 0) == 0) h.attributes.emplace_back(name, p.get_string());
  }
  in->close();
  return h;
}

std::vector<std::pair<std::string, Image>> pasteParts(const std::vector<PartHeader>& parts) {
  const PartHeader& first = parts.front();
  const int n = static_cast<int>(first.channels.size());
  OIIO::ImageBuf frame(OIIO::ImageSpec(first.frameWidth, first.frameHeight, n, OIIO::TypeDesc::FLOAT));
  for (const PartHeader& p : parts) {
    OIIO::ImageBuf part(p.path);
    if (!part.read(0, 0, true, OIIO::TypeDesc::FLOAT)) partFailed(p.path, "cannot read part: " + part.geterror());
    // paste offsets the part's own pixel coordinates, which its data window already
    // places in the frame: an offset of 0.
    if (!OIIO::ImageBufAlgo::paste(frame, 0, 0, 0, 0, part))
      partFailed(p.path, "cannot paste part: " + frame.geterror());
  }
  std::vector<float> data(static_cast<size_t>(first.frameWidth) * first.frameHeight * n);
  frame.get_pixels(frame.roi(), OIIO::TypeDesc::FLOAT, data.data());
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
