// The disk light: a one-sided Lambertian disc (centre `position`, unit normal `direction`
// on its emitting side, `radius`), sampled uniformly by area through the concentric map.
// Included by core/light_types.h only.
#pragma once

namespace penumbra {

// Its strata are cells of (u1, u2), as a quad's: the concentric map keeps their areas equal.
struct DiskLight : LightDefaults {
  static constexpr LightType kType = LightType::Disk;
  static constexpr LightTraits kTraits = {
      LightSupport::Area, StrataKind::Parametric, AimKind::Surface,
      ShadowTest::Segment, DirectSampling::Gated,
      /*emitsShadowPhotons*/ true, /*opensPhysicalMaps*/ true,
      /*gateAvoidsRays*/ true, "disk", kLambertianPower};
  static void prepare(const Light& light, const Vec3& p, LightSampler& s);
  static LightIncidence sample(const LightSampler& s, float u1, float u2);
  // E = L n . J with J the disc's vector irradiance (exact: on the axis pi L R^2 / (R^2 + h^2))
  // where the disc lies wholly above both horizons; false (sample) where one cuts it.
  static bool irradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E);
  static float area(const Light& light);
  static PhotonRay photon(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4);
  // A one-sided fan of kDiskSides triangles whose area is the disc's.
  static EmitterShape emitter(const Light& light);
  static constexpr int kDiskSides = 64;
};

}  // namespace penumbra
