// The BSDF interface: evaluate, sample, pdf, albedo and flags of a material at a
// hit, dispatched on a small tag (no virtual call per ray). The report's Phong
// model is one implementation; the physical model's opaque and glass BSDFs the others.
#pragma once
#include "core/bsdf_family.h"
#include "core/scene.h"

namespace penumbra {

// What a lobe does; a sample reports the flags of the lobe it chose.
enum BsdfFlags : uint8_t {
  kBsdfNone = 0,
  kBsdfDiffuse = 1 << 0,       // Lambertian reflection
  kBsdfGlossy = 1 << 1,        // a finite glossy lobe
  kBsdfSpecular = 1 << 2,      // a delta lobe: mirror, or smooth glass (reflect or refract)
  kBsdfTransmission = 1 << 3,  // light crosses the surface
  // A glossy lobe narrow enough that camera paths follow it by sampled rays, as they
  // follow delta lobes: photon maps would blur it. Photons count it as specular.
  kBsdfNarrow = 1 << 4,
};

// MetalRough widths (GGX alpha): below kDeltaAlpha the specular lobe is a perfect
// mirror; below kNarrowAlpha it is narrow (kBsdfNarrow), traced rather than gathered.
constexpr float kDeltaAlpha = 1e-3f;
constexpr float kNarrowAlpha = 0.1f;

enum class BsdfType : uint8_t {
  ClassicPhong,  // the report's: k_d (N.L) + k_s (R.V)^n; photons by p_r / p_t roulette
  Opaque,        // physical: (1 - kr) (Lambert rho + normalised Phong) + kr mirror
  Dielectric,    // physical: smooth glass, Fresnel reflect / refract, tint on entering
  MetalRough,    // physical: glTF metallic-roughness over GGX microfacets (core/microfacet.h)
};

// A material resolved for one model: plain data, a few dozen bytes, built per hit.
struct Bsdf {
  BsdfType type = BsdfType::ClassicPhong;
  Color diffuse{0.0f};   // classic k_d, or physical rho (the BRDF is rho / pi)
  Color specular{0.0f};  // classic k_s, or physical glossy reflectance
  float shininess = 0.0f;
  float kr = 0.0f;       // mirror reflectance (Opaque), ignored by Dielectric
  float ior = 1.5f;
  Color tint{1.0f};      // transmittance filter on entering glass
  float pR = 0.0f, pT = 0.0f;  // ClassicPhong photon roulette
  bool uniformBounce = true;   // ClassicPhong photon bounce: uniform (report) or cosine
  float metallic = 0.0f;       // MetalRough: 1 a conductor, 0 a dielectric; `diffuse` is the base colour
  float roughness = 0.5f;      // MetalRough: GGX alpha (glTF's roughness squared), >= 0
  // The lobes evaluateBsdf and pdfBsdf count (a photon gather leaves out traced ones).
  uint8_t lobes = kBsdfDiffuse | kBsdfGlossy | kBsdfSpecular | kBsdfTransmission | kBsdfNarrow;
};

// The local frame of a hit: unit normals facing the side the light or ray arrives
// from, and whether that side is the outside (entering versus leaving glass).
struct BsdfFrame {
  Vec3 ns{0.0f, 0.0f, 1.0f};  // shading normal
  Vec3 ng{0.0f, 0.0f, 1.0f};  // geometric normal
  bool outside = true;
};

// weight = f * |cos| / pdf (including the probability of picking the lobe), so a
// path's throughput is multiplied by it; flags say which lobe was picked.
struct BsdfSample {
  Vec3 wi{0.0f};
  Color weight{0.0f};
  uint8_t flags = kBsdfNone;
  bool valid = false;  // false: absorbed (classic roulette) or no usable direction
};

// The material as a BSDF of `family` (core/bsdf_family.h): ClassicPhong for Phong;
// Opaque, Dielectric or MetalRough for Radiometric. `tint` multiplies the base colour
// (diffuse, or the metallic-roughness base): a mesh's vertex colour at the hit, 1 elsewhere.
Bsdf makeBsdf(const Material& m, BsdfFamily family, HemisphereSampling bounce, const Color& tint = Color(1.0f));
// Makes `b` glTF's metallic-roughness at one hit's values: MetalRough in the
// Radiometric family, its Phong terms in the Phong one. makeBsdf calls it with the
// material's factors; a hit with textures calls it again with the texels applied.
void setMetalRough(Bsdf& b, BsdfFamily family, const Color& base, float metallic, float roughness);

// The Lambertian part of evaluateBsdf is lambertCoefficient(b) x max(0, ns . wi)
// (classic k_d; physical (1 - kr) rho / pi); glossyPart(b) evaluates to the rest.
// Lets a caller integrate the diffuse part over an area light in closed form.
Color lambertCoefficient(const Bsdf& b);
Bsdf glossyPart(const Bsdf& b);

// Union of the flags of the BSDF's lobes that have any weight.
uint8_t bsdfFlags(const Bsdf& b);
inline bool hasSmoothLobe(const Bsdf& b) { return bsdfFlags(b) & (kBsdfDiffuse | kBsdfGlossy); }
inline bool hasDeltaLobe(const Bsdf& b) { return bsdfFlags(b) & kBsdfSpecular; }
// Lobes a camera path follows by rays (delta or narrow), and lobes it reads from the
// photon maps (the rest of the smooth ones): where photons are stored and gathered.
inline bool hasTracedLobe(const Bsdf& b) { return bsdfFlags(b) & (kBsdfSpecular | kBsdfNarrow); }
inline bool hasGatheredLobe(const Bsdf& b) {
  const uint8_t f = bsdfFlags(b);
  return (f & kBsdfDiffuse) || ((f & kBsdfGlossy) && !(f & kBsdfNarrow));
}
// The BSDF with only its gathered lobes, for a photon estimate.
Bsdf gatheredPart(const Bsdf& b);

// The colour a delta mirror lobe reflects towards wo (Opaque: kr; MetalRough below
// kDeltaAlpha: its Fresnel at the angle of wo).
Color mirrorReflectance(const Bsdf& b, const BsdfFrame& f, const Vec3& wo);

// One sample of a MetalRough BSDF's narrow specular lobe alone: the direction a
// camera path follows and f cos / pdf of that lobe (its Fresnel times G2 / G1).
BsdfSample sampleNarrowLobe(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, float u1, float u2);

// f(wo, wi) |cos theta_i| of the non-delta lobes; wo points to the viewer, wi to
// the light, both unit. Zero when wi is below the geometric surface.
Color evaluateBsdf(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, const Vec3& wi);

// Solid-angle density with which sampleBsdf picks wi through an Opaque or MetalRough
// BSDF's non-delta lobes. 0 for ClassicPhong (the report's photon roulette bounces by p_r
// and p_t, not by importance-sampling f) and for Dielectric (delta lobes only).
float pdfBsdf(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, const Vec3& wi);

// Samples an incident direction wi for outgoing wo from three uniform numbers.
// `wo` for photons is the reversed direction of travel (towards where it came from).
BsdfSample sampleBsdf(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, float uLobe, float u1,
                      float u2);

// Directional-hemispherical reflectance plus transmittance at normal incidence:
// what fraction of arriving power a bounce returns on average, per channel.
Color albedoBsdf(const Bsdf& b);

}  // namespace penumbra
