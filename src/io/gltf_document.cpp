// The glTF document checks that precede tinygltf: it recurses through nested JSON
// (a stack overflow at depth ~100,000), reads every file a URI names and indexes
// buffers by views it has not bounded, so those are settled here first.
#include "io/gltf_document.h"
#include "io/input_file.h"

#include "io/gltf_checks.h"
#include "io/gltf_extensions.h"
#include "io/json_parse.h"
#include "io/model_import.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

namespace penumbra {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kMaxDepth = 64;                              // glTF needs ~8; extras get the rest
constexpr uint64_t kMaxJsonBytes = 256ull << 20;           // the JSON part of a file
constexpr uint64_t kMaxImageBytes = 256ull << 20;          // one encoded image file
constexpr uint64_t kBufferSlack = 1ull << 20;              // a .bin beyond its byteLength
constexpr uint64_t kMaxInteger = 1ull << 53;               // exact in a double

std::string at(const char* array, size_t i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

// The deepest nesting of arrays and objects, strings skipped; stops counting past `limit`.
int nestingDepth(const std::string& text, int limit) {
  int depth = 0, deepest = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') ++i;
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
      if (deepest > limit) return deepest;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

// An unsigned integer member: `fallback` when absent and not required.
uint64_t integer(const json& object, const char* key, const std::string& where, const std::string& path,
                 bool required, uint64_t fallback, uint64_t lo, uint64_t hi) {
  auto it = object.find(key);
  if (it == object.end()) {
    if (required) gltfFail(path, where, std::string("has no \"") + key + "\"");
    return fallback;
  }
  uint64_t v = 0;
  if (it->is_number_unsigned()) v = it->get<uint64_t>();
  else if (it->is_number_integer() && it->get<int64_t>() >= 0) v = static_cast<uint64_t>(it->get<int64_t>());
  else if (it->is_number_float() && it->get<double>() >= 0.0 && it->get<double>() <= double(kMaxInteger) &&
           it->get<double>() == static_cast<double>(static_cast<uint64_t>(it->get<double>()))) {
    v = static_cast<uint64_t>(it->get<double>());
  } else {
    gltfFail(path, where + "." + key, "must be a non-negative integer, got " + it->dump().substr(0, 40));
  }
  if (v < lo || v > hi) {
    gltfFail(path, where + "." + key, "must be " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + std::to_string(v));
  }
  return v;
}

const json& array(const json& root, const char* key, const std::string& path) {
  static const json empty = json::array();
  auto it = root.find(key);
  if (it == root.end()) return empty;
  if (!it->is_array()) gltfFail(path, key, "must be an array");
  return *it;
}

bool isDataUri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

// An external file a URI names: in the folder, a regular file; returns it and its size.
std::string externalFile(const std::string& folder, const std::string& uri, const std::string& where,
                         const std::string& path, uint64_t& size) {
  const std::string file = resolveGltfUri(folder, uri, where, path);
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status)) gltfFail(path, where, "\"" + uri + "\" does not exist");
  if (!fs::is_regular_file(status)) gltfFail(path, where, "\"" + uri + "\" is not a regular file");
  size = fs::file_size(file, ec);
  if (ec) gltfFail(path, where, "cannot read the size of \"" + uri + "\"");
  return file;
}

void checkHeader(const json& root, const std::string& path) {
  if (!root.is_object()) gltfFail(path, "(root)", "a glTF document must be a JSON object");
  auto asset = root.find("asset");
  if (asset == root.end() || !asset->is_object()) gltfFail(path, "asset", "is missing (every glTF file has one)");
  auto version = asset->find("version");
  if (version == asset->end() || !version->is_string()) gltfFail(path, "asset.version", "is missing");
  const std::string v = version->get<std::string>();
  if (v.rfind("2.", 0) != 0) gltfFail(path, "asset.version", "is \"" + v + "\"; penumbra reads glTF 2.x");
  const json& required = array(root, "extensionsRequired", path);
  for (size_t i = 0; i < required.size(); ++i) {
    const std::string name = required[i].is_string() ? required[i].get<std::string>() : required[i].dump();
    if (readsGltfExtension(name)) continue;
    const std::string hint = unsupportedExtensionHint(name);
    gltfFail(path, at("extensionsRequired", i),
             "requires " + name + (hint.empty() ? "" : " (" + hint + ")") +
                 ", which penumbra does not support; it reads " + supportedGltfExtensions());
  }
}

// Why a file that is not a GLB is not JSON either ("starts with '<!DOCTYPE h'...",
// "starts with '\x89PNG'...", "is empty"), or "" when its first character after a
// byte-order mark and blanks opens a JSON object.
std::string notJsonStart(const std::vector<unsigned char>& bytes) {
  size_t i = bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF ? 3 : 0;
  while (i < bytes.size() && (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\n' || bytes[i] == '\r')) ++i;
  if (i == bytes.size()) return "is empty";
  if (bytes[i] == '{') return "";
  std::string shown;
  const size_t end = std::min(bytes.size(), i + 12);
  for (size_t k = i; k < end && bytes[k] != '\n' && bytes[k] != '\r'; ++k) {
    const unsigned char c = bytes[k];
    shown += c >= 0x20 && c < 0x7F && c != '\'' ? std::string(1, char(c)) : fmt::format("\\x{:02X}", c);
  }
  return "starts with '" + shown + "'" + (end < bytes.size() ? "..." : "");
}

}  // namespace

GltfSource readGltfSource(const std::string& path, const LoadLimits& limits) {
  if (const std::string why = unreadableFileReason(path); !why.empty()) throw ModelError("glTF file " + path + ": " + why);
  std::error_code ec;
  const uint64_t size = fs::file_size(path, ec);
  if (ec) throw ModelError("glTF file " + path + ": cannot read its size");
  if (limits.maxBytes > 0 && size > limits.maxBytes) {
    throw ModelError("glTF file " + path + ": is " + std::to_string(size) + " bytes but " + limits.budgetName + " is " +
                     std::to_string(limits.maxBytes));
  }
  GltfSource s;
  std::ifstream in(path, std::ios::binary);
  s.bytes.resize(size);
  if (!in.read(reinterpret_cast<char*>(s.bytes.data()), static_cast<std::streamsize>(size))) {
    throw ModelError("glTF file " + path + ": cannot read it");
  }
  s.binary = size >= 4 && std::memcmp(s.bytes.data(), "glTF", 4) == 0;
  if (!s.binary) {
    const std::string problem = notJsonStart(s.bytes);
    if (!problem.empty()) {
      throw ModelError(path + ": not a glTF file: " + problem + " (a .glb starts with 'glTF', a .gltf with '{')");
    }
    if (size > kMaxJsonBytes) gltfFail(path, "(file)", "its JSON is larger than 256 MB (keep the data in .bin files)");
    s.json.assign(s.bytes.begin(), s.bytes.end());
    return s;
  }
  // GLB: 12-byte header (magic, version, length), then chunks of length, type, data.
  auto word = [&](uint64_t at) {
    uint32_t w;
    std::memcpy(&w, s.bytes.data() + at, 4);
    return static_cast<uint64_t>(w);
  };
  if (size < 20) gltfFail(path, "GLB header", "the file ends inside its header");
  if (word(4) != 2) gltfFail(path, "GLB header", "version " + std::to_string(word(4)) + "; penumbra reads GLB version 2");
  if (word(8) != size) gltfFail(path, "GLB header", "length " + std::to_string(word(8)) + " but the file has " + std::to_string(size) + " bytes");
  const uint64_t jsonBytes = word(12);
  if (word(16) != 0x4E4F534Au || jsonBytes > size - 20) gltfFail(path, "GLB JSON chunk", "missing or longer than the file");
  if (jsonBytes > kMaxJsonBytes) gltfFail(path, "GLB JSON chunk", "larger than 256 MB");
  s.json.assign(reinterpret_cast<const char*>(s.bytes.data() + 20), jsonBytes);
  const uint64_t bin = 20 + jsonBytes;
  if (bin + 8 <= size && word(bin + 4) == 0x004E4942u) s.binBytes = std::min(word(bin), size - bin - 8);
  return s;
}

void checkGltfDocument(const GltfSource& source, const std::string& path, const std::string& folder,
                       const LoadLimits& limits, GltfFiles& files) {
  if (nestingDepth(source.json, kMaxDepth) > kMaxDepth) {
    gltfFail(path, "(JSON)", "arrays and objects nest deeper than " + std::to_string(kMaxDepth) + " levels");
  }
  json root;
  try {
    root = json::parse(source.json);
  } catch (const json::exception& e) {
    gltfFail(path, "(JSON)", "not valid JSON: " + parseProblem(e.what()));
  }
  checkHeader(root, path);

  const json& buffers = array(root, "buffers", path);
  std::vector<uint64_t> bufferBytes;
  uint64_t total = 0;
  for (size_t i = 0; i < buffers.size(); ++i) {
    const std::string where = at("buffers", i);
    if (!buffers[i].is_object()) gltfFail(path, where, "must be an object");
    const uint64_t bytes = integer(buffers[i], "byteLength", where, path, true, 0, 1, kMaxInteger);
    bufferBytes.push_back(bytes);
    total += bytes;
    auto uri = buffers[i].find("uri");
    if (uri == buffers[i].end()) {
      if (!source.binary || i != 0 || bytes > source.binBytes) {
        gltfFail(path, where, "has no uri and is not the GLB's binary chunk (or is longer than it)");
      }
      continue;
    }
    if (!uri->is_string()) gltfFail(path, where + ".uri", "must be a string");
    if (isDataUri(uri->get<std::string>())) continue;
    uint64_t size = 0;
    const std::string file = externalFile(folder, uri->get<std::string>(), where + ".uri", path, size);
    if (size < bytes) gltfFail(path, where + ".uri", file + " holds " + std::to_string(size) + " bytes, fewer than byteLength " + std::to_string(bytes));
    if (size > bytes + kBufferSlack) {
      gltfFail(path, where + ".uri", file + " holds " + std::to_string(size) + " bytes, far more than byteLength " + std::to_string(bytes));
    }
    files.allow(file, bytes, bytes + kBufferSlack);
  }
  if (limits.maxBytes > 0 && total > limits.maxBytes) {
    gltfFail(path, "buffers", "their byteLengths add up to " + std::to_string(total) + " bytes but " + limits.budgetName +
                                  " is " + std::to_string(limits.maxBytes));
  }

  const json& views = array(root, "bufferViews", path);
  for (size_t i = 0; i < views.size(); ++i) {
    const std::string where = at("bufferViews", i);
    if (!views[i].is_object()) gltfFail(path, where, "must be an object");
    const uint64_t buffer = integer(views[i], "buffer", where, path, true, 0, 0, kMaxInteger);
    if (buffer >= bufferBytes.size()) gltfFail(path, where + ".buffer", "buffer " + std::to_string(buffer) + " does not exist");
    const uint64_t offset = integer(views[i], "byteOffset", where, path, false, 0, 0, kMaxInteger);
    const uint64_t length = integer(views[i], "byteLength", where, path, true, 0, 1, kMaxInteger);
    integer(views[i], "byteStride", where, path, false, 4, 4, 252);
    if (offset + length > bufferBytes[buffer]) {  // both below 2^53: no overflow
      gltfFail(path, where, "byteOffset " + std::to_string(offset) + " + byteLength " + std::to_string(length) +
                                " reaches past the end of buffer " + std::to_string(buffer) + " (" +
                                std::to_string(bufferBytes[buffer]) + " bytes)");
    }
  }

  const json& accessors = array(root, "accessors", path);
  for (size_t i = 0; i < accessors.size(); ++i) {
    const std::string where = at("accessors", i);
    if (!accessors[i].is_object()) gltfFail(path, where, "must be an object");
    integer(accessors[i], "count", where, path, true, 0, 1, kMaxInteger);
    integer(accessors[i], "byteOffset", where, path, false, 0, 0, kMaxInteger);
  }

  // tinygltf reads an image file once per image naming it, so a repeated URI would
  // multiply the bytes read; each file once, all of them within the budget.
  const uint64_t imageCap = limits.maxBytes > 0 ? std::min(kMaxImageBytes, limits.maxBytes) : kMaxImageBytes;
  std::map<std::string, size_t> imageFiles;
  const json& images = array(root, "images", path);
  for (size_t i = 0; i < images.size(); ++i) {
    const std::string where = at("images", i);
    if (!images[i].is_object()) gltfFail(path, where, "must be an object");
    auto uri = images[i].find("uri");
    if (uri == images[i].end()) continue;
    if (!uri->is_string()) gltfFail(path, where + ".uri", "must be a string");
    if (isDataUri(uri->get<std::string>())) continue;
    uint64_t size = 0;
    const std::string file = externalFile(folder, uri->get<std::string>(), where + ".uri", path, size);
    if (size > imageCap) gltfFail(path, where + ".uri", file + " is " + std::to_string(size) + " bytes, more than the " + std::to_string(imageCap) + " an image may have");
    if (!imageFiles.emplace(file, i).second) {
      gltfFail(path, where + ".uri", "names the same file as images[" + std::to_string(imageFiles[file]) + "] (share one image between textures instead)");
    }
    total += size;
    if (limits.maxBytes > 0 && total > limits.maxBytes) {
      gltfFail(path, where + ".uri", "buffers and images add up to " + std::to_string(total) + " bytes but " + limits.budgetName +
                                         " is " + std::to_string(limits.maxBytes));
    }
    files.allow(file, 0, imageCap);
  }
}

}  // namespace penumbra
