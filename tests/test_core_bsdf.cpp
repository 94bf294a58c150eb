// The opaque BSDFs against their definitions: the mean sample weight equals the
// albedo (Lambert: every cosine-sampled weight is exactly rho), a smooth lobe's
// sample weight is evaluate / pdf, the hemispherical integral of evaluate (stratified
// uniform directions, independent of the sampler) is rho for Lambert and <= 1 for
// normalised Phong, and a mirror mixture splits by its reflectance.
#include "support/bsdf_sampling.h"

namespace penumbra {
namespace {

TEST(BsdfLambert, EveryCosineSampleWeighsExactlyRho) {
  // Cosine sampling of rho / pi: f cos / pdf = (rho cos / pi) / (cos / pi) = rho for
  // every sample. Tolerance 1e-5 relative: a few float roundings, no statistics.
  const Color rho(0.6f, 0.3f, 0.1f);
  Bsdf b = physical(opaque(rho));
  EXPECT_EQ(b.type, BsdfType::Opaque);
  EXPECT_EQ(bsdfFlags(b), kBsdfDiffuse);
  BsdfFrame f = frameOf(kNormal);
  Rng rng(7);
  int valid = 0;
  for (double theta : {0.0, 0.7, 1.4}) {
    Vec3 wo = atAngle(kNormal, theta);
    for (int i = 0; i < 20000; ++i) {
      float ul = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
      BsdfSample s = sampleBsdf(b, f, wo, ul, u1, u2);
      if (!s.valid) continue;
      ++valid;
      EXPECT_EQ(s.flags, kBsdfDiffuse);
      EXPECT_GT(glm::dot(s.wi, kNormal), 0.0f);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.weight[c], rho[c], 1e-5f * rho[c]) << i;
      // ... and the weight is evaluate / pdf at the sampled direction.
      Color ratio = evaluateBsdf(b, f, wo, s.wi) / pdfBsdf(b, f, wo, s.wi);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.weight[c], ratio[c], 1e-5f * rho[c]);
    }
  }
  // Cosine samples never fall under the surface (z = sqrt(1 - u1) > 0); allow a
  // handful of grazing directions lost to rounding out of 60000.
  EXPECT_GE(valid, 60000 - 5);
  EXPECT_EQ(albedoBsdf(b), rho);
}

TEST(BsdfLambert, HemisphereIntegralIsRho) {
  // Integral of rho/pi cos over the hemisphere = rho, independent of wo. Tolerance
  // 1%, as asked; a 400x400 jittered grid is accurate to ~1e-4 here.
  const Color rho(0.6f, 0.3f, 0.1f);
  Bsdf b = physical(opaque(rho));
  BsdfFrame f = frameOf(kNormal);
  for (double theta : {0.0, 1.0}) {
    glm::dvec3 integral = hemisphereIntegral(b, f, atAngle(kNormal, theta), 400, 11);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(integral[c], rho[c], 0.01 * rho[c]) << theta;
  }
  // A direction under the geometric surface gets nothing, and has no density.
  Vec3 below = atAngle(-kNormal, 0.3);
  EXPECT_EQ(evaluateBsdf(b, f, kNormal, below), Color(0.0f));
  EXPECT_EQ(pdfBsdf(b, f, kNormal, below), 0.0f);
}

TEST(BsdfPhong, NormalisedLobeIntegratesToAtMostOne) {
  // Pure normalised Phong (rho = 0, specular 1): (n+2)/(2 pi) cos^n(alpha) cos(theta_i).
  // At normal incidence the lobe lies wholly above the surface and integrates to
  // exactly 1 (the normalisation); at oblique incidence part of it is cut off by the
  // horizon, so <= 1. Tolerance 1% for the normal-incidence value (the jittered
  // 1000x1000 grid resolves the n = 100 lobe to ~0.1%), +0.5% above 1 otherwise.
  BsdfFrame f = frameOf(kNormal);
  for (float n : {1.0f, 20.0f, 100.0f}) {
    Bsdf b = physical(opaque(Color(0.0f), Color(1.0f), n));
    EXPECT_EQ(bsdfFlags(b), kBsdfGlossy);
    glm::dvec3 normal = hemisphereIntegral(b, f, kNormal, 1000, 3);
    EXPECT_NEAR(normal.r, 1.0, 0.01) << "n=" << n;
    double last = normal.r;
    for (double deg : {30.0, 60.0, 80.0}) {
      double v = hemisphereIntegral(b, f, atAngle(kNormal, deg * kPiD / 180.0), 1000, 5).r;
      EXPECT_LE(v, 1.005) << "n=" << n << " at " << deg << " deg";
      EXPECT_GT(v, 0.0);
      // The horizon cuts off more of the lobe the more grazing wo is.
      EXPECT_LE(v, last + 0.005) << "n=" << n << " at " << deg << " deg";
      last = v;
    }
  }
}

