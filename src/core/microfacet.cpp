// GGX after pbrt-v4's TrowbridgeReitzDistribution and Heitz's "Sampling the GGX
// Distribution of Visible Normals" (JCGT 2018); the blend of glTF 2.0's appendix B.
#include "core/microfacet.h"
#include "core/bsdf.h"
#include "core/color.h"
#include "core/optics.h"
#include "core/sampling.h"

namespace penumbra {
namespace {

constexpr float kInvPi = 1.0f / kPi;

// A BSDF frame's shading normal as the z axis of a local frame.
struct Local {
  Vec3 t, b, n;
  explicit Local(const Vec3& normal) : n(normal) { orthonormalBasis(n, t, b); }
  Vec3 in(const Vec3& w) const { return Vec3(glm::dot(w, t), glm::dot(w, b), glm::dot(w, n)); }
  Vec3 out(const Vec3& w) const { return w.x * t + w.y * b + w.z * n; }
};

float schlick(float f0, float cosine) {
  const float m = std::clamp(1.0f - cosine, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (1.0f - f0) * (m2 * m2 * m);
}

// The probability of sampling the specular lobe: all of it for a metal, for a
// dielectric its Fresnel weight at wo, kept in [0.1, 0.9] so neither lobe starves.
float specularShare(const Bsdf& b, float cosO) {
  const float dielectric = std::clamp(schlick(dielectricF0(b.ior), cosO), 0.1f, 0.9f);
  return b.metallic + (1.0f - b.metallic) * dielectric;
}

// The specular layer's Fresnel at cosine `c` between the view and the microfacet:
// the conductor's (F0 the base colour) and the dielectric's, blended by metallic.
Color fresnel(const Bsdf& b, float c) {
  const float m = std::clamp(1.0f - c, 0.0f, 1.0f);
  const float m5 = (m * m) * (m * m) * m;
  const Color metal = b.diffuse + (Color(1.0f) - b.diffuse) * m5;
  return b.metallic * metal + Color((1.0f - b.metallic) * schlick(dielectricF0(b.ior), c));
}

// Whether evaluate and pdf count the GGX lobe: not a delta one, and not one the
// caller leaves out (a narrow lobe in a photon gather).
bool specularCounted(const Bsdf& b) {
  if (b.roughness < kDeltaAlpha || !(b.lobes & kBsdfGlossy)) return false;
  return b.roughness >= kNarrowAlpha || (b.lobes & kBsdfNarrow);
}

}  // namespace

float ggxD(const Vec3& h, float alpha) {
  if (h.z <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha, c2 = h.z * h.z;
  const float d = c2 * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

float ggxLambda(const Vec3& w, float alpha) {
  const float c2 = w.z * w.z;
  if (c2 <= 0.0f) return 0.0f;
  const float tan2 = std::max(0.0f, 1.0f - c2) / c2;
  return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

Vec3 sampleGgxVisibleNormal(const Vec3& wo, float alpha, float u1, float u2) {
  // Stretch to the hemisphere configuration, sample the projected disc, unstretch.
  const Vec3 vh = glm::normalize(Vec3(alpha * wo.x, alpha * wo.y, wo.z));
  const float len2 = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = len2 > 0.0f ? Vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len2) : Vec3(1.0f, 0.0f, 0.0f);
  const Vec3 t2 = glm::cross(vh, t1);
  const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.0f + vh.z);
  const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
  const Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(Vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
}

float ggxVisiblePdf(const Vec3& wo, const Vec3& h, float alpha) {
  if (wo.z <= 0.0f) return 0.0f;
  return ggxG1(wo, alpha) * std::max(0.0f, glm::dot(wo, h)) * ggxD(h, alpha) / wo.z;
}

Color evaluateMetalRough(const Bsdf& b, const BsdfFrame& f, const Vec3& woW, const Vec3& wiW) {
  const Local frame(f.ns);
  const Vec3 wo = frame.in(woW), wi = frame.in(wiW);
  if (wo.z <= 0.0f || wi.z <= 0.0f) return Color(0.0f);
  const Vec3 h = glm::normalize(wo + wi);
  const float voh = std::max(0.0f, glm::dot(wo, h));
  const float specular = specularCounted(b) ? ggxD(h, b.roughness) * ggxG2(wo, wi, b.roughness) / (4.0f * wo.z * wi.z) : 0.0f;
  // Conductor: Schlick with the base colour as F0. Dielectric: the specular layer
  // with Fresnel at the microfacet over a Lambertian base that gets what the layer
  // transmits at wo. glTF appendix B's fresnel_mix weighs the base by 1 - F(v.h)
  // instead, which returns up to 1.3 of the light at grazing angles (the furnace test).
  const float diffuse = (b.lobes & kBsdfDiffuse) ? (1.0f - schlick(dielectricF0(b.ior), wo.z)) * kInvPi : 0.0f;
  return (fresnel(b, voh) * specular + (1.0f - b.metallic) * diffuse * b.diffuse) * wi.z;
}

float pdfMetalRough(const Bsdf& b, const BsdfFrame& f, const Vec3& woW, const Vec3& wiW) {
  const Local frame(f.ns);
  const Vec3 wo = frame.in(woW), wi = frame.in(wiW);
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  const Vec3 h = glm::normalize(wo + wi);
  const float voh = glm::dot(wo, h);
  const bool counted = specularCounted(b) && voh > 0.0f;
  const float specular = counted ? ggxVisiblePdf(wo, h, b.roughness) / (4.0f * voh) : 0.0f;
  const float ps = specularShare(b, wo.z);
  return ps * specular + ((b.lobes & kBsdfDiffuse) ? (1.0f - ps) * wi.z * kInvPi : 0.0f);
}

BsdfSample sampleMetalRough(const Bsdf& b, const BsdfFrame& f, const Vec3& woW, float uLobe, float u1, float u2) {
  BsdfSample s;
  const Local frame(f.ns);
  const Vec3 wo = frame.in(woW);
  if (wo.z <= 0.0f) return s;
  const float ps = specularShare(b, wo.z);
  Vec3 wi;
  if (uLobe < ps && b.roughness < kDeltaAlpha) {
    // The mirror limit: a delta lobe, its Fresnel over the probability of picking it.
    s.wi = frame.out(Vec3(-wo.x, -wo.y, wo.z));
    s.weight = fresnel(b, wo.z) / ps;
    s.flags = kBsdfSpecular;
    s.valid = glm::dot(s.wi, f.ng) > 0.0f && maxComponent(s.weight) > 0.0f;
    return s;
  }
  if (uLobe < ps) {
    wi = reflect(-wo, sampleGgxVisibleNormal(wo, b.roughness, u1, u2));
    s.flags = b.roughness < kNarrowAlpha ? kBsdfGlossy | kBsdfNarrow : kBsdfGlossy;
  } else {
    wi = cosineHemisphere(u1, u2);
    s.flags = kBsdfDiffuse;
  }
  if (wi.z <= 0.0f) return s;
  s.wi = frame.out(wi);
  const float pdf = pdfMetalRough(b, f, woW, s.wi);
  if (!(pdf > 0.0f)) return s;
  // The one-sample estimate over both lobes: f cos over the mixture's density.
  s.weight = evaluateMetalRough(b, f, woW, s.wi) / pdf;
  s.valid = true;
  return s;
}

Color metalRoughMirror(const Bsdf& b, const BsdfFrame& f, const Vec3& wo) {
  return fresnel(b, std::max(0.0f, glm::dot(f.ns, wo)));
}

BsdfSample sampleMetalRoughSpecular(const Bsdf& b, const BsdfFrame& f, const Vec3& woW, float u1, float u2) {
  BsdfSample s;
  const Local frame(f.ns);
  const Vec3 wo = frame.in(woW);
  if (wo.z <= 0.0f) return s;
  const Vec3 h = sampleGgxVisibleNormal(wo, b.roughness, u1, u2);
  const Vec3 wi = reflect(-wo, h);
  if (wi.z <= 0.0f) return s;
  s.wi = frame.out(wi);
  if (glm::dot(s.wi, f.ng) <= 0.0f) return s;
  // f cos / pdf of the lobe alone: D and the visible normals' density cancel.
  s.weight = fresnel(b, std::max(0.0f, glm::dot(wo, h))) * (ggxG2(wo, wi, b.roughness) / ggxG1(wo, b.roughness));
  s.flags = b.roughness < kNarrowAlpha ? kBsdfGlossy | kBsdfNarrow : kBsdfGlossy;
  s.valid = maxComponent(s.weight) > 0.0f;
  return s;
}

}  // namespace penumbra
