// Mesh lights (emissive triangle meshes): construction, and MeshLight's answers
// (core/lights/mesh_light.h): sampling by area, closed-form irradiance, photon
// emission; and the clipped Lambert polygon formula.
#include "core/lights/emissive_mesh.h"
#include "core/emission_map.h"
#include "core/sampling.h"
#include <algorithm>

namespace penumbra {

namespace {

// The triangle u falls in, by the cumulative weights `cdf` (areas, or a textured
// light's area x luminance), and u's remainder within it in [0, 1).
size_t pickTriangle(const std::vector<float>& cdf, float u, float& rest) {
  const float target = u * cdf.back();
  size_t i = static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin());
  i = std::min(i, cdf.size() - 1);
  const float lo = i > 0 ? cdf[i - 1] : 0.0f;
  rest = std::clamp((target - lo) / (cdf[i] - lo), 0.0f, 0x1.fffffep-1f);
  return i;
}

const std::vector<float>& drawCdf(const Light& light) {
  return light.emission ? light.emission->weightCdf : light.areaCdf;
}

// A point uniform over triangle i (the square-root warp), its unit normal, and its
// barycentric weights of corners 1 and 2.
Vec3 pointOn(const Light& light, size_t i, float u1, float u2, Vec3& normal, Vec2& bary) {
  const Vec3* t = &light.triangles[3 * i];
  const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
  normal = unitCross(e1, e2);
  const float su = std::sqrt(u1);
  bary = Vec2(su * (1.0f - u2), su * u2);
  return t[0] + bary.x * e1 + bary.y * e2;
}

// A textured light's texel at a point of triangle i, over the triangle's density:
// the radiance factor of a sample drawn by area x density (1 untextured).
Color textureOverDensity(const Light& light, size_t i, Vec2 bary) {
  if (!light.emission) return Color(1.0f);
  const MeshEmission& e = *light.emission;
  const Vec2* uv = &e.uvs[3 * i];
  const Vec2 at = uv[0] + bary.x * (uv[1] - uv[0]) + bary.y * (uv[2] - uv[0]);
  return e.map.at(at) * (e.weightCdf.back() / e.density[i]);
}

}  // namespace

Light makeMeshLight(const std::vector<Vec3>& triangles, const Color& radiance, int material,
                    const std::vector<Vec2>& uvs, const EmissionMap* map) {
  Light light;
  light.type = LightType::Mesh;
  light.color = radiance;
  light.intensity = 1.0f;
  light.material = material;
  float total = 0.0f, reach = 0.0f;
  std::vector<Vec2> kept;  // the uvs of the triangles kept
  for (size_t i = 0; i + 2 < triangles.size(); i += 3) {
    const Vec3 a = triangles[i], e1 = triangles[i + 1] - a, e2 = triangles[i + 2] - a;
    const float area = 0.5f * glm::length(glm::cross(e1, e2));
    if (!(area > 0.0f) || !std::isfinite(area)) continue;
    light.triangles.insert(light.triangles.end(), {a, triangles[i + 1], triangles[i + 2]});
    if (map) kept.insert(kept.end(), {uvs[i], uvs[i + 1], uvs[i + 2]});
    total += area;
    light.areaCdf.push_back(total);
    // Rounding of a + s e1 + t e2, as for a quad: a few ulps of the largest terms.
    reach = std::max(reach, maxComponent(glm::abs(a)) + maxComponent(glm::abs(e1)) +
                                maxComponent(glm::abs(e2)));
  }
  light.pointError = gammaBound(6) * reach;
  if (map && !light.areaCdf.empty()) {
    light.emission = std::make_shared<const MeshEmission>(makeMeshEmission(*map, light.triangles, std::move(kept)));
  }
  return light;
}

float meshLightPowerFactor(const Light& light) {
  const float perSide = light.emission ? light.emission->weightCdf.back() : meshLightArea(light);
  return light.twoSided ? 2.0f * perSide : perSide;
}

void MeshLight::prepare(const Light& light, const Vec3&, LightSampler& s) { s.area = meshLightArea(light); }

float MeshLight::area(const Light& light) { return meshLightArea(light); }

Color MeshLight::power(const Light& light, const SceneSphere&) {
  return light.radiance() * (kPi * meshLightPowerFactor(light));
}

float MeshLight::classicWeight(const Light& light) {
  return luminance(light.radiance()) * meshLightPowerFactor(light) * 0.25f;
}

size_t MeshLight::sampleTable(const Light& light) { return light.areaCdf.size(); }

