// The quad light: set-up per shading point, uniform samples by area, Lambert's
// closed form, area, photons and its surface.
#include "core/light_sample.h"
#include "core/light_strata.h"
#include "core/lights/emissive_mesh.h"
#include "core/sampling.h"
#include <algorithm>

namespace penumbra {

namespace {
// Rounding of position + u e1 + v e2: a few ulps of the largest terms.
float quadPointError(const Light& light) {
  return gammaBound(6) * (maxComponent(glm::abs(light.position)) + maxComponent(glm::abs(light.edge1)) +
                          maxComponent(glm::abs(light.edge2)));
}
}  // namespace

void QuadLight::prepare(const Light& light, const Vec3&, LightSampler& s) {
  s.normal = unitCross(light.edge1, light.edge2);
  s.area = area(light);
  s.band = 2.0f * quadPointError(light);
}

LightIncidence QuadLight::sample(const LightSampler& s, float u1, float u2) {
  const Light& light = *s.light;
  return planarIncidence(s, light.position + u1 * light.edge1 + u2 * light.edge2);
}

// Defined beside its first user, so the quad's sample inlines it.
LightIncidence planarIncidence(const LightSampler& s, const Vec3& y) {
  const Light& light = *s.light;
  LightIncidence in;
  const Vec3 d = y - s.p;
  const float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return in;
  in.distance = std::sqrt(d2);
  in.wi = d / in.distance;
  const float cosLight = -glm::dot(s.normal, in.wi);
  if (cosLight <= 0.0f) return in;  // behind the emitting side
  in.radiance = light.radiance() * (cosLight * s.area / d2);
  // The emitter's own triangles lie within rounding of y's plane: stop before that
  // band, measured along the ray (longer at grazing angles), but never before half-way.
  in.point = y;
  in.margin = std::min(0.5f * in.distance, in.distance * kShadowRayShortening + s.band / cosLight);
  in.valid = true;
  return in;
}

bool QuadLight::irradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E) {
  const Light& light = *s.light;
  if (glm::dot(s.normal, s.p - light.position) <= 0.0f) return true;  // behind its emitting side
  // The quad's corners relative to p, clipped to the half-spaces above both the
  // shading and the geometric normal (samples below either are rejected too).
  const Vec3 corners[4] = {light.position - s.p, light.position + light.edge1 - s.p,
                           light.position + light.edge1 + light.edge2 - s.p,
                           light.position + light.edge2 - s.p};
  const float factor = clippedPolygonFactor(corners, 4, n, ng);
  if (factor > 0.0f) E = light.radiance() * factor;
  return true;
}

float QuadLight::area(const Light& light) {
  const Vec3 c = glm::cross(light.edge1, light.edge2);
  const float area = glm::length(c);
  return std::isfinite(area) ? area
                             : static_cast<float>(glm::length(glm::cross(glm::dvec3(light.edge1), glm::dvec3(light.edge2))));
}

EmitterShape QuadLight::emitter(const Light& light) {
  EmitterShape e;
  e.mesh = makeQuad(light.position, light.edge1, light.edge2);
  return e;
}

TriangleMesh makeQuad(const Vec3& corner, const Vec3& edge1, const Vec3& edge2, int material) {
  TriangleMesh mesh;
  mesh.name = "quad";
  mesh.material = material;
  mesh.positions = {corner, corner + edge1, corner + edge1 + edge2, corner + edge2};
  // Triangle (0,1,2) has edges e1 and e1+e2, whose cross product is cross(e1, e2).
  Vec3 normal = unitCross(edge1, edge2);
  mesh.normals.assign(4, normal);
  mesh.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  return mesh;
}

PhotonRay QuadLight::photon(const Light& light, const SceneSphere&, float u1, float u2, float u3, float u4) {
  PhotonRay r;
  r.origin = light.position + u1 * light.edge1 + u2 * light.edge2;
  r.normal = unitCross(light.edge1, light.edge2);
  r.error = quadPointError(light);
  r.stratum = stratumOf(u1, u2);
  r.dir = toWorld(cosineHemisphere(u3, u4), r.normal);
  return r;
}

}  // namespace penumbra
