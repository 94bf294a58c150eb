// An image header judged before its pixels: its sizes, and its last row read through
// a buffer of one row (one tile for tiled files), which fails on a file that ends
// before the pixels its header claims. Decoding then reads bands of rows.
#include "io/image_header.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <vector>

namespace penumbra {

namespace {

// Tiled files are read a row of tiles at a time: a tile's side bounds that band.
constexpr int kMaxTileSide = 1024;

// "" when every attribute of the OpenEXR header(s) at `in` (past the magic and version)
// claims no more bytes than the file has left, else the problem. OpenEXR 3.1 sizes a
// string attribute's buffer from its claim: a 529-byte file claiming 1.9 GB made it
// allocate 2 GB before failing on the end of the file.
std::string exrAttributeProblem(std::ifstream& in, uint64_t fileBytes, bool multipart) {
  const auto token = [&in](std::string& text) {  // a name or type: at most 255 characters
    text.clear();
    for (char c; in.get(c) && c != '\0';) {
      if (text.size() == 255) return false;
      text += c;
    }
    return bool(in);
  };
  std::string name, type;
  for (bool first = true;; first = false) {  // each header, then (multipart) an empty one ends the list
    if (!token(name)) return "its OpenEXR header ends early";
    if (name.empty() && (!first || !multipart)) return "";
    while (!name.empty()) {
      int32_t size = 0;
      if (!token(type) || !in.read(reinterpret_cast<char*>(&size), 4)) return "its OpenEXR header ends early";
      const uint64_t left = fileBytes - uint64_t(in.tellg());
      if (size < 0 || uint64_t(size) > left) {
        return "an attribute of its OpenEXR header claims " + std::to_string(size) + " bytes, more than the " +
               std::to_string(left) + " the file has left";
      }
      in.seekg(size, std::ios::cur);
      if (!token(name)) return "its OpenEXR header ends early";
    }
    if (!multipart) return "";
  }
}

std::string sizeText(const ImageInfo& spec) {
  return std::to_string(spec.width) + "x" + std::to_string(spec.height);
}

}  // namespace

std::unique_ptr<ImageReader> openImage(const std::string& path, const std::string& label, std::string& problem) {
  std::error_code ec;
  const uint64_t fileBytes = std::filesystem::file_size(path, ec);
  std::ifstream file(path, std::ios::binary);
  unsigned char head[8] = {};
  // OpenEXR's magic, whatever the name: OIIO asks every reader when the name's refuses.
  if (!ec && file.read(reinterpret_cast<char*>(head), 8) && head[0] == 0x76 && head[1] == 0x2f && head[2] == 0x31 &&
      head[3] == 0x01) {
    const bool multipart = (head[5] & 0x10) != 0;  // version bit 12
    const std::string exr = exrAttributeProblem(file, fileBytes, multipart);
    if (!exr.empty()) {
      problem = label + " is corrupt: " + exr;
      return nullptr;
    }
  }
  std::string error;
  auto in = imageCodec().open(path, error);
  if (!in) problem = "cannot read " + label + ": " + firstLine(error);
  return in;
}

std::string firstLine(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  return line.empty() ? "unknown error" : line;
}

int bandRows(const ImageInfo& spec) { return spec.tileWidth > 0 ? spec.tileHeight : 64; }

bool readRows(ImageReader& in, int y, int rows, int chbegin, int chend, float* data, std::ptrdiff_t xstride,
              std::ptrdiff_t ystride) {
  const ImageInfo& spec = in.info();
  return in.readFloat(spec.x, spec.x + spec.width, y, y + rows, chbegin, chend, data, xstride, ystride);
}

std::string imageHeaderProblem(const ImageReader& in, const std::string& label, const ImageBound& bound) {
  const ImageInfo& spec = in.info();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1) {
    return label + " has no pixels (a flat image needs at least 1x1)";
  }
  if (spec.width > bound.maxSide || spec.height > bound.maxSide) {
    return label + " is " + sizeText(spec) + " pixels: " + (spec.width > bound.maxSide ? "wider" : "taller") +
           " than the " + std::to_string(bound.maxSide) + " pixels penumbra reads in a row or column";
  }
  if (uint64_t(spec.width) * uint64_t(spec.height) > bound.maxPixels) {
    return label + " is " + sizeText(spec) + " pixels, more than " + bound.maxText;
  }
  const bool tiled = spec.tileWidth > 0;
  if (tiled && (spec.tileWidth > kMaxTileSide || spec.tileHeight > kMaxTileSide || spec.tileHeight <= 0)) {
    return label + " has " + std::to_string(spec.tileWidth) + "x" + std::to_string(spec.tileHeight) +
           " pixel tiles, larger than the " + std::to_string(kMaxTileSide) + "x" + std::to_string(kMaxTileSide) +
           " penumbra reads";
  }
  return "";
}

std::string lastRowProblem(ImageReader& in, const std::string& label) {
  const ImageInfo spec = in.info();
  const bool tiled = spec.tileWidth > 0;
  // The last row (the last tile of a tiled file): a decoder reaches it only through
  // what the file really holds.
  const int yEnd = spec.y + spec.height;
  const int last = tiled ? spec.y + (spec.height - 1) / spec.tileHeight * spec.tileHeight : yEnd - 1;
  const size_t values = tiled ? size_t(spec.tileWidth) * size_t(spec.tileHeight) : size_t(spec.width);
  std::vector<float> row(values * size_t(spec.nchannels));
  const bool read = tiled ? in.readFloat(spec.x, std::min(spec.x + spec.tileWidth, spec.x + spec.width), last, yEnd, 0,
                                         spec.nchannels, row.data(), kAutoStride, kAutoStride)
                          : readRows(in, last, 1, 0, spec.nchannels, row.data());
  if (!read) {
    return label + " is truncated or corrupt: its header says " + sizeText(spec) +
           " pixels but its last row cannot be read (" + firstLine(in.error()) + ")";
  }
  return "";
}

}  // namespace penumbra
