// The scan reads each line once and keeps nothing but counts, so a file that would
// not fit is refused before any of it is loaded.
#include "io/obj_scan.h"
#include "core/byte_size.h"
#include "io/float_checks.h"
#include "io/obj_loader.h"
#include <fmt/format.h>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

std::string shown(const std::string& field) { return field.size() > 24 ? field.substr(0, 24) + "..." : field; }

// A field that strtod reads whole as a finite single-precision number.
bool finiteFloat(const std::string& field, double& value) {
  char* end = nullptr;
  value = std::strtod(field.c_str(), &end);
  return end != field.c_str() && *end == '\0' && std::isfinite(value) && std::fabs(value) <= FLT_MAX;
}

// MTL statements with numbers, and the range each number must lie in.
struct MtlRule {
  const char* tag;
  double lo, hi;
  const char* range;
};
constexpr MtlRule kMtlRules[] = {
    {"Ka", 0.0, FLT_MAX, ">= 0"}, {"Kd", 0.0, FLT_MAX, ">= 0"}, {"Ks", 0.0, FLT_MAX, ">= 0"},
    {"Ke", 0.0, FLT_MAX, ">= 0"}, {"Tf", 0.0, FLT_MAX, ">= 0"}, {"d", 0.0, 1.0, "in [0, 1]"},
    {"Tr", 0.0, 1.0, "in [0, 1]"}, {"Ns", 0.0, FLT_MAX, ">= 0"}, {"Ni", kMinIor, kMaxIor, "in [0.01, 100]"},
};

void checkMtl(const std::string& path) {
  std::error_code ec;
  const uint64_t size = fs::file_size(path, ec);
  if (!ec && size > kMaxMtlBytes) {
    throw ObjError(fmt::format("MTL file {}: {} MB is not a material library (at most {} MB)", path, size >> 20,
                               kMaxMtlBytes >> 20));
  }
  std::ifstream in(path, std::ios::binary);
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream fields(line.substr(0, line.find('#')));
    std::string tag, field;
    fields >> tag;
    for (const MtlRule& rule : kMtlRules) {
      if (tag != rule.tag) continue;
      while (fields >> field) {
        double v = 0.0;
        if (!finiteFloat(field, v) || v < rule.lo || v > rule.hi) {
          throw ObjError(fmt::format("MTL file {}:{}: {} \"{}\" must be a finite number {}", path, number, tag,
                                     shown(field), rule.range));
        }
      }
    }
  }
}

}  // namespace

uint64_t ObjScan::loadBytes() const {
  // tinyobjloader: 3 floats per v/vn, 2 per vt, a 12-byte index per corner; then a
  // hash entry and a unified vertex (position, normal, uv) per corner at most, and
  // the split by material copying vertices and triangles once more. A colour: 3
  // floats, then RGBA per unified vertex and its copy.
  return positions * 12 + normals * 12 + uvs * 8 + faceCorners * (12 + 48 + 2 * 32) + faces * 8 +
         coloured * 12 + (coloured > 0 ? faceCorners * 2 * 16 : 0);
}

ObjScan scanObj(const std::string& path, const LoadLimits& limits) {
  ObjScan scan;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  const fs::path dir = fs::path(path).parent_path();
  for (size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream fields(line.substr(0, line.find('#')));
    std::string tag, field;
    fields >> tag;
    if (tag == "mtllib") {
      // tinyobjloader opens each name beside the OBJ. One it cannot find would leave
      // the model grey and unlit without a word: refused, saying where it looked.
      while (fields >> field) {
        const fs::path p = fs::path(field).is_relative() ? dir / field : fs::path(field);
        std::error_code ec;
        if (!fs::is_regular_file(p, ec)) {
          const fs::path folder = fs::absolute(dir.empty() ? fs::path(".") : dir, ec).lexically_normal();
          throw ObjError(fmt::format("OBJ file {}:{}: mtllib '{}' not found (looked for {}; names resolve "
                                     "against the OBJ's folder {})", path, number, field,
                                     p.lexically_normal().string(), folder.string()));
        }
        checkMtl(p.string());
        scan.mtlFiles.push_back(p.lexically_normal().string());
      }
      continue;
    }
    if (tag == "f") {
      uint64_t corners = 0;
      while (fields >> field) ++corners;
      scan.faceCorners += corners;
      scan.faces += corners >= 3 ? corners - 2 : 0;  // triangulated as a fan
      continue;
    }
    const char* what = tag == "v" ? "vertex" : tag == "vn" ? "normal" : tag == "vt" ? "texture coordinate" : nullptr;
    if (!what) continue;
    (tag == "v" ? scan.positions : tag == "vn" ? scan.normals : scan.uvs) += 1;
    for (int count = 0; fields >> field; ++count) {
      if (tag == "v" && count == 5) ++scan.coloured;
      double v = 0.0;
      if (!finiteFloat(field, v)) {
        throw ObjError(fmt::format("OBJ file {}:{}: {} field \"{}\" is not a finite single-precision number", path,
                                   number, what, shown(field)));
      }
      if (tag == "vt" && std::fabs(v) > kMaxTexCoord) {
        throw ObjError(fmt::format("OBJ file {}:{}: texture coordinate {} is beyond +-{:g} (a texture repeats every "
                                   "unit)", path, number, shown(field), kMaxTexCoord));
      }
    }
  }
  if (limits.maxBytes > 0 && scan.loadBytes() > limits.maxBytes) {
    throw ObjError(fmt::format("OBJ file {}: needs ~{} to load ({} vertices, {} faces) but {} is {}", path,
                               formatBytes(double(scan.loadBytes())), scan.positions, scan.faces, limits.budgetName,
                               formatBytes(double(limits.maxBytes))));
  }
  return scan;
}

}  // namespace penumbra
