// The "environment" section: a constant sky or an HDR lat-long map (EXR or Radiance
// .hdr through OpenImageIO), decoded and checked whole at load, appended as the last light.
#include "core/environment.h"
#include "core/byte_size.h"
#include "io/scene_sections.h"
#include "io/texture_check.h"
#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;

namespace penumbra {

namespace {

// The largest map: 8192 x 4096 (a "8k" sky) is 32M pixels, 16 bytes each once decoded
// with its sampling tables (512 MB): enough for any sky, and still a load of seconds.
constexpr uint64_t kMaxEnvironmentPixels = 8192ull * 4096ull;
constexpr double kEnvironmentBytesPerPixel = sizeof(Color) + sizeof(float);

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// The map's pixels as linear RGB, or the problem in one line. Grey maps (one
// channel) light in grey; a second channel (alpha) is ignored.
std::string decodeMap(const std::string& path, const LoadLimits& limits, int& width, int& height,
                      std::vector<Color>& texels) {
  std::error_code ec;
  if (fs::file_size(path, ec) > kMaxTextureFileBytes && !ec) {
    return path + " is larger than " + formatBytes(static_cast<double>(kMaxTextureFileBytes));
  }
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    std::string error = OIIO::geterror();
    return "cannot read " + path + ": " + error.substr(0, error.find('\n'));
  }
  const OIIO::ImageSpec spec = in->spec();
  if (spec.width < 2 || spec.height < 1 || spec.nchannels <= 0 || spec.depth > 1) {
    return path + " is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
           " pixels: a lat-long map needs at least 2x1";
  }
  const uint64_t pixels = uint64_t(spec.width) * uint64_t(spec.height);
  if (pixels > kMaxEnvironmentPixels) {
    return path + " is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
           " pixels, more than the 8192x4096 an environment map may have";
  }
  const double bytes = static_cast<double>(pixels) * kEnvironmentBytesPerPixel;
  if (limits.maxBytes > 0 && bytes > static_cast<double>(limits.maxBytes)) {
    return path + " needs " + formatBytes(bytes) + " decoded, more than the " + limits.budgetName + " (" +
           formatBytes(static_cast<double>(limits.maxBytes)) + ")";
  }
  const int channels = spec.nchannels;
  std::vector<float> raw(pixels * size_t(channels));
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, raw.data()) || in->has_error()) {
    const std::string error = in->geterror();
    return path + " is truncated or corrupt: " + error.substr(0, error.find('\n'));
  }
  width = spec.width;
  height = spec.height;
  texels.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    const float* p = &raw[i * size_t(channels)];
    const Color c = channels >= 3 ? Color(p[0], p[1], p[2]) : Color(p[0]);
    if (!isFinite(c) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f) {
      return path + " has a " + (isFinite(c) ? "negative" : "non-finite") + " value at row " +
             std::to_string(i / size_t(width)) + ", column " + std::to_string(i % size_t(width)) +
             " (radiance must be finite and >= 0)";
    }
    texels[i] = c;
  }
  return "";
}

}  // namespace

void readEnvironment(const JsonNode& node, Scene& scene) {
  node.requireObject();
  node.allowKeys({"color", "intensity", "map", "rotation"});
  // Lights name themselves in 16 bits (core/photon.h); the environment is one more.
  if (scene.lights.size() >= 65535) node.fail("at most 65535 lights, the environment included");
  const Color color = node.colorOr("color", Color(1.0f));
  const float intensity = node.floatOr("intensity", 1.0f, Range::atLeast(0.0));
  std::shared_ptr<const EnvironmentMap> map;
  if (node.has("map")) {
    const JsonNode file = node.child("map");
    const std::string name = file.asString();
    if (name.empty()) file.fail("must name an .exr or .hdr file");
    const std::string path = resolvePath(file, name);
    const std::string ext = lowerExtension(path);
    if (ext != ".exr" && ext != ".hdr") {
      file.fail("an environment map is high dynamic range: an .exr or .hdr file, got \"" + name + "\"");
    }
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) file.fail("environment map not found: " + path);
    int width = 0, height = 0;
    std::vector<Color> texels;
    const std::string problem = decodeMap(path, node.context().limits, width, height, texels);
    if (!problem.empty()) file.fail(problem);
    const float rotation = node.floatOr("rotation", 0.0f, Range::between(-360.0, 360.0));
    map = makeEnvironmentMap(width, height, std::move(texels), rotation);
    scene.inputs.push_back(path);
  } else if (node.has("rotation")) {
    node.child("rotation").fail("turns a map: give \"map\" too (a constant sky looks the same every way)");
  }
  scene.lights.push_back(makeEnvironmentLight(color, intensity, std::move(map)));
}

}  // namespace penumbra
