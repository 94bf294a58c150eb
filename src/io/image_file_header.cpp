// PNG chunks and OpenEXR header attributes walked with plain reads: only the bytes
// the answer needs, each length checked against the file before it is trusted.
#include "io/image_file_header.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <type_traits>

namespace penumbra {
namespace {

constexpr unsigned char kPngMagic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr unsigned char kExrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
constexpr const char* kPenumbraPrefix = "penumbra:";

uint32_t bigEndian32(const unsigned char* b) {
  return uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | uint32_t(b[3]);
}

template <typename T>
bool readLittle(std::ifstream& in, T& value) {
  unsigned char b[sizeof(T)];
  if (!in.read(reinterpret_cast<char*>(b), sizeof b)) return false;
  std::make_unsigned_t<T> v = 0;
  for (size_t i = sizeof b; i-- > 0;) v = static_cast<std::make_unsigned_t<T>>(v << 8 | b[i]);
  value = static_cast<T>(v);
  return true;
}

// A null-terminated EXR name or type: at most 255 characters.
bool readToken(std::ifstream& in, std::string& text) {
  text.clear();
  for (char c; in.get(c);) {
    if (c == '\0') return true;
    if (text.size() == 255) return false;
    text += c;
  }
  return false;
}

// The text chunks before the first IDAT (what a decoder's header read reports).
std::optional<std::string> pngText(std::ifstream& in, uint64_t fileBytes, const std::string& name) {
  uint64_t at = sizeof kPngMagic;
  unsigned char head[8];
  while (at + 12 <= fileBytes && in.seekg(std::streamoff(at)) && in.read(reinterpret_cast<char*>(head), 8)) {
    const uint32_t length = bigEndian32(head);
    if (length > fileBytes - at - 12) return std::nullopt;
    if (std::memcmp(head + 4, "IDAT", 4) == 0 || std::memcmp(head + 4, "IEND", 4) == 0) return std::nullopt;
    if (std::memcmp(head + 4, "tEXt", 4) == 0 && length > name.size() && length <= (1u << 24)) {
      std::string data(length, '\0');
      if (!in.read(data.data(), length)) return std::nullopt;
      if (data.compare(0, name.size() + 1, name.c_str(), name.size() + 1) == 0) return data.substr(name.size() + 1);
    }
    at += 12 + uint64_t(length);
  }
  return std::nullopt;
}

struct ExrHeader {
  bool parsed = false;
  std::optional<std::string> text;  // the asked-for string attribute
  int32_t ymin = 0, ymax = -1;
  int compression = -1;
};

// A single-part, scanline, flat file's header, after the magic.
ExrHeader exrHeader(std::ifstream& in, uint64_t fileBytes, const std::string& name) {
  ExrHeader h;
  uint32_t version = 0;
  if (!readLittle(in, version) || (version & 0xff) != 2 || (version & 0x1a00) != 0) return h;  // tiled, deep, multipart
  std::string attr, type;
  bool window = false;
  while (readToken(in, attr)) {
    if (attr.empty()) {
      h.parsed = window && h.compression >= 0;
      return h;
    }
    int32_t size = 0;
    if (!readToken(in, type) || !readLittle(in, size) || size < 0 ||
        uint64_t(size) > fileBytes - uint64_t(in.tellg())) {
      return h;
    }
    const std::streampos next = in.tellg() + std::streamoff(size);
    if (attr == name && type == "string") {
      std::string value(size_t(size), '\0');
      if (!in.read(value.data(), size)) return h;
      h.text = value;
    } else if (attr == "dataWindow" && type == "box2i" && size == 16) {
      int32_t xmin = 0, xmax = 0;
      window = readLittle(in, xmin) && readLittle(in, h.ymin) && readLittle(in, xmax) && readLittle(in, h.ymax);
    } else if (attr == "compression" && size == 1) {
      h.compression = in.get();
    }
    if (!in.seekg(next)) return h;
  }
  return h;
}

// Scanlines per chunk of each OpenEXR compression, by its code (NONE .. DWAB).
int linesPerChunk(int compression) {
  constexpr int lines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
  return compression >= 0 && compression < int(std::size(lines)) ? lines[compression] : 0;
}

enum class Kind { Png, Exr, Other };

Kind open(const std::string& path, std::ifstream& in, uint64_t& fileBytes) {
  in.open(path, std::ios::binary | std::ios::ate);
  if (!in) return Kind::Other;
  fileBytes = uint64_t(in.tellg());
  in.seekg(0);
  unsigned char magic[8] = {};
  if (!in.read(reinterpret_cast<char*>(magic), 4)) return Kind::Other;
  if (std::memcmp(magic, kExrMagic, 4) == 0) return Kind::Exr;
  if (in.read(reinterpret_cast<char*>(magic + 4), 4) && std::memcmp(magic, kPngMagic, 8) == 0) return Kind::Png;
  return Kind::Other;
}

}  // namespace

std::optional<std::string> penumbraAttribute(const std::string& path, const std::string& name) {
  if (name.rfind(kPenumbraPrefix, 0) != 0) return std::nullopt;
  std::ifstream in;
  uint64_t fileBytes = 0;
  switch (open(path, in, fileBytes)) {
    case Kind::Png: return pngText(in, fileBytes, name);
    case Kind::Exr: {
      const ExrHeader h = exrHeader(in, fileBytes, name);
      return h.parsed ? h.text : std::nullopt;
    }
    case Kind::Other: break;
  }
  return std::nullopt;
}

std::optional<bool> exrLastChunkWhole(const std::string& path) {
  std::ifstream in;
  uint64_t fileBytes = 0;
  if (open(path, in, fileBytes) != Kind::Exr) return std::nullopt;
  const ExrHeader h = exrHeader(in, fileBytes, "");
  const int lines = linesPerChunk(h.compression);
  if (!h.parsed || lines == 0 || h.ymax < h.ymin) return std::nullopt;
  const uint64_t chunks = (uint64_t(h.ymax) - uint64_t(h.ymin) + uint64_t(lines)) / uint64_t(lines);
  // The offset table follows the header; its last entry is the last rows' chunk.
  const uint64_t tableEnd = uint64_t(in.tellg()) + chunks * 8;
  uint64_t offset = 0;
  if (tableEnd > fileBytes || !in.seekg(std::streamoff(tableEnd - 8)) || !readLittle(in, offset)) return false;
  int32_t y = 0, bytes = 0;
  if (offset < tableEnd || offset > fileBytes - 8 || !in.seekg(std::streamoff(offset)) || !readLittle(in, y) ||
      !readLittle(in, bytes)) {
    return false;
  }
  const int64_t lastY = int64_t(h.ymin) + int64_t(chunks - 1) * lines;
  return y == lastY && bytes >= 0 && uint64_t(bytes) <= fileBytes - offset - 8;
}

}  // namespace penumbra
