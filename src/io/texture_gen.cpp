// Procedural lat-long textures (checker, grid, gas giant, earth-like) built on
// GLM simplex noise over sphere directions, plus the on-disk builtin: cache.
#include "io/texture_gen.h"
#include "core/color.h"

#include "core/error.h"
#include "io/image_io.h"

#include <glm/gtc/noise.hpp>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>

namespace penumbra {
namespace {

// Bump when any generator's output changes: cached files carry it in their name.
constexpr int kContentVersion = 1;
constexpr int kDefaultWidth = 2048;
constexpr int kMaxSize = 16384;

float smooth(float e0, float e1, float x) { return glm::smoothstep(e0, e1, x); }

// Palette colours are picked by eye in sRGB; textures hold linear values.
Color fromSrgb(Color c) { return srgbToLinear(c); }

uint64_t splitMix64(uint64_t& state) {
  uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Seeded fractal noise: GLM's simplex noise has no seed, so each seed gets
// its own far-apart offsets into the noise field, one per octave (decorrelating
// octaves too). Offsets stay within +-256 so float positions keep precision.
class Fbm {
 public:
  explicit Fbm(uint64_t seed) {
    uint64_t state = seed;
    for (Vec3& offset : offsets_)
      for (int a = 0; a < 3; ++a)
        offset[a] = static_cast<float>(splitMix64(state) >> 40) / (1 << 24) * 512.0f - 256.0f;
  }
  // Roughly in [-1, 1]; octave k has frequency 2^k and weight gain^k.
  float operator()(Vec3 p, int octaves, float gain = 0.5f) const {
    float sum = 0.0f, weight = 1.0f, norm = 0.0f;
    for (int k = 0; k < octaves; ++k) {
      sum += weight * glm::simplex(p + offsets_[k]);
      norm += weight;
      weight *= gain;
      p *= 2.0f;
    }
    return sum / norm;
  }

 private:
  Vec3 offsets_[12];
};

struct Sample {
  float u, v;       // texture coordinates of the pixel centre
  float lon, lat;   // radians; lon in [0, 2pi), lat in [-pi/2, pi/2]
  Vec3 dir;         // unit sphere direction, y up
  float pixelDegU;  // pixel footprint in degrees, for anti-aliased lines
  float pixelDegV;
};

using Shader = std::function<Color(const Sample&)>;

Image render(int width, int height, const Shader& shade) {
  Image image(width, height);
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      Sample s;
      s.u = (x + 0.5f) / width;
      s.v = (y + 0.5f) / height;
      s.lon = 2.0f * kPi * s.u;
      s.lat = 0.5f * kPi - kPi * s.v;
      float theta = kPi * s.v;
      s.dir = Vec3(std::sin(theta) * std::cos(s.lon), std::cos(theta),
                   std::sin(theta) * std::sin(s.lon));
      s.pixelDegU = 360.0f / width;
      s.pixelDegV = 180.0f / height;
      image.at(x, y) = shade(s);
    }
  });
  return image;
}

Color checker(const Sample& s) {
  int cx = static_cast<int>(s.u * 8.0f), cy = static_cast<int>(s.v * 4.0f);
  const float* c = (cx + cy) % 2 == 0 ? kCheckerLight : kCheckerDark;
  return Color(c[0], c[1], c[2]);
}

// Coverage of a line `width` pixels wide at `distance` degrees, `pixel` degrees a pixel.
float lineCoverage(float distance, float pixel, float width) {
  return glm::clamp(0.5f * width + 0.5f - distance / pixel, 0.0f, 1.0f);
}

Color grid(const Sample& s) {
  float lonDeg = s.u * 360.0f, latDeg = 90.0f - s.v * 180.0f;
  auto toLine = [](float deg) { return std::abs(deg - 15.0f * std::round(deg / 15.0f)); };
  float lines = std::max(lineCoverage(toLine(lonDeg), s.pixelDegU, 1.5f),
                         lineCoverage(toLine(latDeg), s.pixelDegV, 1.5f));
  float meridianDistance = std::min(lonDeg, 360.0f - lonDeg);  // u = 0 and u = 1 meet
  float meridian = lineCoverage(meridianDistance, s.pixelDegU, 3.0f);
  Color color = glm::mix(fromSrgb({0.04f, 0.06f, 0.22f}), fromSrgb({0.55f, 0.65f, 0.85f}), lines);
  return glm::mix(color, fromSrgb({1.0f, 0.85f, 0.15f}), meridian);
}

