// The light interface: incident light at a point, emitted photons, total power,
// delta-ness; dispatched on Light::type. Units: a point light's colour x intensity
// is its radiant intensity (W/sr), a directional light's is its irradiance (W/m^2).
#pragma once
#include "core/scene.h"

namespace penumbra {

// A sphere enclosing the scene: directional lights emit photons from a disc of
// its radius, and their total power is irradiance x that disc's area.
struct SceneSphere {
  Vec3 center{0.0f};
  float radius = 1.0f;
};

// Light arriving at a point from one light (one sample of it, for area lights).
// The reflected radiance is evaluateBsdf(wo, wi) * radiance when unoccluded.
struct LightIncidence {
  Vec3 wi{0.0f};          // unit, towards the light
  float distance = kInf;  // to the light's sample point; kInf for directional
  Color radiance{0.0f};   // I / d^2 for a point light, E for a directional one
  bool valid = false;
};

LightIncidence incidentLight(const Light& light, const Vec3& p);

// Total emitted flux, per channel: 4 pi I for a point light, E pi R^2 for a
// directional light over the scene's bounding disc.
Color lightPower(const Light& light, const SceneSphere& bounds);

bool isDeltaLight(const Light& light);

// Where and which way one emitted photon starts, from two (point) or four
// (directional) uniform numbers; every photon of a light carries power / count.
struct PhotonRay {
  Vec3 origin{0.0f};
  Vec3 dir{0.0f, 0.0f, -1.0f};
};
PhotonRay sampleLightPhoton(const Light& light, const SceneSphere& bounds, float u1, float u2,
                            float u3, float u4);

}  // namespace penumbra
