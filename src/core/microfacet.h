// Trowbridge-Reitz (GGX) microfacets with Smith's height-correlated shadowing, sampled
// by their visible normals (Heitz 2018), and glTF's metallic-roughness BSDF built on
// them: a conductor with Schlick's Fresnel from the base colour, blended by
// `metallic` with a dielectric (a Lambertian base under the GGX specular layer).
#pragma once
#include "core/math.h"

namespace penumbra {

struct Bsdf;
struct BsdfFrame;
struct BsdfSample;

// In a local frame whose z is the normal; alpha is GGX's width (glTF: roughness^2).
float ggxD(const Vec3& h, float alpha);
float ggxLambda(const Vec3& w, float alpha);
inline float ggxG1(const Vec3& w, float alpha) { return 1.0f / (1.0f + ggxLambda(w, alpha)); }
inline float ggxG2(const Vec3& wo, const Vec3& wi, float alpha) {
  return 1.0f / (1.0f + ggxLambda(wo, alpha) + ggxLambda(wi, alpha));
}
// A microfacet normal seen from wo (wo.z > 0), with density ggxVisiblePdf.
Vec3 sampleGgxVisibleNormal(const Vec3& wo, float alpha, float u1, float u2);
float ggxVisiblePdf(const Vec3& wo, const Vec3& h, float alpha);

// The glTF dielectric's reflectance at normal incidence: ((ior - 1) / (ior + 1))^2.
inline float dielectricF0(float ior) {
  const float r = (ior - 1.0f) / (ior + 1.0f);
  return r * r;
}

// BsdfType::MetalRough behind bsdf.h's interface (same contracts).
Color evaluateMetalRough(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, const Vec3& wi);
float pdfMetalRough(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, const Vec3& wi);
BsdfSample sampleMetalRough(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, float uLobe, float u1, float u2);
// bsdf.h's mirrorReflectance and sampleNarrowLobe for MetalRough.
Color metalRoughMirror(const Bsdf& b, const BsdfFrame& f, const Vec3& wo);
BsdfSample sampleMetalRoughSpecular(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, float u1, float u2);

}  // namespace penumbra