LightIncidence MeshLight::sample(const LightSampler& s, float u1, float u2) {
  const Light& light = *s.light;
  LightIncidence in;
  if (light.areaCdf.empty()) return in;
  float rest;
  const size_t i = pickTriangle(drawCdf(light), u1, rest);
  Vec3 normal;
  Vec2 bary;
  const Vec3 y = pointOn(light, i, rest, u2, normal, bary);
  const Vec3 d = y - s.p;
  const float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return in;
  in.distance = std::sqrt(d2);
  in.wi = d / in.distance;
  float cosLight = -glm::dot(normal, in.wi);
  if (light.twoSided) cosLight = std::abs(cosLight);
  if (cosLight <= 0.0f) return in;  // behind this triangle's emitting side
  // 1 / pdf_A is the area (uniform) or W / density (textured: in textureOverDensity).
  const float inversePdf = light.emission ? 1.0f : s.area;
  in.radiance = light.radiance() * textureOverDensity(light, i, bary) * (cosLight * inversePdf / d2);
  // Stop short of the emitter's rounding band, as a quad light's shadow rays do.
  const float band = 2.0f * light.pointError;
  in.point = y;
  in.margin = std::min(0.5f * in.distance, in.distance * kShadowRayShortening + band / cosLight);
  in.valid = true;
  return in;
}

bool MeshLight::irradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E) {
  const Light& light = *s.light;
  E = Color(0.0f);
  const size_t count = light.areaCdf.size();
  if (count > kMeshClosedFormTriangles || light.emission) return false;
  float sum = 0.0f;
  for (size_t i = 0; i < count; ++i) {
    const Vec3* t = &light.triangles[3 * i];
    const Vec3 normal = glm::cross(t[1] - t[0], t[2] - t[0]);
    if (!light.twoSided && glm::dot(normal, s.p - t[0]) <= 0.0f) continue;  // behind its emitting side
    const Vec3 corners[3] = {t[0] - s.p, t[1] - s.p, t[2] - s.p};
    sum += clippedPolygonFactor(corners, 3, n, ng);
  }
  E = light.radiance() * sum;
  return true;
}

PhotonRay MeshLight::photon(const Light& light, const SceneSphere&, float u1, float u2, float u3, float u4) {
  PhotonRay r;
  if (light.areaCdf.empty()) return r;
  float rest;
  const size_t i = pickTriangle(drawCdf(light), u1, rest);
  // A two-sided light picks its side from one more bit of u1's remainder.
  const bool back = light.twoSided && rest >= 0.5f;
  if (light.twoSided) rest = std::min(2.0f * rest - (back ? 1.0f : 0.0f), 0x1.fffffep-1f);
  Vec3 n;
  Vec2 bary;
  r.origin = pointOn(light, i, rest, u2, n, bary);
  if (back) n = -n;
  r.dir = toWorld(cosineHemisphere(u3, u4), n);
  // Power is pi W L over the photons: a textured one carries its texel over density.
  if (light.emission) r.weight = textureOverDensity(light, i, bary) * (1.0f / light.emission->weightCdf.back());
  r.normal = n;
  r.error = light.pointError;
  return r;
}

float clippedPolygonFactor(const Vec3* corners, int m, const Vec3& n, const Vec3& ng) {
  Vec3 poly[8];
  std::copy(corners, corners + m, poly);
  for (const Vec3& plane : {n, ng}) {
    Vec3 clipped[8];
    int k = 0;
    for (int i = 0; i < m; ++i) {
      const Vec3& a = poly[i];
      const Vec3& b = poly[(i + 1) % m];
      const float da = glm::dot(plane, a), db = glm::dot(plane, b);
      if (da >= 0.0f) clipped[k++] = a;
      if ((da >= 0.0f) != (db >= 0.0f)) clipped[k++] = a + (b - a) * (da / (da - db));
    }
    m = k;
    std::copy(clipped, clipped + k, poly);
    if (m < 3) return 0.0f;
  }
  // Lambert: E = L / 2 |sum_i theta_i (n . unit(r_i x r_i+1))|, theta_i the angle of
  // edge i, by atan2 (acos loses the small angles of a small or distant polygon).
  Vec3 unit[8];
  for (int i = 0; i < m; ++i) unit[i] = glm::normalize(poly[i]);
  float sum = 0.0f;
  for (int i = 0; i < m; ++i) {
    const Vec3 c = glm::cross(unit[i], unit[(i + 1) % m]);
    const float len = glm::length(c);
    if (!(len > 0.0f)) continue;
    sum += std::atan2(len, glm::dot(unit[i], unit[(i + 1) % m])) * glm::dot(n, c / len);
  }
  return 0.5f * std::abs(sum);
}

}  // namespace penumbra
