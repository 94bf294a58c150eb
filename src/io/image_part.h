// Part files: one tile of a frame as a float EXR whose data window is the tile and
// whose display window is the frame, with extra named layers; and their paste into
// one frame-sized buffer.
#pragma once
#include "core/image.h"
#include "core/pixel_bounds.h"
#include "io/image_io.h"
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

// Writes the pixels of `image` (frame-sized) inside `bounds` as 32-bit float R, G, B
// (A = coverage for depth and normals), then each layer's as NAME.R, NAME.G, NAME.B,
// whole or not at all. Throws InputError unless `path` is a writable .exr.
void writeImagePart(const std::string& path, const Image& image, const PixelBounds& bounds,
                    const std::vector<std::pair<std::string, const Image*>>& layers, const ImageMetadata& metadata);

// A part file's header: its frame (display window), bounds (data window), channels
// and penumbra:* attributes.
struct PartHeader {
  std::string path;
  int frameWidth = 0, frameHeight = 0;
  PixelBounds bounds;
  std::vector<std::string> channels;
  ImageMetadata attributes;  // penumbra:* only
  std::string attribute(const std::string& key) const;
};
// Throws InputError (one line naming the file) when it cannot be read.
PartHeader readPartHeader(const std::string& path);

// The parts' pixels pasted into frame-sized images: "" is R, G, B (and A as coverage
// when present), then each layer NAME of the first part's channels. The caller has
// checked that the parts share frame, channels and cover it once.
std::vector<std::pair<std::string, Image>> pasteParts(const std::vector<PartHeader>& parts);

}  // namespace penumbra