// Belts and zones of the gas giant, as (sin latitude, sRGB colour) stops.
struct Stop {
  float at;
  Color color;
};
const Stop kBands[] = {
    {-1.00f, {0.47f, 0.48f, 0.52f}}, {-0.90f, {0.56f, 0.53f, 0.50f}},
    {-0.78f, {0.72f, 0.63f, 0.52f}}, {-0.66f, {0.88f, 0.80f, 0.67f}},
    {-0.58f, {0.62f, 0.45f, 0.33f}}, {-0.50f, {0.92f, 0.86f, 0.74f}},
    {-0.42f, {0.97f, 0.93f, 0.84f}}, {-0.30f, {0.70f, 0.42f, 0.26f}},
    {-0.19f, {0.80f, 0.57f, 0.38f}}, {-0.08f, {0.97f, 0.93f, 0.84f}},
    {0.06f, {0.93f, 0.85f, 0.70f}},  {0.15f, {0.52f, 0.33f, 0.22f}},
    {0.26f, {0.78f, 0.58f, 0.41f}},  {0.34f, {0.96f, 0.91f, 0.80f}},
    {0.44f, {0.64f, 0.47f, 0.34f}},  {0.52f, {0.90f, 0.82f, 0.69f}},
    {0.63f, {0.74f, 0.60f, 0.47f}},  {0.76f, {0.80f, 0.72f, 0.61f}},
    {0.90f, {0.56f, 0.53f, 0.50f}},  {1.00f, {0.47f, 0.48f, 0.52f}},
};

Color bandColor(float b) {
  b = glm::clamp(b, -1.0f, 1.0f);
  size_t k = 1;
  while (k + 1 < std::size(kBands) && kBands[k].at < b) ++k;
  const Stop &lo = kBands[k - 1], &hi = kBands[k];
  float t = smooth(lo.at, hi.at, b);
  return glm::mix(lo.color, hi.color, t * t * (3.0f - 2.0f * t));  // crisper edges
}

Color planet(const Sample& s, const Fbm& noise) {
  // Features stretch along longitude: the noise runs 6x faster in y than in x, z.
  // Two levels of domain warping (q, then t sampled through q) give the
  // flowing, curling turbulence of belt edges instead of plain blobs.
  const Vec3 p = s.dir * Vec3(1.0f, 6.0f, 1.0f);
  Vec3 q(noise(p * 1.5f, 3), noise(p * 1.5f + 17.0f, 3), noise(p * 1.5f + 41.0f, 3));
  float turbulence = noise(p * 2.5f + 2.2f * q, 6, 0.55f);
  float b = s.dir.y + 0.06f * turbulence;

  // The storm: an oval in the south, ~2:1 wide, whose interior swirls; bands
  // flow around it because its neighbourhood pushes b away from its centre.
  const float stormLon = 1.1f * kPi, stormLat = -0.38f, radiusLon = 0.30f, radiusLat = 0.13f;
  float dLon = std::remainder(s.lon - stormLon, 2.0f * kPi) * std::cos(stormLat);
  float dLat = s.lat - stormLat;
  float r = std::sqrt(glm::pow(dLon / radiusLon, 2.0f) + glm::pow(dLat / radiusLat, 2.0f));
  b += 0.04f * dLat / (std::abs(dLat) + 0.03f) * std::exp(-r * r);

  Color color = bandColor(b);
  // Fine streaks riding the same flow, and mottling that grows towards the poles.
  color *= 1.0f + 0.10f * noise(p * 10.0f + 3.0f * q, 4);
  float polar = smooth(0.55f, 0.9f, std::abs(s.dir.y));
  color *= 1.0f + 0.12f * polar * noise(s.dir * 9.0f + 2.0f * q, 4);

  if (r < 1.3f) {
    float angle = 6.0f * glm::pow(glm::max(0.0f, 1.0f - r), 1.5f);  // fastest at the core
    float ca = std::cos(angle), sa = std::sin(angle);
    Vec3 local(ca * dLon - sa * dLat * 2.0f, sa * dLon + ca * dLat * 2.0f, 0.0f);
    float swirl = noise(local * 12.0f + Vec3(0.0f, 0.0f, 7.0f), 5);
    Color core = glm::mix(Color(0.70f, 0.27f, 0.16f), Color(0.90f, 0.55f, 0.34f),
                          glm::clamp(0.5f + 0.9f * swirl, 0.0f, 1.0f));
    core = glm::mix(core, Color(0.96f, 0.88f, 0.76f), smooth(0.55f, 0.92f, r));  // pale collar
    color = glm::mix(core, color, smooth(0.92f, 1.2f, r + 0.08f * swirl));
  }

  // A string of small white ovals in the southern temperate zone.
  for (int k = 0; k < 4; ++k) {
    float oLat0 = -0.70f - 0.03f * (k % 2), size = 0.045f + 0.012f * ((k * 7) % 3);
    float oLon = std::remainder(s.lon - (0.3f + 0.45f * k), 2.0f * kPi) * std::cos(oLat0);
    float oLat = s.lat - oLat0;
    float ro = std::sqrt(glm::pow(oLon / size, 2.0f) + glm::pow(oLat / (0.55f * size), 2.0f));
    if (ro > 1.6f) continue;
    ro += 0.25f * noise(Vec3(oLon, oLat, 0.0f) * 40.0f + 3.0f * k, 3);
    color *= 1.0f - 0.15f * smooth(0.7f, 1.0f, ro) * (1.0f - smooth(1.0f, 1.4f, ro));  // dark rim
    color = glm::mix(Color(0.97f, 0.94f, 0.88f), color, smooth(0.5f, 0.95f, ro));
  }
  return fromSrgb(glm::clamp(color, 0.0f, 1.0f));
}

