// The environment light: a constant sky or a lat-long map, its luminance
// distribution, pdfs in solid angle and photons from a disc over the scene.
#include "core/lights/environment_map.h"
#include "core/sampling.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

// A normalised CDF of `weights` into cdf[0 .. n] (cdf[n] = 1); all-zero weights give
// a uniform CDF so a search still lands somewhere, though nothing is ever drawn there.
double buildCdf(const float* weights, int n, float* cdf) {
  double sum = 0.0;
  cdf[0] = 0.0f;
  for (int k = 0; k < n; ++k) sum += weights[k];
  double run = 0.0;
  for (int k = 0; k < n; ++k) {
    run += weights[k];
    cdf[k + 1] = sum > 0.0 ? static_cast<float>(run / sum) : static_cast<float>(k + 1) / static_cast<float>(n);
  }
  cdf[n] = 1.0f;
  return sum;
}

// The interval of cdf[0 .. n] holding u (never one of zero width) and u's place in it.
int pickInterval(const float* cdf, int n, float u, float& frac) {
  const int k = static_cast<int>(std::upper_bound(cdf, cdf + n + 1, u) - cdf) - 1;
  const int i = std::clamp(k, 0, n - 1);
  const float width = cdf[i + 1] - cdf[i];
  frac = width > 0.0f ? std::clamp((u - cdf[i]) / width, 0.0f, 1.0f) : 0.5f;
  return i;
}

Vec3 direction(float theta, float phi) {
  const float st = std::sin(theta);
  return {-st * std::sin(phi), std::cos(theta), st * std::cos(phi)};
}

// Row and column of the pixel a unit direction falls in, and its sin(theta).
struct MapPixel {
  int row = 0, col = 0;
  float sinTheta = 0.0f;
};

MapPixel pixelOf(const EnvironmentMap& map, const Vec3& wi) {
  MapPixel p;
  const float y = std::clamp(wi.y, -1.0f, 1.0f);
  const float theta = std::acos(y);
  float phi = std::atan2(-wi.x, wi.z) + map.rotation;
  phi -= 2.0f * kPi * std::floor(phi / (2.0f * kPi));
  p.row = std::clamp(static_cast<int>(theta / kPi * static_cast<float>(map.height)), 0, map.height - 1);
  p.col = std::clamp(static_cast<int>(phi / (2.0f * kPi) * static_cast<float>(map.width)), 0, map.width - 1);
  // From x and z, not 1 - y^2: that cancels near the poles, where the pdf divides by it.
  p.sinTheta = std::sqrt(wi.x * wi.x + wi.z * wi.z);
  return p;
}

float pixelWeight(const EnvironmentMap& map, int row, int col) {
  const float sinTheta = std::sin((static_cast<float>(row) + 0.5f) * kPi / static_cast<float>(map.height));
  return std::max(0.0f, luminance(map.texels[static_cast<size_t>(row) * map.width + col])) * sinTheta;
}

// pdf(u, v) / (2 pi^2 sin theta): the (u, v) density turned into one per steradian.
float mapPdf(const EnvironmentMap& map, int row, int col, float sinTheta) {
  if (!(map.weightMean > 0.0) || !(sinTheta > 0.0f)) return 0.0f;
  const double uv = pixelWeight(map, row, col) / map.weightMean;
  return static_cast<float>(uv / (2.0 * kPi * kPi * sinTheta));
}

}  // namespace

double environmentMapBytes(int width, int height) {
  const double w = width, h = height;
  return w * h * sizeof(Color) + (h * (w + 1) + (h + 1)) * sizeof(float);
}

std::shared_ptr<const EnvironmentMap> makeEnvironmentMap(int width, int height, std::vector<Color> texels,
                                                         float rotationDegrees) {
  auto map = std::make_shared<EnvironmentMap>();
  map->width = width;
  map->height = height;
  map->texels = std::move(texels);
  // Right-handed about +y: a positive angle turns the map's +z towards +x.
  map->rotation = rotationDegrees * kPi / 180.0f;
  map->marginal.assign(static_cast<size_t>(height) + 1, 0.0f);
  map->conditional.assign(static_cast<size_t>(height) * (width + 1), 0.0f);
  std::vector<float> rowWeights(static_cast<size_t>(height)), weights(static_cast<size_t>(width));
  glm::dvec3 integral(0.0);
  double total = 0.0;
  for (int i = 0; i < height; ++i) {
    // The solid angle of one pixel of this row, exactly: (2 pi / W)(cos top - cos bottom).
    const double top = M_PI * i / height, bottom = M_PI * (i + 1) / height;
    const double pixelSolidAngle = 2.0 * M_PI / width * (std::cos(top) - std::cos(bottom));
    for (int j = 0; j < width; ++j) {
      weights[static_cast<size_t>(j)] = pixelWeight(*map, i, j);
      integral += glm::dvec3(map->texels[static_cast<size_t>(i) * width + j]) * pixelSolidAngle;
    }
    rowWeights[static_cast<size_t>(i)] = static_cast<float>(
        buildCdf(weights.data(), width, &map->conditional[static_cast<size_t>(i) * (width + 1)]));
    total += rowWeights[static_cast<size_t>(i)];
  }
  buildCdf(rowWeights.data(), height, map->marginal.data());
  map->weightMean = total / (static_cast<double>(width) * height);
  map->integral = Color(integral);
  return map;
}

