// The sphere light: a Lambertian sphere emitting all round, sampled uniformly over
// the cone it subtends. Included by core/light_types.h only.
#pragma once

namespace penumbra {

struct SphereLight : LightDefaults {
  static constexpr LightType kType = LightType::Sphere;
  static constexpr LightTraits kTraits = {
      LightSupport::Area, StrataKind::Surface, AimKind::SphereCaps,
      ShadowTest::FirstHitIsEmitter, DirectSampling::Gated,
      /*emitsShadowPhotons*/ true, /*opensPhysicalMaps*/ true,
      /*gateAvoidsRays*/ true, "sphere", kLambertianPower};
  static void prepare(const Light& light, const Vec3& p, LightSampler& s);
  static LightIncidence sample(const LightSampler& s, float u1, float u2);
  static bool irradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E);
  static float area(const Light& light);
  static PhotonRay photon(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4);
  // A photon's start at the unit outward normal n: its surface point and rounding
  // error (no direction yet).
  static PhotonRay start(const Light& light, const Vec3& n);
  static EmitterShape emitter(const Light& light);  // the sphere itself, two-sided
};

}  // namespace penumbra
