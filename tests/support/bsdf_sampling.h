// Shared by the BSDF tests: materials, tilted frames, a textbook Fresnel in double,
// Monte Carlo means of sample weights and stratified hemisphere integrals.
#pragma once
#include "core/bsdf.h"
#include "core/rng.h"
#include "core/sampling.h"
#include <gtest/gtest.h>
#include <cmath>
#include <string>
#include <vector>

namespace penumbra {

inline constexpr double kPiD = 3.14159265358979323846;

inline Material opaque(Color rho, Color spec = Color(0.0f), float shininess = 0.0f, float kr = 0.0f) {
  Material m;
  m.name = "opaque";
  m.diffuse = rho;
  m.specular = spec;
  m.shininess = shininess;
  m.kr = kr;
  return m;
}

inline Material glass(float ior, Color tint = Color(1.0f)) {
  Material m;
  m.name = "glass";
  m.diffuse = Color(0.0f);
  m.specular = Color(0.0f);
  m.transparent = true;
  m.ior = ior;
  m.tint = tint;
  return m;
}

// glTF's metallic-roughness BSDF with GGX width `alpha` (core/microfacet.h).
inline Bsdf metalRough(const Color& base, float metallic, float alpha) {
  Bsdf b;
  b.type = BsdfType::MetalRough;
  b.diffuse = base;
  b.metallic = metallic;
  b.roughness = alpha;
  return b;
}

inline Bsdf physical(const Material& m) { return makeBsdf(m, BsdfFamily::Radiometric, HemisphereSampling::Cosine); }

// A tilted frame, so a bug that assumes n = +z shows up.
const Vec3 kNormal = glm::normalize(Vec3(0.3f, 0.5f, 0.8f));
inline BsdfFrame frameOf(const Vec3& n, bool outside = true) { return {n, n, outside}; }

// A unit direction at polar angle theta (radians) from n, in a fixed azimuth.
inline Vec3 atAngle(const Vec3& n, double theta) {
  Vec3 t, b;
  orthonormalBasis(n, t, b);
  return glm::normalize(static_cast<float>(std::cos(theta)) * n + static_cast<float>(std::sin(theta)) * t);
}

// Unpolarised Fresnel reflectance from the textbook s/p formulas, in double.
inline double fresnelRef(double cosI, double n1, double n2) {
  double sinI = std::sqrt(std::max(0.0, 1.0 - cosI * cosI));
  double sinT = n1 / n2 * sinI;
  if (sinT >= 1.0) return 1.0;
  double cosT = std::sqrt(1.0 - sinT * sinT);
  double rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
  double rp = (n1 * cosT - n2 * cosI) / (n1 * cosT + n2 * cosI);
  return 0.5 * (rs * rs + rp * rp);
}

struct MeanWeight {
  glm::dvec3 mean{0.0}, se{0.0};  // mean and its standard error, per channel
  int invalid = 0, specular = 0, transmitted = 0;
};

// Mean of sampleBsdf's weight over n samples (invalid samples count as 0).
inline MeanWeight meanWeight(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, int n, uint64_t seed) {
  Rng rng(seed);
  glm::dvec3 sum(0.0), sum2(0.0);
  MeanWeight out;
  for (int i = 0; i < n; ++i) {
    float ul = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    BsdfSample s = sampleBsdf(b, f, wo, ul, u1, u2);
    glm::dvec3 w = s.valid ? glm::dvec3(s.weight) : glm::dvec3(0.0);
    if (!s.valid) ++out.invalid;
    if (s.flags & kBsdfSpecular) ++out.specular;
    if (s.flags & kBsdfTransmission) ++out.transmitted;
    sum += w;
    sum2 += w * w;
  }
  out.mean = sum / double(n);
  glm::dvec3 var = sum2 / double(n) - out.mean * out.mean;
  out.se = glm::sqrt(glm::max(var, glm::dvec3(0.0)) / double(n));
  return out;
}

// Integral of evaluateBsdf (f |cos|) over the hemisphere around f.ns, by
// stratified (jittered grid) uniform directions in (cos theta, phi): unbiased,
// and independent of the BSDF's own sampler and pdf.
inline glm::dvec3 hemisphereIntegral(const Bsdf& b, const BsdfFrame& f, const Vec3& wo, int grid, uint64_t seed) {
  Rng rng(seed);
  glm::dvec3 sum(0.0);
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) {
      float u1 = (i + rng.uniform()) / grid, u2 = (j + rng.uniform()) / grid;
      Vec3 wi = toWorld(uniformHemisphere(u1, u2), f.ns);
      sum += glm::dvec3(evaluateBsdf(b, f, wo, wi));
    }
  }
  return sum * (2.0 * kPiD / (double(grid) * grid));
}

inline void expectNearMean(const MeanWeight& m, const glm::dvec3& expected, const std::string& what) {
  for (int c = 0; c < 3; ++c) {
    // 4 standard errors of the Monte Carlo mean, plus 1e-6 for float rounding.
    EXPECT_NEAR(m.mean[c], expected[c], 4.0 * m.se[c] + 1e-6)
        << what << " channel " << c << " (se " << m.se[c] << ")";
  }
}

}  // namespace penumbra
