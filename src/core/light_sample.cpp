// Point, directional, quad, sphere and mesh lights behind the light interface.
#include "core/light_sample.h"
#include "core/environment.h"
#include "core/light_strata.h"
#include "core/mesh_light.h"
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

LightSampler prepareLight(const Light& light, const Vec3& p) {
  LightSampler s;
  s.light = &light;
  s.p = p;
  if (light.type == LightType::Quad) {
    s.normal = unitCross(light.edge1, light.edge2);
    s.area = lightArea(light);
    s.band = 2.0f * quadPointError(light);
  } else if (light.type == LightType::Mesh) {
    s.area = meshLightArea(light);
  } else if (light.type == LightType::Sphere) {
    const Vec3 toCentre = light.position - p;
    s.dc2 = glm::dot(toCentre, toCentre);
    s.r2 = light.radius * light.radius;
    s.outside = s.dc2 > s.r2 && std::isfinite(s.dc2);
    if (s.outside) {
      s.dc = std::sqrt(s.dc2);
      s.w = toCentre / s.dc;
      // 1 - cos(theta_max) as sin^2 / (1 + cos): the subtraction would cancel to 0
      // for a small or distant sphere (r / d below ~2e-4 in float).
      const float sin2Max = s.r2 / s.dc2;
      s.oneMinusCosMax = sin2Max / (1.0f + std::sqrt(std::max(0.0f, 1.0f - sin2Max)));
      orthonormalBasis(s.w, s.t, s.b);
    }
  }
  return s;
}