TEST(BsdfPhong, LambertPlusGlossyMeanWeightIsTheAlbedo) {
  // rho + glossy (n = 20), coloured, at normal incidence: the albedo is exactly
  // rho + specular (both lobes whole), and the mean of 400k sample weights must
  // equal it within 4 standard errors. Smooth lobes: weight == evaluate / pdf.
  const Color rho(0.6f, 0.3f, 0.1f), spec(0.2f, 0.3f, 0.4f);
  Bsdf b = physical(opaque(rho, spec, 20.0f));
  EXPECT_EQ(bsdfFlags(b), kBsdfDiffuse | kBsdfGlossy);
  BsdfFrame f = frameOf(kNormal);
  const glm::dvec3 albedo = glm::dvec3(rho) + glm::dvec3(spec);
  MeanWeight m = meanWeight(b, f, kNormal, 400000, 17);
  expectNearMean(m, albedo, "normal incidence");
  for (int c = 0; c < 3; ++c) EXPECT_LT(m.se[c], 0.003) << "too few samples to mean anything";
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(albedoBsdf(b)[c], albedo[c], 1e-6);
  EXPECT_NEAR(hemisphereIntegral(b, f, kNormal, 1000, 19).g, albedo.g, 0.01 * albedo.g);

  // Oblique incidence: no closed form, but the sampler must agree with the
  // integral of evaluate (4 standard errors + 0.3% for the grid), and both stay
  // below the normal-incidence albedo.
  for (double deg : {45.0, 75.0}) {
    Vec3 wo = atAngle(kNormal, deg * kPiD / 180.0);
    MeanWeight mo = meanWeight(b, f, wo, 400000, 23);
    glm::dvec3 integral = hemisphereIntegral(b, f, wo, 1000, 29);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(mo.mean[c], integral[c], 4.0 * mo.se[c] + 0.003 * integral[c]) << deg << " ch " << c;
      EXPECT_LE(integral[c], albedo[c] * 1.005) << deg;
    }
  }

  // Every smooth sample's weight is evaluate / pdf at its direction (1e-5 relative).
  Rng rng(31);
  Vec3 wo = atAngle(kNormal, 0.6);
  int glossy = 0, diffuse = 0;
  for (int i = 0; i < 20000; ++i) {
    float ul = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    BsdfSample s = sampleBsdf(b, f, wo, ul, u1, u2);
    if (!s.valid) continue;
    glossy += (s.flags & kBsdfGlossy) != 0;
    diffuse += (s.flags & kBsdfDiffuse) != 0;
    float pdf = pdfBsdf(b, f, wo, s.wi);
    ASSERT_GT(pdf, 0.0f);
    Color ratio = evaluateBsdf(b, f, wo, s.wi) / pdf;
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.weight[c], ratio[c], 1e-5f * std::max(1.0f, ratio[c])) << i;
  }
  // Lobes are picked by mean reflectance: glossy 0.3 / (0.333 + 0.3) of the time
  // (minus the glossy samples under the horizon); both must occur.
  EXPECT_GT(glossy, 4000);
  EXPECT_GT(diffuse, 8000);
}

TEST(BsdfMirror, DiffusePlusMirrorSplitsByReflectance) {
  // (1 - kr) rho/pi + kr mirror with kr = 0.3, rho = (0.6, 0.3, 0.1) (mean 1/3):
  // the mirror lobe is picked with probability kr / (kr + (1-kr) mean(rho)) = 0.3 / 0.5333,
  // reflects exactly, and the mean weight is the albedo (1 - kr) rho + kr per channel.
  // Tolerance: 4 standard errors (binomial for the lobe fraction).
  const Color rho(0.6f, 0.3f, 0.1f);
  const float kr = 0.3f;
  Bsdf b = physical(opaque(rho, Color(0.0f), 0.0f, kr));
  EXPECT_EQ(bsdfFlags(b), kBsdfDiffuse | kBsdfSpecular);
  EXPECT_TRUE(hasDeltaLobe(b));
  EXPECT_TRUE(hasSmoothLobe(b));
  BsdfFrame f = frameOf(kNormal);
  const Vec3 wo = atAngle(kNormal, 0.8);
  const int n = 400000;
  MeanWeight m = meanWeight(b, f, wo, n, 41);
  const glm::dvec3 albedo = (1.0 - kr) * glm::dvec3(rho) + glm::dvec3(kr);
  expectNearMean(m, albedo, "diffuse + mirror");
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(albedoBsdf(b)[c], albedo[c], 1e-6);
  const double pMirror = kr / (kr + (1.0 - kr) * (0.6 + 0.3 + 0.1) / 3.0);
  EXPECT_NEAR(m.specular / double(n), pMirror, 4.0 * std::sqrt(pMirror * (1 - pMirror) / n));

  // The mirror sample: the exact reflection of wo, and evaluate / pdf ignore it
  // (a delta lobe has no density): evaluate is the diffuse part alone.
  Rng rng(43);
  for (int i = 0; i < 2000; ++i) {
    float ul = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    BsdfSample s = sampleBsdf(b, f, wo, ul, u1, u2);
    ASSERT_TRUE(s.valid);
    if (s.flags & kBsdfSpecular) {
      Vec3 mirror = 2.0f * glm::dot(wo, kNormal) * kNormal - wo;
      EXPECT_NEAR(glm::length(s.wi - mirror), 0.0f, 1e-5f);
      continue;
    }
    float cosI = glm::dot(kNormal, s.wi);
    Color e = evaluateBsdf(b, f, wo, s.wi);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], (1.0f - kr) * rho[c] / kPi * cosI, 1e-6f);
  }
  glm::dvec3 integral = hemisphereIntegral(b, f, wo, 400, 47);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(integral[c], (1.0 - kr) * rho[c], 0.01 * rho[c]);
}

}  // namespace
}  // namespace penumbra
