// The three BSDFs behind one switch. Physical lobes follow pbrt-v4 and Lafortune &
// Willems' normalised Phong; the classic one is the report's Phong, term for term.
#include "core/bsdf.h"
#include "core/color.h"
#include "core/microfacet.h"
#include "core/optics.h"
#include "core/sampling.h"

namespace penumbra {
namespace {

constexpr float kInvPi = 1.0f / kPi;

// Lobe-selection weights of an Opaque BSDF: each lobe's mean reflectance.
struct OpaqueLobes {
  float diffuse, glossy, mirror, total;
};
OpaqueLobes lobesOf(const Bsdf& b) {
  OpaqueLobes l;
  l.diffuse = (1.0f - b.kr) * meanOf(b.diffuse);
  l.glossy = b.shininess > 0.0f ? (1.0f - b.kr) * meanOf(b.specular) : 0.0f;
  l.mirror = b.kr;
  l.total = l.diffuse + l.glossy + l.mirror;
  return l;
}

// cos^n of the angle between wi and the mirror direction of wo.
float phongCosine(const Vec3& n, const Vec3& wo, const Vec3& wi, float shininess) {
  float c = glm::dot(reflect(-wo, n), wi);
  return c > 0.0f ? std::pow(c, shininess) : 0.0f;
}

Color evaluateClassic(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, const Vec3& wi) {
  // The report's terms exactly as the Whitted tracer always computed them.
  float nDotL = glm::dot(f.ns, wi);
  if (nDotL <= 0.0f) return Color(0.0f);
  Color c = b.diffuse * nDotL;
  if (b.shininess > 0.0f && maxComponent(b.specular) > 0.0f) {
    float rDotV = glm::dot(reflect(-wi, f.ns), wo);
    if (rDotV > 0.0f) c += b.specular * std::pow(rDotV, b.shininess);
  }
  return c;
}

Color evaluateOpaque(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, const Vec3& wi) {
  float cosI = glm::dot(f.ns, wi);
  if (cosI <= 0.0f) return Color(0.0f);
  Color fr = b.diffuse * kInvPi;
  if (b.shininess > 0.0f) {
    // Normalised so that the lobe reflects `specular` of the light at normal incidence.
    fr += b.specular * ((b.shininess + 2.0f) * 0.5f * kInvPi * phongCosine(f.ns, wo, wi, b.shininess));
  }
  return (1.0f - b.kr) * fr * cosI;
}

float pdfOpaque(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, const Vec3& wi) {
  OpaqueLobes l = lobesOf(b);
  float cosI = glm::dot(f.ns, wi);
  if (l.total <= 0.0f || cosI <= 0.0f) return 0.0f;
  float p = l.diffuse * cosI * kInvPi;
  if (l.glossy > 0.0f) {
    p += l.glossy * (b.shininess + 1.0f) * 0.5f * kInvPi * phongCosine(f.ns, wo, wi, b.shininess);
  }
  return p / l.total;
}

BsdfSample sampleClassic(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, float uLobe, float u1,
                         float u2) {
  // The report's Russian roulette: reflect with p_r, transmit with p_t, else absorb.
  // A survivor keeps its power level and takes on the surface's hue, scaled so that
  // no channel gains: the expected power after the bounce is p_r * colour / max(colour)
  // <= what arrived (docs/photon-maps.md, "energy").
  BsdfSample s;
  if (uLobe < b.pR) {
    Vec3 local = b.uniformBounce ? uniformHemisphere(u1, u2) : cosineHemisphere(u1, u2);
    s.wi = toWorld(local, f.ng);
    float top = maxComponent(b.diffuse);
    s.weight = top > 0.0f ? b.diffuse / top : Color(0.0f);
    // A uniform bounce carries the ratio of the cosine density to its own, 2 cos.
    if (b.uniformBounce) s.weight *= 2.0f * local.z;
    s.flags = kBsdfDiffuse;
  } else if (uLobe < b.pR + b.pT) {
    Vec3 d = -wo;
    float eta = f.outside ? 1.0f / b.ior : b.ior;
    bool refracted = refract(d, f.ns, eta, s.wi);
    if (!refracted) s.wi = reflect(d, f.ns);  // total internal reflection
    float top = maxComponent(b.tint);
    s.weight = Color(1.0f);
    if (refracted && f.outside) s.weight = top > 0.0f ? b.tint / top : Color(0.0f);
    s.flags = refracted ? kBsdfSpecular | kBsdfTransmission : kBsdfSpecular;
  } else {
    return s;
  }
  s.valid = maxComponent(s.weight) > 0.0f;
  return s;
}

BsdfSample sampleOpaque(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, float uLobe, float u1,
                        float u2) {
  BsdfSample s;
  OpaqueLobes l = lobesOf(b);
  if (l.total <= 0.0f) return s;
  float pick = uLobe * l.total;
  if (pick < l.mirror) {
    s.wi = reflect(-wo, f.ns);
    if (glm::dot(s.wi, f.ng) <= 0.0f) s.wi = reflect(-wo, f.ng);
    s.weight = Color(l.total);  // kr / (kr / total)
    s.flags = kBsdfSpecular;
    s.valid = true;
    return s;
  }
  if (pick < l.mirror + l.diffuse) {
    s.wi = toWorld(cosineHemisphere(u1, u2), f.ns);
    s.flags = kBsdfDiffuse;
  } else {
    // cos^n lobe around the mirror direction: cos(alpha) = u1^(1 / (n + 1)).
    float cosA = std::pow(u1, 1.0f / (b.shininess + 1.0f));
    float sinA = std::sqrt(std::max(0.0f, 1.0f - cosA * cosA));
    float phi = 2.0f * kPi * u2;
    s.wi = toWorld(Vec3(sinA * std::cos(phi), sinA * std::sin(phi), cosA), reflect(-wo, f.ns));
    s.flags = kBsdfGlossy;
  }
  if (glm::dot(s.wi, f.ng) <= 0.0f) return s;  // under the surface: no light comes back
  float pdf = pdfOpaque(b, f, wo, s.wi);
  if (!(pdf > 0.0f)) return s;
  s.weight = evaluateOpaque(b, f, wo, s.wi) / pdf;
  s.valid = maxComponent(s.weight) > 0.0f;
  return s;
}

BsdfSample sampleDielectric(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, float uLobe) {
  // Reflect with probability F, refract with 1 - F: the choice carries the Fresnel
  // weight exactly, so the sample weight is 1 (or the tint on entering).
  BsdfSample s;
  float etaI = f.outside ? 1.0f : b.ior, etaT = f.outside ? b.ior : 1.0f;
  float fr = fresnelDielectric(glm::dot(f.ns, wo), etaI, etaT);
  Vec3 d = -wo, t;
  bool canRefract = refract(d, f.ns, etaI / etaT, t);
  if (!canRefract || uLobe < fr) {
    s.wi = reflect(d, f.ns);
    s.weight = Color(1.0f);
    s.flags = kBsdfSpecular;
  } else {
    s.wi = t;
    s.weight = f.outside ? b.tint : Color(1.0f);
    s.flags = kBsdfSpecular | kBsdfTransmission;
  }
  s.valid = maxComponent(s.weight) > 0.0f;
  return s;
}

}  // namespace

void setMetalRough(Bsdf& b, BsdfFamily family, const Color& base, float metallic, float roughness) {
  b.diffuse = base;
  b.metallic = std::clamp(metallic, 0.0f, 1.0f);
  const float alpha = std::clamp(roughness, 0.0f, 1.0f) * std::clamp(roughness, 0.0f, 1.0f);
  if (family == BsdfFamily::Radiometric) {
    b.type = BsdfType::MetalRough;
    b.roughness = alpha;
    return;
  }
  // Classic Phong terms: the base under (1 - metallic), a highlight of the metal's
  // colour (0.04 for a dielectric) with the Beckmann-Phong exponent 2 / alpha^2 - 2,
  // and a mirror only as the metal gets smooth, so rough metals are never mirrors.
  b.diffuse = (1.0f - b.metallic) * base;
  b.specular = b.metallic * base + Color((1.0f - b.metallic) * 0.04f);
  b.shininess = alpha > 0.01f ? std::min(2.0f / (alpha * alpha) - 2.0f, 10000.0f) : 10000.0f;
  const float smooth = std::clamp(1.0f - roughness, 0.0f, 1.0f);
  b.kr = b.metallic * (smooth * smooth) * (smooth * smooth);
}

Bsdf makeBsdf(const Material& m, BsdfFamily family, HemisphereSampling bounce, const Color& tint) {
  Bsdf b;
  const Color base = m.diffuse * tint;
  b.diffuse = base;
  b.specular = m.specular;
  b.shininess = m.shininess;
  b.kr = m.kr;
  b.ior = m.ior;
  b.tint = m.tint;
  b.pR = m.pR;
  b.pT = m.pT;
  b.uniformBounce = bounce == HemisphereSampling::Uniform;
  if (family == BsdfFamily::Phong) b.type = BsdfType::ClassicPhong;
  else b.type = m.transparent ? BsdfType::Dielectric : BsdfType::Opaque;
  if (m.metalRough && !m.transparent) setMetalRough(b, family, base, m.metallic, m.roughness);
  return b;
}

uint8_t bsdfFlags(const Bsdf& b) {
  switch (b.type) {
    case BsdfType::ClassicPhong: {
      uint8_t f = kBsdfNone;
      if (maxComponent(b.diffuse) > 0.0f) f |= kBsdfDiffuse;
      if (b.shininess > 0.0f && maxComponent(b.specular) > 0.0f) f |= kBsdfGlossy;
      if (b.kr > 0.0f || b.pT > 0.0f) f |= kBsdfSpecular;
      if (b.pT > 0.0f) f |= kBsdfTransmission;
      return f;
    }
    case BsdfType::Opaque: {
      OpaqueLobes l = lobesOf(b);
      return (l.diffuse > 0.0f ? kBsdfDiffuse : 0) | (l.glossy > 0.0f ? kBsdfGlossy : 0) |
             (l.mirror > 0.0f ? kBsdfSpecular : 0);
    }
    case BsdfType::Dielectric: return kBsdfSpecular | kBsdfTransmission;
    case BsdfType::MetalRough: {
      const uint8_t base = b.metallic < 1.0f && maxComponent(b.diffuse) > 0.0f ? kBsdfDiffuse : 0;
      if (b.roughness < kDeltaAlpha) return kBsdfSpecular | base;
      return kBsdfGlossy | (b.roughness < kNarrowAlpha ? kBsdfNarrow : 0) | base;
    }
  }
  return kBsdfNone;
}

Color evaluateBsdf(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, const Vec3& wi) {
  if (glm::dot(f.ng, wi) <= 0.0f) return Color(0.0f);
  switch (b.type) {
    case BsdfType::ClassicPhong: return evaluateClassic(b, f, wo, wi);
    case BsdfType::Opaque: return evaluateOpaque(b, f, wo, wi);
    case BsdfType::Dielectric: return Color(0.0f);  // only delta lobes
    case BsdfType::MetalRough: return evaluateMetalRough(b, f, wo, wi);
  }
  return Color(0.0f);
}

float pdfBsdf(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, const Vec3& wi) {
  if (glm::dot(f.ng, wi) <= 0.0f) return 0.0f;
  if (b.type == BsdfType::MetalRough) return pdfMetalRough(b, f, wo, wi);
  return b.type == BsdfType::Opaque ? pdfOpaque(b, f, wo, wi) : 0.0f;
}

BsdfSample sampleBsdf(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, float uLobe, float u1,
                      float u2) {
  switch (b.type) {
    case BsdfType::ClassicPhong: return sampleClassic(b, f, wo, uLobe, u1, u2);
    case BsdfType::Opaque: return sampleOpaque(b, f, wo, uLobe, u1, u2);
    case BsdfType::Dielectric: return sampleDielectric(b, f, wo, uLobe);
    case BsdfType::MetalRough: return sampleMetalRough(b, f, wo, uLobe, u1, u2);
  }
  return {};
}

Color albedoBsdf(const Bsdf& b) {
  switch (b.type) {
    case BsdfType::ClassicPhong: {
      float dTop = maxComponent(b.diffuse), tTop = maxComponent(b.tint);
      return b.pR * (dTop > 0.0f ? b.diffuse / dTop : Color(0.0f)) +
             b.pT * (tTop > 0.0f ? b.tint / tTop : Color(0.0f));
    }
    case BsdfType::Opaque:
      return (1.0f - b.kr) * (b.diffuse + (b.shininess > 0.0f ? b.specular : Color(0.0f))) +
             Color(b.kr);
    case BsdfType::Dielectric: {
      float f0 = fresnelDielectric(1.0f, 1.0f, b.ior);
      return Color(f0) + (1.0f - f0) * b.tint;
    }
    case BsdfType::MetalRough: {
      // At normal incidence, before the microfacets' shadowing loss: an upper bound.
      const float f0 = dielectricF0(b.ior);
      return b.metallic * b.diffuse + (1.0f - b.metallic) * (Color(f0) + (1.0f - f0) * b.diffuse);
    }
  }
  return Color(0.0f);
}

Color lambertCoefficient(const Bsdf& b) {
  switch (b.type) {
    case BsdfType::ClassicPhong: return b.diffuse;
    case BsdfType::Opaque: return (1.0f - b.kr) * b.diffuse * kInvPi;
    case BsdfType::Dielectric: return Color(0.0f);
    case BsdfType::MetalRough: return Color(0.0f);  // its base is Fresnel-weighted: all of it is sampled
  }
  return Color(0.0f);
}

Bsdf gatheredPart(const Bsdf& b) {
  Bsdf g = b;
  g.lobes = static_cast<uint8_t>(g.lobes & ~kBsdfNarrow);
  return g;
}

Color mirrorReflectance(const Bsdf& b, const BsdfFrame& f, const Vec3& wo) {
  return b.type == BsdfType::MetalRough ? metalRoughMirror(b, f, wo) : Color(b.kr);
}

BsdfSample sampleNarrowLobe(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, float u1, float u2) {
  return b.type == BsdfType::MetalRough ? sampleMetalRoughSpecular(b, f, wo, u1, u2) : BsdfSample{};
}

Bsdf glossyPart(const Bsdf& b) {
  Bsdf g = b;
  if (b.type != BsdfType::MetalRough) g.diffuse = Color(0.0f);
  return g;
}

}  // namespace penumbra
