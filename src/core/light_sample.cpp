// The light interface's dispatchers: each function calls its answer in the light's
// type (core/lights/, through core/light_types.h), and the defaults types leave out.
#include "core/light_sample.h"
#include "core/rng.h"
#include "core/sampling.h"

namespace penumbra {

void LightDefaults::prepare(const Light&, const Vec3&, LightSampler&) {}
bool LightDefaults::irradiance(const LightSampler&, const Vec3&, const Vec3&, Color&) { return false; }
float LightDefaults::area(const Light&) { return 0.0f; }
Color LightDefaults::power(const Light& light, const SceneSphere&) {
  return light.radiance() * (kPi * lightArea(light));  // a Lambertian emitter: pi A L
}
float LightDefaults::classicWeight(const Light& light) { return luminance(light.radiance()) * lightArea(light) * 0.25f; }
Color LightDefaults::classicPower(const Light& light, const SceneSphere& bounds, float count) {
  return lightPower(light, bounds) * (1.0f / count);
}
int LightDefaults::startNumbers(const Light&) { return 4; }
Vec3 LightDefaults::photonOrigin(const Light&, const PhotonRay& r, const SceneSphere&) {
  return offsetRayOrigin(r.origin, r.normal, r.error, r.dir);
}

EmitterShape LightDefaults::emitter(const Light&) { return {}; }
size_t LightDefaults::sampleTable(const Light&) { return 0; }

EmitterShape emitterOf(const Light& light) {
  return dispatchLight(light.type, [&](auto t) { return decltype(t)::emitter(light); });
}

size_t lightSampleTable(const Light& light) {
  return dispatchLight(light.type, [&](auto t) { return decltype(t)::sampleTable(light); });
}

LightSampler prepareLight(const Light& light, const Vec3& p) {
  LightSampler s;
  s.light = &light;
  s.p = p;
  dispatchLight(light.type, [&](auto t) { decltype(t)::prepare(light, p, s); });
  return s;
}

LightIncidence sampleLight(const LightSampler& s, float u1, float u2) {
  return dispatchLight(s.light->type, [&](auto t) { return decltype(t)::sample(s, u1, u2); });
}

bool unoccludedIrradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E) {
  E = Color(0.0f);
  return dispatchLight(s.light->type, [&](auto t) { return decltype(t)::irradiance(s, n, ng, E); });
}

float lightArea(const Light& light) {
  return dispatchLight(light.type, [&](auto t) { return decltype(t)::area(light); });
}

Color lightPower(const Light& light, const SceneSphere& bounds) {
  return dispatchLight(light.type, [&](auto t) { return decltype(t)::power(light, bounds); });
}

PhotonRay sampleLightPhoton(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4) {
  return dispatchLight(light.type, [&](auto t) { return decltype(t)::photon(light, bounds, u1, u2, u3, u4); });
}

float classicPhotonWeight(const Light& light) {
  return dispatchLight(light.type, [&](auto t) { return decltype(t)::classicWeight(light); });
}

Vec3 photonOrigin(const Light& light, const PhotonRay& r, const SceneSphere& bounds) {
  return dispatchLight(light.type, [&](auto t) { return decltype(t)::photonOrigin(light, r, bounds); });
}

PhotonRay emitterPhoton(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4) {
  PhotonRay r = sampleLightPhoton(light, bounds, u1, u2, u3, u4);
  r.origin = photonOrigin(light, r, bounds);
  return r;
}

int photonStartNumbers(const Light& light) {
  return dispatchLight(light.type, [&](auto t) { return decltype(t)::startNumbers(light); });
}

// The rng's draws stay in order (u1, u2, then u3, u4 only for a light that reads them),
// so every stream emits the photons it always did.
PhotonRay classicPhotonStart(const Light& light, const SceneSphere& bounds, Rng& rng) {
  const float u1 = rng.uniform(), u2 = rng.uniform();
  if (photonStartNumbers(light) == 2) return emitterPhoton(light, bounds, u1, u2, 0.0f, 0.0f);
  const float u3 = rng.uniform(), u4 = rng.uniform();
  return emitterPhoton(light, bounds, u1, u2, u3, u4);
}

PhotonRay shadowPhotonStart(const Light& light, const SceneSphere& bounds, const Kronecker4& starts, uint64_t i,
                            Rng& rng) {
  if (photonStartNumbers(light) == 2) return classicPhotonStart(light, bounds, rng);
  return emitterPhoton(light, bounds, starts(i, 0), starts(i, 1), starts(i, 2), starts(i, 3));
}

Color classicPhotonPower(const Light& light, const SceneSphere& bounds, float count) {
  return dispatchLight(light.type, [&](auto t) { return decltype(t)::classicPower(light, bounds, count); });
}

}  // namespace penumbra
