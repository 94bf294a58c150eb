// The light interface: incident light at a point (one sample of an area light),
// emitted photons, total power, delta-ness; each dispatched to the light's type
// (core/light_types.h, the code in core/lights/). Units: a
// point light's colour x intensity is its radiant intensity (W/sr), a directional
// light's its irradiance (W/m^2), an area or environment light's its radiance
// (W/(sr m^2)).
#pragma once
#include "core/scene.h"
#include <optional>

namespace penumbra {

class Rng;         // core/rng.h
class Kronecker4;  // core/sampling.h

// A sphere enclosing the scene: directional lights emit photons from a disc of
// its radius, and their total power is irradiance x that disc's area.
struct SceneSphere {
  Vec3 center{0.0f};
  float radius = 1.0f;
  // Photons of lights at infinity start this far out (radii), just clear of the scene.
  static constexpr float kSkyStart = 1.01f;
};

// Light arriving at a point from one light (one sample of it, for area lights).
// The reflected radiance is evaluateBsdf(wo, wi) * radiance when unoccluded.
struct LightIncidence {
  Vec3 wi{0.0f};          // unit, towards the light
  float distance = kInf;  // to the light's sample point; kInf for directional
  Vec3 point{0.0f};       // the light's sample point (delta: its position); unused for directional
  float margin = 0.0f;    // how far short of `point` a shadow ray stops: the light, not its occluders
  // I / d^2 for a point light, E for a directional one; for an area light the
  // sample's estimate L / pdf (pdf in solid angle), so that averaging
  // f cos * radiance over the samples is an unbiased estimate of reflected light.
  Color radiance{0.0f};
  bool valid = false;
};

// What sampling one light from one point needs, computed once for all its samples
// by its type's prepare: scratch a type may use as its header says.
struct LightSampler {
  const Light* light = nullptr;
  Vec3 p{0.0f};
  Vec3 normal{0.0f};  // a planar emitter's normal
  float area = 0.0f;
  float band = 0.0f;  // a planar emitter: the rounding band about its plane a shadow ray stops short of
  Vec3 w{0.0f}, t{0.0f}, b{0.0f};  // towards the centre, and a frame about it (the sphere)
  float dc = 0.0f, dc2 = 0.0f, r2 = 0.0f, oneMinusCosMax = 0.0f;
  bool outside = false;
};
LightSampler prepareLight(const Light& light, const Vec3& p);
// A delta light's incidence (u1, u2 unused), or one sample of an area light, as its
// type's header says: e.g. a quad or disk uniformly over its area (pdf d^2 / (A cos_l)),
// a sphere uniformly over the cone it subtends (pdf 1 / (2 pi (1 - cos_max))), a mesh
// uniformly by area over all its triangles (core/lights/emissive_mesh.h); invalid where
// the emitter faces away or the point is inside the sphere.
LightIncidence sampleLight(const LightSampler& sampler, float u1, float u2);
// For the planar area lights' samples (core/lights/): the incidence from point y of a
// one-sided emitter uniform by area (the sampler's normal, area and band set by prepare):
// L cos_l A / d^2, invalid behind it, stopping short of the rounding band about its plane.
LightIncidence planarIncidence(const LightSampler& sampler, const Vec3& y);
inline LightIncidence sampleLight(const Light& light, const Vec3& p, float u1, float u2) {
  return sampleLight(prepareLight(light, p), u1, u2);
}
// The unoccluded irradiance E = integral of L cos(theta) over the light, at the
// sampler's point with unit shading normal n and geometric normal ng, in closed
// form where its type has one (its header says): e.g. a quad (each triangle of a small
// mesh light) by Lambert's polygon formula (clipped to the hemispheres of n and ng), a
// sphere or disk wholly above both horizons. False where there is none (a delta light,
// a sphere or disk cut by a horizon): sample instead.
bool unoccludedIrradiance(const LightSampler& sampler, const Vec3& n, const Vec3& ng, Color& E);

// Surface area of an area light (0 for a delta light).
float lightArea(const Light& light);
// Area lights in a scene get this many samples per shading point, delta lights one.
inline int lightSampleCount(const Light& light, int areaSamples) { return isDelta(light.type) ? 1 : areaSamples; }

// Total emitted flux, per channel: 4 pi I for a point light, E pi R^2 for a
// directional light over the scene's bounding disc, pi A L for an area light, pi R^2
// x the integral of L over all directions for an environment.
Color lightPower(const Light& light, const SceneSphere& bounds);

inline const LightTraits& lightTraits(const Light& light) { return lightTraits(light.type); }
inline bool isDeltaLight(const Light& light) { return isDelta(light.type); }
// Whether the shadow gate answers for a light: it emits shadow photons and is not dark.
inline bool answersGate(const Light& light) {
  return lightTraits(light).emitsShadowPhotons && maxComponent(light.radiance()) > 0.0f;
}

// The surface an area light adds to the scene as an emitting object (io's addEmitters
// gives it a black material that glows): a mesh or a sphere, neither for the rest.
struct EmitterShape {
  std::optional<TriangleMesh> mesh;
  std::optional<Sphere> sphere;
  bool twoSided = false;  // it glows on both sides (a sphere, seen from inside too)
};
EmitterShape emitterOf(const Light& light);

// Entries one sample of the light searches (a mesh light's cumulative areas), 0 for a
// light that draws a sample without a search: the resource estimate's cost per sample.
size_t lightSampleTable(const Light& light);

// The lights a model file can hold (glTF's punctual lights), at colour 1 and intensity 1:
// a point; a spot shining along the unit `direction` with cone angles in radians
// (setSpotCone); a directional light travelling along the unit `direction`.
Light makePointLight(const Vec3& position);
Light makeSpotLight(const Vec3& position, const Vec3& direction, float innerAngle, float outerAngle);
Light makeDirectionalLight(const Vec3& direction);

// A spot's share of its intensity towards `dir` (the way light leaves it): glTF's
// falloff, the square of a linear ramp between the outer and inner cone; 1 for
// every other light.
float spotFalloff(const Light& light, const Vec3& dir);
// Makes a light a spot (its type and cone) with glTF's cone angles (radians, 0 <= inner < outer <= pi/2).
void setSpotCone(Light& light, float innerAngle, float outerAngle);
// The falloff integrated over directions: a spot's power is this times its intensity.
float spotSolidAngle(const Light& light);

// Where and which way one emitted photon starts, from two (point) or four
// (directional, area) uniform numbers; every photon of a light carries power /
// count. An area light's photons start uniformly over its surface, cosine-weighted
// about its normal (a planar light's or a mesh triangle's emitting side; a sphere's
// outward normal).
struct PhotonRay {
  Vec3 origin{0.0f};
  Vec3 dir{0.0f, 0.0f, -1.0f};
  Vec3 normal{0.0f};  // an area light's surface normal at the origin (0 for delta lights)
  float error = 0.0f;  // an area light's origin: its rounding error along normal
  // Per channel, on the light's power / count: 1 but for an environment map's photons,
  // whose power follows the map's colour at the drawn direction (core/lights/environment_map.h).
  Color weight{1.0f};
  uint8_t stratum = 0;  // the part of the light it left from (core/light_strata.h)
};

// Where photons start (the classic and physical passes share these). emitterPhoton is
// sampleLightPhoton with its origin made safe to trace from (photonOrigin): an area
// light's point lifted off its own surface, a point light's position pushed a rounding
// error along the photon's way, a directional light's disc point as drawn.
PhotonRay emitterPhoton(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4);
Vec3 photonOrigin(const Light& light, const PhotonRay& r, const SceneSphere& bounds);
// How many of u1..u4 a light's photon reads: 2 for a point light, 4 for the rest.
int photonStartNumbers(const Light& light);
// A classic photon's start from the light's own stream: its numbers drawn in order.
PhotonRay classicPhotonStart(const Light& light, const SceneSphere& bounds, Rng& rng);
// Shadow photon i of a batch: every light that reads four numbers takes them from point
// i of the batch's Kronecker sequence (a cell's vote per stratum sees a sixteenth of a
// light's photons, and evenly spread ones decide it right more often than as many
// independent ones); a point light keeps classicPhotonStart's two.
PhotonRay shadowPhotonStart(const Light& light, const SceneSphere& bounds, const Kronecker4& starts, uint64_t i,
                            Rng& rng);
// The power each of `count` classic photons carries: power / count (a point light's
// as 4 pi I / count).
Color classicPhotonPower(const Light& light, const SceneSphere& bounds, float count);

// A light's share of the classic photon budget, in the units of a point light's
// intensity (flux / 4 pi): area lights pi A L / (4 pi); directional and environment
// lights emit no classic photons (the classic model lights by them through shadow rays).
float classicPhotonWeight(const Light& light);
PhotonRay sampleLightPhoton(const Light& light, const SceneSphere& bounds, float u1, float u2,
                            float u3, float u4);

}  // namespace penumbra