namespace {
LightIncidence sampleQuad(const LightSampler& s, float u1, float u2) {
  const Light& light = *s.light;
  LightIncidence in;
  const Vec3 y = light.position + u1 * light.edge1 + u2 * light.edge2;
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

LightIncidence sampleSphere(const LightSampler& s, float u1, float u2) {
  LightIncidence in;
  if (!s.outside) return in;  // inside (or on) the sphere
  // Uniform over the cone: 1 - cos(theta) uniform in [0, 1 - cos(theta_max)].
  const float t = u1 * s.oneMinusCosMax;
  const float cosTheta = 1.0f - t, sinTheta = std::sqrt(std::max(0.0f, t * (2.0f - t)));
  const float phi = 2.0f * kPi * u2;
  in.wi = cosTheta * s.w + sinTheta * (std::cos(phi) * s.t + std::sin(phi) * s.b);
  // The near intersection along wi: dc cos - sqrt(r^2 - dc^2 sin^2), never < 0.
  const float disc = std::max(0.0f, s.r2 - s.dc2 * sinTheta * sinTheta);
  in.distance = std::max(0.0f, s.dc * cosTheta - std::sqrt(disc));
  in.radiance = s.light->radiance() * (2.0f * kPi * s.oneMinusCosMax);
  // Shadow rays to a sphere light identify the emitter they meet: no margin needed.
  in.point = s.p + in.distance * in.wi;
  in.margin = -in.distance * kShadowRayShortening;
  in.valid = in.distance > 0.0f;
  return in;
}
}  // namespace

LightIncidence sampleLight(const LightSampler& s, float u1, float u2) {
  const Light& light = *s.light;
  LightIncidence in;
  switch (light.type) {
    case LightType::Point: {
      Vec3 d = light.position - s.p;
      float d2 = glm::dot(d, d);
      if (!(d2 > 0.0f) || !std::isfinite(d2)) return in;
      in.distance = std::sqrt(d2);
      in.wi = d / in.distance;
      in.radiance = light.radiance() * (1.0f / d2);  // as the Whitted tracer always did: bit-identical images
      if (light.isSpot()) in.radiance *= spotFalloff(light, -in.wi);
      in.point = light.position;
      in.margin = in.distance * kShadowRayShortening;
      break;
    }
    case LightType::Directional:
      in.wi = -light.direction;
      in.radiance = light.radiance();
      break;
    case LightType::Quad: return sampleQuad(s, u1, u2);
    case LightType::Sphere: return sampleSphere(s, u1, u2);
    case LightType::Mesh: return sampleMeshLight(s, u1, u2);
    case LightType::Environment: {
      // Without a normal: the map by luminance, a constant sky uniformly (the tracer
      // samples it about the normal instead, trace/environment_light.h).
      const EnvironmentSample e = sampleEnvironmentSphere(light, u1, u2);
      in.wi = e.wi;
      in.radiance = e.valid ? e.radiance / e.pdf : Color(0.0f);
      in.valid = e.valid;
      return in;
    }
  }
  in.valid = true;
  return in;
}

bool unoccludedIrradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E) {
  const Light& light = *s.light;
  E = Color(0.0f);
  if (light.type == LightType::Sphere) {
    if (!s.outside) return false;
    const float cosBeta = glm::dot(n, s.w), cosGeo = glm::dot(ng, s.w), sin2Alpha = s.r2 / s.dc2;
    // Cut by either horizon: no closed form.
    if (cosBeta <= 0.0f || cosBeta * cosBeta < sin2Alpha || cosGeo <= 0.0f || cosGeo * cosGeo < sin2Alpha)
      return false;
    E = light.radiance() * (kPi * sin2Alpha * cosBeta);
    return true;
  }
  if (light.type == LightType::Mesh) return meshLightIrradiance(s, n, ng, E);
  if (light.type != LightType::Quad) return false;
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

float lightArea(const Light& light) {
  if (light.type == LightType::Quad) {
    const Vec3 c = glm::cross(light.edge1, light.edge2);
    const float area = glm::length(c);
    return std::isfinite(area) ? area
                               : static_cast<float>(glm::length(glm::cross(glm::dvec3(light.edge1), glm::dvec3(light.edge2))));
  }
  if (light.type == LightType::Sphere) return 4.0f * kPi * light.radius * light.radius;
  if (light.type == LightType::Mesh) return meshLightArea(light);
  return 0.0f;
}

Color lightPower(const Light& light, const SceneSphere& bounds) {
  if (light.isSpot()) return light.radiance() * spotSolidAngle(light);
  if (light.type == LightType::Point) return light.radiance() * (4.0f * kPi);
  if (light.type == LightType::Directional) return light.radiance() * (kPi * bounds.radius * bounds.radius);
  if (light.type == LightType::Environment) return environmentPower(light, bounds);
  if (light.type == LightType::Mesh) return light.radiance() * (kPi * meshLightPowerFactor(light));
  return light.radiance() * (kPi * lightArea(light));  // a Lambertian emitter: pi A L
}

float spotFalloff(const Light& light, const Vec3& dir) {
  if (!light.isSpot()) return 1.0f;
  const float c = glm::dot(dir, light.direction);
  if (c >= light.spotCosInner) return 1.0f;
  if (c <= light.spotCosOuter) return 0.0f;
  const float t = (c - light.spotCosOuter) / (light.spotCosInner - light.spotCosOuter);
  return t * t;
}

void setSpotCone(Light& light, float innerAngle, float outerAngle) {
  light.spotCosOuter = std::cos(outerAngle);
  // A cone with no ramp (inner = outer) would divide by zero in the falloff.
  light.spotCosInner = std::max(std::cos(innerAngle), light.spotCosOuter + 1e-6f);
}

float spotSolidAngle(const Light& light) {
  if (!light.isSpot()) return 4.0f * kPi;
  // 2 pi [ (1 - cos_i) + the ramp's t^2 integrated over cos from cos_o to cos_i ].
  return 2.0f * kPi * ((1.0f - light.spotCosInner) + (light.spotCosInner - light.spotCosOuter) / 3.0f);
}

PhotonRay sampleLightPhoton(const Light& light, const SceneSphere& bounds, float u1, float u2,
                            float u3, float u4) {
  PhotonRay r;
  if (light.isSpot()) {
    // Uniform within the outer cone, weighted by the falloff over its mean there.
    const float cosT = 1.0f - u1 * (1.0f - light.spotCosOuter);
    const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT)), phi = 2.0f * kPi * u2;
    r.origin = light.position;
    r.dir = toWorld(Vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT), light.direction);
    r.weight = Color(spotFalloff(light, r.dir) * (2.0f * kPi * (1.0f - light.spotCosOuter)) / spotSolidAngle(light));
    return r;
  }
  if (light.type == LightType::Point) {
    r.origin = light.position;
    r.dir = uniformSphere(u1, u2);
    return r;
  }
  if (light.type == LightType::Mesh) return meshLightPhoton(light, u1, u2, u3, u4);
  if (light.type == LightType::Environment) return environmentPhoton(light, bounds, u1, u2, u3, u4);
  if (light.type == LightType::Quad || light.type == LightType::Sphere) {
    if (light.type == LightType::Quad) {
      r.origin = light.position + u1 * light.edge1 + u2 * light.edge2;
      r.normal = unitCross(light.edge1, light.edge2);
      r.error = quadPointError(light);
      r.stratum = stratumOf(u1, u2);
    } else {
      r = sphereLightStart(light, uniformSphere(u1, u2));
      r.stratum = sphereStratum(r.normal);
    }
    r.dir = toWorld(cosineHemisphere(u3, u4), r.normal);
    return r;
  }
  // Uniform over the disc that covers the scene, seen along the light's direction,
  // placed just outside the bounding sphere.
  float rad = bounds.radius * std::sqrt(u3), phi = 2.0f * kPi * u4;
  Vec3 t, b;
  orthonormalBasis(light.direction, t, b);
  r.origin = bounds.center - light.direction * (1.01f * bounds.radius) +
             rad * (std::cos(phi) * t + std::sin(phi) * b);
  r.dir = light.direction;
  return r;
}

PhotonRay sphereLightStart(const Light& light, const Vec3& n) {
  PhotonRay r;
  r.origin = light.position + light.radius * n;
  r.normal = n;
  r.error = gammaBound(5) * (maxComponent(glm::abs(light.position)) + light.radius);
  return r;
}

float classicPhotonWeight(const Light& light) {
  if (light.isSpot()) return luminance(light.radiance()) * spotSolidAngle(light) / (4.0f * kPi);
  if (light.type == LightType::Point) return luminance(light.radiance());
  if (light.type == LightType::Directional || light.type == LightType::Environment) return 0.0f;
  if (light.type == LightType::Mesh) return luminance(light.radiance()) * meshLightPowerFactor(light) * 0.25f;
  return luminance(light.radiance()) * lightArea(light) * 0.25f;
}

}  // namespace penumbra
