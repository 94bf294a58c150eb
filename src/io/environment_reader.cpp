// The "environment" section: a constant sky, the built-in studio or an HDR lat-long map
// (OpenEXR or Radiance HDR, as the image module finds it), decoded and checked whole at
// load, appended as the last light.
#include "core/lights/environment_map.h"
#include "core/lights/studio_environment.h"
#include "io/input_file.h"
#include "core/byte_size.h"
#include "io/image_header.h"
#include "io/scene_sections.h"
#include "io/texture_check.h"
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

namespace fs = std::filesystem;

namespace penumbra {

namespace {

// The largest map: 8192 x 4096 (a "8k" sky) is 32M pixels, 512 MB once decoded with
// its sampling tables: enough for any sky, and still a load of seconds.
constexpr uint64_t kMaxEnvironmentPixels = 8192ull * 4096ull;
// A side at most twice the 8k map's width: a lat-long map is twice as wide as tall.
constexpr int kMaxEnvironmentSide = 16384;
const Range kRotationRange = Range::between(-360.0, 360.0);
// The skies an environment may name; "uniform" is the constant sky of color x intensity.
const std::vector<std::string> kPresets = {"uniform", "studio"};
constexpr size_t kUniform = 0, kStudio = 1;

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// The map's pixels as linear RGB, or the problem in one line. Grey maps (one
// channel) light in grey; a second channel (alpha) is ignored. Bands of rows are
// decoded straight into the texels: the map and its tables are the load's peak.
std::string decodeMap(const std::string& path, const LoadLimits& limits, int& width, int& height,
                      std::vector<Color>& texels) {
  std::error_code ec;
  if (fs::file_size(path, ec) > kMaxTextureFileBytes && !ec) {
    return path + " is larger than " + formatBytes(static_cast<double>(kMaxTextureFileBytes));
  }
  std::string problem;
  auto in = openImage(path, path, problem);
  if (!in) return problem;
  // What the decoder found, not the name: an 8-bit PNG called sky.exr holds display
  // values, not radiance.
  const std::string format = in->info().formatName;
  if (format != "openexr" && format != "hdr") {
    return path + " is a " + format + " image of " + in->info().pixelType +
           " values, not high dynamic range: an environment map must be OpenEXR or Radiance HDR";
  }
  const std::string header = imageHeaderProblem(*in, path,
                                                {kMaxEnvironmentPixels, "the 8192x4096 an environment map may have",
                                                 kMaxEnvironmentSide});
  if (!header.empty()) return header;
  const ImageInfo spec = in->info();
  if (spec.width < 2) {
    return path + " is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
           " pixels: a lat-long map needs at least 2x1";
  }
  const double bytes = environmentMapBytes(spec.width, spec.height);
  const double held = static_cast<double>(limits.heldBytes);
  if (limits.maxBytes > 0 && held + bytes > static_cast<double>(limits.maxBytes)) {
    return path + " needs " + formatBytes(bytes) + " decoded with its sampling tables, beside the process's " +
           formatBytes(held) + ": more than the " + limits.budgetName + " (" +
           formatBytes(static_cast<double>(limits.maxBytes)) + ")";
  }
  const std::string lastRow = lastRowProblem(*in, path);
  if (!lastRow.empty()) return lastRow;
  width = spec.width;
  height = spec.height;
  texels.resize(size_t(width) * size_t(height));
  const int channels = spec.nchannels >= 3 ? 3 : 1;
  const int band = bandRows(spec);
  const std::ptrdiff_t rowBytes = std::ptrdiff_t(width) * std::ptrdiff_t(sizeof(Color));
  for (int row = 0; row < height; row += band) {
    const int rows = std::min(band, height - row);
    Color* first = &texels[size_t(row) * size_t(width)];
    if (!readRows(*in, spec.y + row, rows, 0, channels, &first->r, sizeof(Color), rowBytes)) {
      return path + " is truncated or corrupt: " + firstLine(in->error());
    }
    for (size_t i = 0; i < size_t(rows) * size_t(width); ++i) {
      Color& c = first[i];
      if (channels == 1) c = Color(c.r);
      if (!isFinite(c) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f) {
        return path + " has a " + (isFinite(c) ? "negative" : "non-finite") + " value at row " +
               std::to_string(size_t(row) + i / size_t(width)) + ", column " + std::to_string(i % size_t(width)) +
               " (radiance must be finite and >= 0)";
      }
    }
  }
  return "";
}

// The "map" key's lat-long map, decoded, checked and turned by "rotation".
std::shared_ptr<const EnvironmentMap> readMap(const JsonNode& node, Scene& scene) {
  const JsonNode file = node.child("map");
  const std::string name = file.asString();
  if (name.empty()) file.fail("must name an .exr or .hdr file");
  const std::string path = resolvePath(file, name);
  const std::string ext = lowerExtension(path);
  if (ext != ".exr" && ext != ".hdr") {
    file.fail("an environment map is high dynamic range: an .exr or .hdr file, got \"" + name + "\"");
  }
  if (const std::string why = unreadableFileReason(path); !why.empty()) file.fail("environment map " + path + ": " + why);
  int width = 0, height = 0;
  std::vector<Color> texels;
  const std::string problem = decodeMap(path, node.context().limits, width, height, texels);
  if (!problem.empty()) file.fail(problem);
  const float rotation = node.floatOr("rotation", 0.0f, kRotationRange);
  scene.inputs.push_back(path);
  return makeEnvironmentMap(width, height, std::move(texels), rotation);
}

}  // namespace

void readEnvironment(const JsonNode& node, Scene& scene) {
  // Lights name themselves in 16 bits (core/photon.h); the environment is one more.
  if (scene.lights.size() >= 65535) node.fail("at most 65535 lights, the environment included");
  // "studio" or "uniform" alone: that preset with every key at its default.
  static const nlohmann::json kNoKeys = nlohmann::json::object();
  const bool named = node.value().is_string();
  if (!named && !node.value().is_object()) {
    node.fail("must be \"studio\", \"uniform\" or an object, got " + describeJson(node.value()));
  }
  const JsonNode keys = named ? JsonNode(kNoKeys, node.path(), node.context()) : node;
  const size_t preset = named ? node.asEnum(kPresets) : keys.enumOr("preset", kUniform, kPresets);
  keys.allowKeys({"preset", "color", "intensity", "map", "rotation", "background", "medium"});  // medium: io/media_reader.h
  const Color color = keys.colorOr("color", Color(1.0f));
  const float intensity = keys.floatOr("intensity", 1.0f, Range::atLeast(0.0));
  // Checked before a map is decoded: bad input is refused before heavy work.
  std::optional<Color> background;
  if (keys.has("background")) background = keys.child("background").asColor();
  if (preset == kStudio) {
    if (keys.has("map")) keys.child("map").fail("a map and the studio are two skies: give one");
    addStudioEnvironment(scene, color, intensity, keys.floatOr("rotation", 0.0f, kRotationRange));
  } else {
    if (keys.has("rotation") && !keys.has("map")) {
      keys.child("rotation").fail(
          "turns a map or the studio: give \"map\" too (a constant sky looks the same every way)");
    }
    scene.lights.push_back(makeEnvironmentLight(color, intensity, keys.has("map") ? readMap(keys, scene) : nullptr));
  }
  if (background) scene.render.environmentBackground = background;
}

}  // namespace penumbra
