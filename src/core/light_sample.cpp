// Point and directional lights behind the light interface.
#include "core/light_sample.h"
#include "core/sampling.h"

namespace penumbra {

LightIncidence incidentLight(const Light& light, const Vec3& p) {
  LightIncidence in;
  if (light.type == LightType::Point) {
    Vec3 d = light.position - p;
    float d2 = glm::dot(d, d);
    if (!(d2 > 0.0f) || !std::isfinite(d2)) return in;
    in.distance = std::sqrt(d2);
    in.wi = d / in.distance;
    in.radiance = light.radiance() * (1.0f / d2);  // as the Whitted tracer always did: bit-identical images
  } else {
    in.wi = -light.direction;
    in.radiance = light.radiance();
  }
  in.valid = true;
  return in;
}

Color lightPower(const Light& light, const SceneSphere& bounds) {
  if (light.type == LightType::Point) return light.radiance() * (4.0f * kPi);
  return light.radiance() * (kPi * bounds.radius * bounds.radius);
}

bool isDeltaLight(const Light&) { return true; }  // point and directional; area lights are not

PhotonRay sampleLightPhoton(const Light& light, const SceneSphere& bounds, float u1, float u2,
                            float u3, float u4) {
  PhotonRay r;
  if (light.type == LightType::Point) {
    r.origin = light.position;
    r.dir = uniformSphere(u1, u2);
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

}  // namespace penumbra