Light makeEnvironmentLight(const Color& color, float intensity, std::shared_ptr<const EnvironmentMap> map) {
  Light light;
  light.type = LightType::Environment;
  light.color = color;
  light.intensity = intensity;
  light.environment = std::move(map);
  return light;
}

Color environmentRadiance(const Light& light, const Vec3& wi) {
  const EnvironmentMap* map = light.environment.get();
  if (!map) return light.radiance();
  const MapPixel p = pixelOf(*map, wi);
  return map->texels[static_cast<size_t>(p.row) * map->width + p.col] * light.radiance();
}

namespace {
// One luminance-drawn direction of a map, with the texel it came from (before the
// light's colour x intensity).
EnvironmentSample sampleMap(const EnvironmentMap& map, float u1, float u2, Color& texel) {
  EnvironmentSample e;
  if (!(map.weightMean > 0.0)) return e;  // a black map: nothing to draw
  float fv, fu;
  const int row = pickInterval(map.marginal.data(), map.height, u1, fv);
  const int col = pickInterval(&map.conditional[static_cast<size_t>(row) * (map.width + 1)], map.width, u2, fu);
  const float theta = (static_cast<float>(row) + fv) * kPi / static_cast<float>(map.height);
  const float phi = (static_cast<float>(col) + fu) * 2.0f * kPi / static_cast<float>(map.width) - map.rotation;
  e.wi = direction(theta, phi);
  e.pdf = mapPdf(map, row, col, std::sin(theta));
  texel = map.texels[static_cast<size_t>(row) * map.width + col];
  e.valid = e.pdf > 0.0f && std::isfinite(e.pdf);
  return e;
}
}  // namespace

EnvironmentSample sampleEnvironmentSphere(const Light& light, float u1, float u2) {
  const EnvironmentMap* map = light.environment.get();
  if (map) {
    Color texel(0.0f);
    EnvironmentSample e = sampleMap(*map, u1, u2, texel);
    e.radiance = texel * light.radiance();
    return e;
  }
  EnvironmentSample e;
  e.wi = uniformSphere(u1, u2);
  e.pdf = 1.0f / (4.0f * kPi);
  e.radiance = light.radiance();
  e.valid = true;
  return e;
}

EnvironmentSample sampleEnvironment(const Light& light, const Vec3& n, float u1, float u2) {
  if (light.environment) return sampleEnvironmentSphere(light, u1, u2);
  EnvironmentSample e;
  e.wi = toWorld(cosineHemisphere(u1, u2), n);
  e.pdf = std::max(0.0f, glm::dot(n, e.wi)) / kPi;
  e.radiance = light.radiance();
  e.valid = e.pdf > 0.0f;
  return e;
}

float environmentPdf(const Light& light, const Vec3& n, const Vec3& wi) {
  const EnvironmentMap* map = light.environment.get();
  if (!map) return std::max(0.0f, glm::dot(n, wi)) / kPi;
  const MapPixel p = pixelOf(*map, wi);
  return mapPdf(*map, p.row, p.col, p.sinTheta);
}

Color environmentPower(const Light& light, const SceneSphere& bounds) {
  const Color integral = light.environment ? light.environment->integral : Color(4.0f * kPi);
  return light.radiance() * integral * (kPi * bounds.radius * bounds.radius);
}

PhotonRay environmentPhoton(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3,
                            float u4) {
  PhotonRay r;
  const EnvironmentMap* map = light.environment.get();
  Color texel(1.0f);
  const EnvironmentSample e = map ? sampleMap(*map, u1, u2, texel) : sampleEnvironmentSphere(light, u1, u2);
  if (!e.valid) {
    r.weight = Color(0.0f);
    return r;
  }
  r.dir = -e.wi;
  const float rad = bounds.radius * std::sqrt(u3), phi = 2.0f * kPi * u4;
  Vec3 t, b;
  orthonormalBasis(e.wi, t, b);
  r.origin = bounds.center + e.wi * (SceneSphere::kSkyStart * bounds.radius) + rad * (std::cos(phi) * t + std::sin(phi) * b);
  if (map) {
    // L(w) / (pdf(w) x integral of L), per channel; a constant sky's is 1 exactly.
    for (int c = 0; c < 3; ++c) {
      r.weight[c] = map->integral[c] > 0.0f ? texel[c] / (e.pdf * map->integral[c]) : 0.0f;
    }
  }
  return r;
}

}  // namespace penumbra