Color earthlike(const Sample& s, const Fbm& noise) {
  // A gentle domain warp bends coastlines without marbling the continents.
  Vec3 p = s.dir * 1.4f;
  Vec3 warp(noise(p + 3.0f, 3), noise(p + 11.0f, 3), noise(p + 23.0f, 3));
  float height = noise(p + 0.35f * warp, 9, 0.5f) + 0.04f;
  float absLat = std::abs(s.lat) * 180.0f / kPi;
  float ice = smooth(71.0f, 73.0f, absLat + 8.0f * noise(p * 4.0f + 5.0f, 5));

  Color color;
  if (height < 0.0f) {
    // Shallow shelves hug the coasts; the open ocean is uniformly deep.
    float depth = smooth(0.0f, 0.08f, -height);
    color = glm::mix(Color(0.12f, 0.40f, 0.55f), Color(0.03f, 0.12f, 0.32f), depth);
  } else {
    // Dry belts near 25 degrees, wetter at the equator and mid-latitudes.
    float moisture = 0.6f + 0.4f * noise(p * 2.5f + 31.0f, 5) -
                     0.3f * std::exp(-glm::pow((absLat - 24.0f) / 9.0f, 2.0f));
    Color lowland = glm::mix(Color(0.76f, 0.66f, 0.46f), Color(0.24f, 0.42f, 0.17f),
                             smooth(0.35f, 0.55f, moisture));
    Color highland = glm::mix(lowland, Color(0.46f, 0.38f, 0.29f), smooth(0.15f, 0.32f, height));
    color = glm::mix(highland, Color(0.88f, 0.88f, 0.90f), smooth(0.44f, 0.50f, height));
  }
  color = glm::mix(color, Color(0.93f, 0.95f, 0.98f), ice);
  return fromSrgb(color);
}

std::string validNames() {
  std::string list;
  for (const std::string& name : builtinTextureNames()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

// The user's own cache first: a fixed name under a shared /tmp could be created
// in advance by someone else, so it is only the last resort.
std::filesystem::path cacheDirectory() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && *xdg) return std::filesystem::path(xdg) / "penumbra" / "textures";
  const char* home = std::getenv("HOME");
  if (home && *home) return std::filesystem::path(home) / ".cache" / "penumbra" / "textures";
  return std::filesystem::path("/tmp") / ("penumbra-textures-" + std::to_string(::getuid()));
}

}  // namespace

std::filesystem::path textureCacheDirectory() { return cacheDirectory(); }

const std::vector<std::string>& builtinTextureNames() {
  static const std::vector<std::string> names{"checker", "grid", "planet", "earthlike"};
  return names;
}

Image makeTexture(const std::string& name, int width, int height, uint64_t seed) {
  if (width < 1 || height < 1 || width > kMaxSize || height > kMaxSize) {
    throw InputError("texture '" + name + "': size " + std::to_string(width) + "x" +
                     std::to_string(height) + " outside [1, 16384]");
  }
  Fbm noise(seed);
  if (name == "checker") return render(width, height, checker);
  if (name == "grid") return render(width, height, grid);
  if (name == "planet") return render(width, height, [&](const Sample& s) { return planet(s, noise); });
  if (name == "earthlike")
    return render(width, height, [&](const Sample& s) { return earthlike(s, noise); });
  throw InputError("unknown builtin texture '" + name + "' (valid: " + validNames() + ")");
}

std::string builtinTexturePath(const std::string& spec) {
  const std::string prefix = "builtin:";
  if (spec.compare(0, prefix.size(), prefix) != 0) {
    throw InputError("texture '" + spec + "': expected builtin:NAME or builtin:NAME@WIDTH");
  }
  std::string name = spec.substr(prefix.size());
  int width = kDefaultWidth;
  if (size_t at = name.find('@'); at != std::string::npos) {
    std::string digits = name.substr(at + 1);
    name.resize(at);
    char* end = nullptr;
    long parsed = digits.empty() ? 0 : std::strtol(digits.c_str(), &end, 10);
    if (digits.empty() || *end != '\0' || parsed < 2 || parsed > kMaxSize) {
      throw InputError("texture '" + spec + "': width must be an integer in [2, 16384]");
    }
    width = static_cast<int>(parsed);
  }
  const auto& names = builtinTextureNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    throw InputError("texture '" + spec + "': unknown builtin texture '" + name +
                     "' (valid: " + validNames() + ")");
  }

  std::filesystem::path dir = cacheDirectory();
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError("texture '" + spec + "': cannot create cache " + dir.string() + ": " + ec.message());
  std::filesystem::path file = std::filesystem::absolute(
      dir / (name + "-" + std::to_string(width) + "-v" + std::to_string(kContentVersion) + ".exr"));
  if (!std::filesystem::exists(file)) {
    writeImage(file.string(), makeTexture(name, width, width / 2),
               {{"penumbra:texture", spec}, {"penumbra:texture_version", std::to_string(kContentVersion)}});
  }
  return file.string();
}

}  // namespace penumbra
