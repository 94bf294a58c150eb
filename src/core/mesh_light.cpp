// Mesh lights (emissive triangle meshes): construction, sampling by area, closed-form
// irradiance, photon emission; and the clipped Lambert polygon formula.
#include "core/mesh_light.h"
#include "core/sampling.h"
#include <algorithm>

namespace penumbra {

namespace {

// The triangle u falls in, by cumulative area, and u's remainder within it in [0, 1).
size_t pickTriangle(const Light& light, float u, float& rest) {
  const std::vector<float>& cdf = light.areaCdf;
  const float target = u * cdf.back();
  size_t i = static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin());
  i = std::min(i, cdf.size() - 1);
  const float lo = i > 0 ? cdf[i - 1] : 0.0f;
  rest = std::clamp((target - lo) / (cdf[i] - lo), 0.0f, 0x1.fffffep-1f);
  return i;
}

// A point uniform over triangle i (the square-root warp) and its unit normal.
Vec3 pointOn(const Light& light, size_t i, float u1, float u2, Vec3& normal) {
  const Vec3* t = &light.triangles[3 * i];
  const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
  normal = unitCross(e1, e2);
  const float su = std::sqrt(u1);
  return t[0] + (su * (1.0f - u2)) * e1 + (su * u2) * e2;
}

}  // namespace

Light makeMeshLight(const std::vector<Vec3>& triangles, const Color& radiance, int material) {
  Light light;
  light.type = LightType::Mesh;
  light.color = radiance;
  light.intensity = 1.0f;
  light.material = material;
  float total = 0.0f, reach = 0.0f;
  for (size_t i = 0; i + 2 < triangles.size(); i += 3) {
    const Vec3 a = triangles[i], e1 = triangles[i + 1] - a, e2 = triangles[i + 2] - a;
    const float area = 0.5f * glm::length(glm::cross(e1, e2));
    if (!(area > 0.0f) || !std::isfinite(area)) continue;
    light.triangles.insert(light.triangles.end(), {a, triangles[i + 1], triangles[i + 2]});
    total += area;
    light.areaCdf.push_back(total);
    // Rounding of a + s e1 + t e2, as for a quad: a few ulps of the largest terms.
    reach = std::max(reach, maxComponent(glm::abs(a)) + maxComponent(glm::abs(e1)) +
                                maxComponent(glm::abs(e2)));
  }
  light.pointError = gammaBound(6) * reach;
  return light;
}

LightIncidence sampleMeshLight(const LightSampler& s, float u1, float u2) {
  const Light& light = *s.light;
  LightIncidence in;
  if (light.areaCdf.empty()) return in;
  float rest;
  const size_t i = pickTriangle(light, u1, rest);
  Vec3 normal;
  const Vec3 y = pointOn(light, i, rest, u2, normal);
  const Vec3 d = y - s.p;
  const float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return in;
  in.distance = std::sqrt(d2);
  in.wi = d / in.distance;
  const float cosLight = -glm::dot(normal, in.wi);
  if (cosLight <= 0.0f) return in;  // behind this triangle's emitting side
  in.radiance = light.radiance() * (cosLight * s.area / d2);
  // Stop short of the emitter's rounding band, as a quad light's shadow rays do.
  const float band = 2.0f * light.pointError;
  in.point = y;
  in.margin = std::min(0.5f * in.distance, in.distance * kShadowRayShortening + band / cosLight);
  in.valid = true;
  return in;
}

bool meshLightIrradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E) {
  const Light& light = *s.light;
  E = Color(0.0f);
  const size_t count = light.areaCdf.size();
  if (count > kMeshClosedFormTriangles) return false;
  float sum = 0.0f;
  for (size_t i = 0; i < count; ++i) {
    const Vec3* t = &light.triangles[3 * i];
    const Vec3 normal = glm::cross(t[1] - t[0], t[2] - t[0]);
    if (glm::dot(normal, s.p - t[0]) <= 0.0f) continue;  // behind its emitting side
    const Vec3 corners[3] = {t[0] - s.p, t[1] - s.p, t[2] - s.p};
    sum += clippedPolygonFactor(corners, 3, n, ng);
  }
  E = light.radiance() * sum;
  return true;
}

PhotonRay meshLightPhoton(const Light& light, float u1, float u2, float u3, float u4) {
  PhotonRay r;
  if (light.areaCdf.empty()) return r;
  float rest;
  const size_t i = pickTriangle(light, u1, rest);
  Vec3 n;
  r.origin = pointOn(light, i, rest, u2, n);
  r.dir = toWorld(cosineHemisphere(u3, u4), n);
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
