// Glass and the classic BSDF against their definitions: glass reflects with the
// Fresnel probability (computed in double from the textbook formula), always
// reflects beyond the critical angle and tints only what enters; the classic Phong
// evaluate is k_d cos + k_s (R.V)^n term for term and its roulette never gains.
#include "support/bsdf_sampling.h"

namespace penumbra {
namespace {

TEST(BsdfDielectric, ReflectsWithTheFresnelProbability) {
  // Smooth glass, ior 1.5: reflect with probability F(theta), weight 1; refract
  // with 1 - F, weight 1 (tint 1). Reference F from the s/p formulas in double;
  // literature values: F(0) = ((1.5-1)/(1.5+1))^2 = 0.04, F(60 deg) = 0.0892.
  // Tolerance: 4 binomial standard deviations of the reflected fraction (N = 400k).
  Bsdf b = physical(glass(1.5f));
  EXPECT_EQ(b.type, BsdfType::Dielectric);
  EXPECT_EQ(bsdfFlags(b), kBsdfSpecular | kBsdfTransmission);
  EXPECT_NEAR(fresnelRef(1.0, 1.0, 1.5), 0.04, 1e-12);
  EXPECT_NEAR(fresnelRef(std::cos(60.0 * kPiD / 180.0), 1.0, 1.5), 0.0892, 2e-4);
  const int n = 400000;
  struct Case {
    double deg;
    bool outside;
  };
  for (Case cs : {Case{0.0, true}, Case{60.0, true}, Case{85.0, true}, Case{0.0, false},
                  Case{30.0, false}}) {
    const double theta = cs.deg * kPiD / 180.0;
    const double n1 = cs.outside ? 1.0 : 1.5, n2 = cs.outside ? 1.5 : 1.0;
    const double expected = fresnelRef(std::cos(theta), n1, n2);
    BsdfFrame f = frameOf(kNormal, cs.outside);
    Vec3 wo = atAngle(kNormal, theta);
    MeanWeight m = meanWeight(b, f, wo, n, 53 + static_cast<uint64_t>(cs.deg));
    const double reflected = double(n - m.transmitted) / n;
    const double sd = std::sqrt(expected * (1 - expected) / n);
    std::string what = std::to_string(cs.deg) + (cs.outside ? " deg from outside" : " deg from inside");
    EXPECT_NEAR(reflected, expected, 4.0 * sd + 1e-6) << what;
    EXPECT_EQ(m.invalid, 0) << what;
    EXPECT_EQ(m.specular, n) << what;  // every sample is a delta lobe
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.mean[c], 1.0, 1e-6) << what;  // weight 1 always

    // Directions: the mirror of wo, or Snell's law on the other side.
    Rng rng(59);
    for (int i = 0; i < 2000; ++i) {
      BsdfSample s = sampleBsdf(b, f, wo, rng.uniform(), 0.5f, 0.5f);
      if (s.flags & kBsdfTransmission) {
        double cosT = -glm::dot(s.wi, kNormal);
        ASSERT_GT(cosT, 0.0) << what;
        double sinT = std::sqrt(std::max(0.0, 1.0 - cosT * cosT));
        EXPECT_NEAR(sinT, n1 / n2 * std::sin(theta), 1e-5) << what;
        // In the plane of incidence, on the far side of the normal from wo.
        Vec3 tanWo = wo - glm::dot(wo, kNormal) * kNormal, tanWi = s.wi - glm::dot(s.wi, kNormal) * kNormal;
        if (theta > 0.0) {
          EXPECT_LT(glm::dot(tanWo, tanWi), 0.0f) << what;
        }
      } else {
        Vec3 mirror = 2.0f * glm::dot(wo, kNormal) * kNormal - wo;
        EXPECT_NEAR(glm::length(s.wi - mirror), 0.0f, 1e-5f) << what;
      }
    }
  }
  // A dielectric has only delta lobes: nothing to evaluate, no density.
  BsdfFrame f = frameOf(kNormal);
  EXPECT_EQ(evaluateBsdf(b, f, kNormal, atAngle(kNormal, 0.4)), Color(0.0f));
  EXPECT_EQ(pdfBsdf(b, f, kNormal, atAngle(kNormal, 0.4)), 0.0f);
}

TEST(BsdfDielectric, TotalInternalReflectionBeyondTheCriticalAngle) {
  // From inside ior 1.5 the critical angle is asin(1/1.5) = 41.81 deg: at 42, 50 and
  // 80 deg every sample reflects (exactly: no statistics), with weight 1.
  Bsdf b = physical(glass(1.5f, Color(0.5f)));
  BsdfFrame f = frameOf(kNormal, /*outside=*/false);
  for (double deg : {42.0, 50.0, 80.0}) {
    Vec3 wo = atAngle(kNormal, deg * kPiD / 180.0);
    MeanWeight m = meanWeight(b, f, wo, 20000, 61);
    EXPECT_EQ(m.transmitted, 0) << deg;
    EXPECT_EQ(m.specular, 20000) << deg;
    EXPECT_EQ(m.mean, glm::dvec3(1.0)) << deg;  // no tint on a reflection
  }
  // Just inside the critical angle light still gets out (F < 1).
  Vec3 wo = atAngle(kNormal, 41.0 * kPiD / 180.0);
  MeanWeight m = meanWeight(b, f, wo, 20000, 67);
  EXPECT_GT(m.transmitted, 0);
}

TEST(BsdfDielectric, TintFiltersOnlyLightEnteringTheGlass) {
  // Normal incidence, tint (0.5, 0.7, 0.9): from outside the mean weight is
  // F0 + (1 - F0) tint = 0.04 + 0.96 tint; from inside no tint applies (mean 1).
  // Tolerance: 4 standard errors of the mean weight (N = 400k).
  const Color tint(0.5f, 0.7f, 0.9f);
  Bsdf b = physical(glass(1.5f, tint));
  MeanWeight out = meanWeight(b, frameOf(kNormal, true), kNormal, 400000, 71);
  glm::dvec3 expected = 0.04 + 0.96 * glm::dvec3(tint);
  expectNearMean(out, expected, "entering");
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(albedoBsdf(b)[c], expected[c], 1e-5);
  MeanWeight in = meanWeight(b, frameOf(kNormal, false), kNormal, 20000, 73);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(in.mean[c], 1.0, 1e-6);
  // Refracted samples carry exactly the tint on entering.
  Rng rng(79);
  for (int i = 0; i < 1000; ++i) {
    BsdfSample s = sampleBsdf(b, frameOf(kNormal, true), kNormal, rng.uniform(), 0.5f, 0.5f);
    if (s.flags & kBsdfTransmission) EXPECT_EQ(s.weight, tint);
    else EXPECT_EQ(s.weight, Color(1.0f));
  }
}

TEST(BsdfClassic, EvaluateIsKdCosPlusKsRdotVToTheN) {
  // The report's Phong: k_d (N.L) + k_s (R.V)^n with R = 2 (N.L) N - L, computed
  // here in double for random light/view pairs. Tolerance 1e-5 (float rounding).
  Material m = opaque(Color(0.7f, 0.4f, 0.2f), Color(0.5f, 0.6f, 0.3f), 12.0f);
  Bsdf b = makeBsdf(m, BsdfFamily::Phong, HemisphereSampling::Uniform);
  EXPECT_EQ(b.type, BsdfType::ClassicPhong);
  BsdfFrame f = frameOf(kNormal);
  const glm::dvec3 N(kNormal);
  Rng rng(83);
  int withHighlight = 0;
  for (int i = 0; i < 5000; ++i) {
    Vec3 wi = toWorld(uniformHemisphere(rng.uniform(), rng.uniform()), kNormal);
    Vec3 wo = toWorld(uniformHemisphere(rng.uniform(), rng.uniform()), kNormal);
    const glm::dvec3 L(wi), V(wo);
    double nl = glm::dot(N, L);
    glm::dvec3 R = 2.0 * nl * N - L;
    double rv = glm::dot(R, V);
    glm::dvec3 expected = glm::dvec3(m.diffuse) * std::max(0.0, nl);
    if (nl > 0.0 && rv > 0.0) {
      expected += glm::dvec3(m.specular) * std::pow(rv, 12.0);
      withHighlight += std::pow(rv, 12.0) > 0.1;
    }
    Color got = evaluateBsdf(b, f, wo, wi);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], expected[c], 1e-5 * (1.0 + expected[c])) << i;
  }
  EXPECT_GT(withHighlight, 20);  // the specular term was exercised
  // Light from below the surface: nothing.
  EXPECT_EQ(evaluateBsdf(b, f, kNormal, -kNormal), Color(0.0f));
}

TEST(BsdfClassic, RouletteMeanWeightIsTheAlbedo) {
  // The report's roulette with p_r = 0.6: a survivor's weight is colour / max(colour)
  // (times 2 cos for a uniform bounce, whose mean is 1), so the mean weight is
  // p_r colour / max(colour) per channel, and no channel exceeds p_r. 4 s.e.
  Material m = opaque(Color(0.9f, 0.45f, 0.09f));
  m.pR = 0.6f;
  for (HemisphereSampling hs : {HemisphereSampling::Uniform, HemisphereSampling::Cosine}) {
    Bsdf b = makeBsdf(m, BsdfFamily::Phong, hs);
    MeanWeight w = meanWeight(b, frameOf(kNormal), kNormal, 400000, 89);
    glm::dvec3 expected = 0.6 * glm::dvec3(1.0, 0.5, 0.1);
    expectNearMean(w, expected, hs == HemisphereSampling::Uniform ? "uniform" : "cosine");
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(albedoBsdf(b)[c], expected[c], 1e-6);
    EXPECT_NEAR(double(w.invalid) / 400000, 0.4, 4.0 * std::sqrt(0.24 / 400000));
  }
}

}  // namespace
}  // namespace penumbra
