// Shared by the glTF hard cases: a one-triangle glTF document to edit, written
// to a scratch folder and loaded as a scene, and the refusal it meets.
#pragma once
#include "core/error.h"
#include "io/model_import.h"
#include "io/scene_loader.h"
#include "support/scratch_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstring>
#include <functional>

namespace penumbra::hard_gltf {

using nlohmann::json;
using testing::ScratchDir;
namespace fs = std::filesystem;


inline std::string base64(const std::string& bytes) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint8_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= uint8_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= uint8_t(bytes[i + 2]);
    out += k[v >> 18 & 63];
    out += k[v >> 12 & 63];
    out += i + 1 < bytes.size() ? k[v >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? k[v & 63] : '=';
  }
  return out;
}

template <typename T>
std::string bytesOf(std::initializer_list<T> values) {
  std::string s(values.size() * sizeof(T), '\0');
  std::memcpy(s.data(), values.begin(), s.size());
  return s;
}

// One triangle in z = 0 facing +z, with normals and uvs, under node 0; buffer 0 is
// a data URI of 36 bytes positions + 36 normals + 24 uvs + 4 index bytes (0 1 2 0).
inline const std::string kVertexData = bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}) + bytesOf<float>({0, 0, 1, 0, 0, 1, 0, 0, 1}) +
                                bytesOf<float>({0, 0, 1, 0, 0, 1});

inline std::string dataUri(const std::string& bytes) { return "data:application/octet-stream;base64," + base64(bytes); }

inline json triangle() {
  const std::string data = kVertexData + std::string("\0\1\2\0", 4);
  json j = json::parse(R"({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
      {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
      {"bufferView": 3, "componentType": 5121, "count": 3, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 72, "byteLength": 24}, {"buffer": 0, "byteOffset": 96, "byteLength": 4}],
    "buffers": [{"byteLength": 100}]})");
  j["buffers"][0]["uri"] = dataUri(data);
  return j;
}

// The InputError loading `file` as a scene throws ("" when it loads), in `limit`.
inline std::string refusal(const fs::path& file, const LoadLimits& limits = {}) {
  try {
    loadScene(file.string(), {}, limits);
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find(file.filename().string()), std::string::npos) << what;
    return what;
  }
  return "";
}

// Writes `doc` as model.gltf in `dir` and expects a refusal containing each of `parts`.
inline void expectRefused(const ScratchDir& dir, const json& doc, std::vector<std::string> parts, const LoadLimits& limits = {}) {
  const fs::path file = dir.write("model.gltf", doc.dump());
  const std::string what = refusal(file, limits);
  ASSERT_FALSE(what.empty()) << "loaded: " << doc.dump().substr(0, 300);
  for (const std::string& p : parts) EXPECT_NE(what.find(p), std::string::npos) << "wanted \"" << p << "\" in: " << what;
}

}  // namespace penumbra::hard_gltf

