// Optics and sampling primitives against closed forms: Fresnel (normal, grazing,
// critical angle, energy balance from the s/p transmittances), Snell refraction,
// mirror reflection, the direction samplers, the orthonormal basis, the
// octahedral photon encoding and the self-intersection offset rule.
#include "core/math.h"
#include "core/optics.h"
#include "core/photon.h"
#include "core/rng.h"
#include "core/sampling.h"
#include <gtest/gtest.h>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

// Fresnel in double with an independent derivation of the transmitted side:
// amplitude coefficients t_s, t_p and power transmittance T = (n_t cos_t)/(n_i cos_i) t^2.
struct FresnelRef {
  double rs, rp, ts, tp;  // power reflectances and transmittances
};
FresnelRef fresnelRef(double cosI, double etaI, double etaT) {
  double sinI = std::sqrt(1.0 - cosI * cosI);
  double sinT = etaI / etaT * sinI;
  double cosT = std::sqrt(1.0 - sinT * sinT);
  double rs = (etaI * cosI - etaT * cosT) / (etaI * cosI + etaT * cosT);
  double rp = (etaT * cosI - etaI * cosT) / (etaT * cosI + etaI * cosT);
  double ts = 2.0 * etaI * cosI / (etaI * cosI + etaT * cosT);
  double tp = 2.0 * etaI * cosI / (etaT * cosI + etaI * cosT);
  double k = (etaT * cosT) / (etaI * cosI);
  return {rs * rs, rp * rp, k * ts * ts, k * tp * tp};
}

TEST(Fresnel, NormalIncidenceIsSquaredIndexRatio) {
  for (double n : {1.5, 1.33, 2.4}) {
    double expected = std::pow((n - 1.0) / (n + 1.0), 2.0);
    EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f, static_cast<float>(n)), expected, 1e-6) << "n=" << n;
    // Reciprocity: the same from inside the denser medium.
    EXPECT_NEAR(fresnelDielectric(1.0f, static_cast<float>(n), 1.0f), expected, 1e-6) << "n=" << n;
  }
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f, 1.5f), 0.04, 1e-7);
}

TEST(Fresnel, GrazingIncidenceReflectsEverything) {
  for (float n : {1.33f, 1.5f, 2.4f}) {
    float r = fresnelDielectric(1e-4f, 1.0f, n);
    EXPECT_LE(r, 1.0f);
    EXPECT_NEAR(r, 1.0f, 1e-3f) << "n=" << n;
  }
  EXPECT_EQ(fresnelDielectric(0.0f, 1.0f, 1.5f), 1.0f);
  // Out-of-range cosines are clamped, not extrapolated.
  EXPECT_NEAR(fresnelDielectric(1.5f, 1.0f, 1.5f), 0.04f, 1e-7f);
}

TEST(Fresnel, BeyondCriticalAngleIsTotalReflection) {
  const double critical = std::asin(1.0 / 1.5);  // ~41.81 degrees
  for (double extra : {1e-3, 0.01, 0.1, 0.5, 0.8}) {
    double theta = critical + extra;
    ASSERT_LT(theta, kPi / 2);
    EXPECT_EQ(fresnelDielectric(static_cast<float>(std::cos(theta)), 1.5f, 1.0f), 1.0f) << theta;
  }
  // Just inside the critical angle some light still leaves.
  float below = fresnelDielectric(static_cast<float>(std::cos(critical - 0.01)), 1.5f, 1.0f);
  EXPECT_LT(below, 1.0f);
  // ...but far more is reflected than at normal incidence (0.04).
  EXPECT_GT(below, 0.3f);
  EXPECT_NEAR(below, 1.0 - 0.5 * (fresnelRef(std::cos(critical - 0.01), 1.5, 1.0).ts +
                                  fresnelRef(std::cos(critical - 0.01), 1.5, 1.0).tp),
              1e-4);
  // Entering the denser medium there is no critical angle.
  EXPECT_LT(fresnelDielectric(static_cast<float>(std::cos(critical + 0.5)), 1.0f, 1.5f), 1.0f);
}

TEST(Fresnel, ReflectedPlusTransmittedIsOne) {
  for (auto [etaI, etaT] : {std::pair{1.0, 1.5}, std::pair{1.5, 1.0}, std::pair{1.0, 2.4},
                            std::pair{1.33, 1.0}}) {
    for (double deg : {0.0, 10.0, 25.0, 40.0, 55.0, 70.0, 85.0}) {
      double cosI = std::cos(deg * kPi / 180.0);
      if (etaI / etaT * std::sqrt(1.0 - cosI * cosI) >= 1.0) continue;  // TIR: covered above
      FresnelRef ref = fresnelRef(cosI, etaI, etaT);
      // Each polarisation conserves energy on its own...
      EXPECT_NEAR(ref.rs + ref.ts, 1.0, 1e-12);
      EXPECT_NEAR(ref.rp + ref.tp, 1.0, 1e-12);
      // ...so the transmitted fraction derived from t_s, t_p is 1 - kr.
      float kr = fresnelDielectric(static_cast<float>(cosI), static_cast<float>(etaI),
                                   static_cast<float>(etaT));
      double kt = 0.5 * (ref.ts + ref.tp);
      EXPECT_NEAR(1.0 - kr, kt, 2e-6) << etaI << "->" << etaT << " at " << deg << " deg";
      EXPECT_NEAR(kr, 0.5 * (ref.rs + ref.rp), 2e-6);
    }
  }
}

TEST(Fresnel, HandComputedAt45Degrees) {
  // n = 1.5, theta_i = 45: sin_t = 0.4714, cos_t = 0.8819,
  // R_s = ((0.7071 - 1.3229) / 2.0300)^2 = 0.0920, R_p = (0.1788 / 1.9426)^2 = 0.0085.
  FresnelRef ref = fresnelRef(std::sqrt(0.5), 1.0, 1.5);
  EXPECT_NEAR(ref.rs, 0.0920, 1e-4);
  EXPECT_NEAR(ref.rp, 0.0085, 1e-4);
  EXPECT_NEAR(fresnelDielectric(std::sqrt(0.5f), 1.0f, 1.5f), 0.0502, 1e-4);
  EXPECT_NEAR(fresnelDielectric(std::sqrt(0.5f), 1.0f, 1.5f), 0.5 * (ref.rs + ref.rp), 1e-6);
}

// Unit incident direction at angle theta to -n, tilted towards +x, with n = +z.
Vec3 incident(double theta) {
  return Vec3(static_cast<float>(std::sin(theta)), 0.0f, static_cast<float>(-std::cos(theta)));
}

TEST(Snell, RefractObeysSnellBothWays) {
  // A tilted normal so the check does not rely on axis-aligned arithmetic.
  const Vec3 n = glm::normalize(Vec3(0.3f, -0.2f, 1.0f));
  Vec3 t, b;
  orthonormalBasis(n, t, b);
  for (auto [n1, n2] : {std::pair{1.0f, 1.5f}, std::pair{1.5f, 1.0f}, std::pair{1.0f, 2.4f}}) {
    for (double deg : {0.0, 5.0, 20.0, 35.0, 41.0, 60.0, 80.0, 89.0}) {
      double theta = deg * kPi / 180.0;
      double sinI = std::sin(theta);
      Vec3 d = glm::normalize(static_cast<float>(sinI) * t - static_cast<float>(std::cos(theta)) * n);
      Vec3 out(0.0f);
      bool ok = refract(d, n, n1 / n2, out);
      bool tir = n1 / n2 * sinI > 1.0;
      ASSERT_EQ(ok, !tir) << n1 << "->" << n2 << " at " << deg;
      if (!ok) continue;
      EXPECT_NEAR(glm::length(out), 1.0f, 1e-5f);
      // Far side of the surface.
      EXPECT_LT(glm::dot(out, n), 0.0f);
      // In the plane of incidence (spanned by d and n).
      Vec3 planeNormal = glm::cross(d, n);
      if (glm::length(planeNormal) > 1e-6f) {
        EXPECT_NEAR(glm::dot(out, glm::normalize(planeNormal)), 0.0f, 1e-5f);
      }
      // Snell: n2 sin(theta_t) = n1 sin(theta_i), and bent to the same tangential side.
      double sinT = glm::length(glm::cross(out, n));
      EXPECT_NEAR(n2 * sinT, n1 * sinI, 2e-5) << n1 << "->" << n2 << " at " << deg;
      if (deg > 0.0) {
        EXPECT_GT(glm::dot(out, t), 0.0f);
      }
    }
  }
}

TEST(Snell, RefractReportsTotalInternalReflection) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  const double critical = std::asin(1.0 / 1.5);
  Vec3 out(7.0f);
  EXPECT_FALSE(refract(incident(critical + 0.01), n, 1.5f, out));
  EXPECT_FALSE(refract(incident(1.5), n, 1.5f, out));
  EXPECT_TRUE(refract(incident(critical - 0.01), n, 1.5f, out));
  // Just under the critical angle the transmitted ray skims the surface.
  EXPECT_LT(-out.z, 0.2f);
  // Normal incidence passes straight through.
  ASSERT_TRUE(refract(Vec3(0, 0, -1), n, 1.5f, out));
  EXPECT_NEAR(out.x, 0.0f, 1e-7f);
  EXPECT_NEAR(out.z, -1.0f, 1e-7f);
}

TEST(Reflect, AngleInEqualsAngleOut) {
  Rng rng(42);
  for (int i = 0; i < 200; ++i) {
    Vec3 n = uniformSphere(rng.uniform(), rng.uniform());
    Vec3 d = uniformSphere(rng.uniform(), rng.uniform());
    if (glm::dot(d, n) > 0.0f) d = -d;
    Vec3 r = reflect(d, n);
    EXPECT_NEAR(glm::length(r), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(r, n), -glm::dot(d, n), 1e-5f);  // angle in = angle out
    // Tangential part unchanged (which also puts r in the plane of d and n).
    Vec3 tanD = d - glm::dot(d, n) * n, tanR = r - glm::dot(r, n) * n;
    EXPECT_NEAR(glm::length(tanD - tanR), 0.0f, 1e-5f);
    Vec3 plane = glm::cross(d, n);
    if (glm::length(plane) > 1e-3f) {
      EXPECT_NEAR(glm::dot(r, glm::normalize(plane)), 0.0f, 1e-5f);
    }
  }
  Vec3 r = reflect(glm::normalize(Vec3(1, 0, -1)), Vec3(0, 0, 1));
  EXPECT_NEAR(r.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(r.z, std::sqrt(0.5f), 1e-6f);
}

TEST(Sampling, UniformSphereHasZeroMeanAndUniformZ) {
  Rng rng(7);
  const int n = 200000, bins = 20;
  std::vector<int> hist(bins, 0);
  glm::dvec3 sum(0.0);
  for (int i = 0; i < n; ++i) {
    Vec3 d = uniformSphere(rng.uniform(), rng.uniform());
    ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
    sum += glm::dvec3(d);
    int bin = std::min(bins - 1, static_cast<int>((d.z + 1.0f) * 0.5f * bins));
    ++hist[bin];
  }
  // Each component has variance 1/3: 4 sigma of the mean is 4 / sqrt(3 n).
  double tol = 4.0 / std::sqrt(3.0 * n);
  EXPECT_NEAR(sum.x / n, 0.0, tol);
  EXPECT_NEAR(sum.y / n, 0.0, tol);
  EXPECT_NEAR(sum.z / n, 0.0, tol);
  // Archimedes: z is uniform on [-1, 1]. Chi-square with 19 dof has mean 19, sd ~6.2;
  // 50 is beyond the 99.99th percentile, while a cos-weighted z would score thousands.
  double expected = static_cast<double>(n) / bins, chi2 = 0.0;
  for (int c : hist) chi2 += (c - expected) * (c - expected) / expected;
  EXPECT_LT(chi2, 50.0);
}

TEST(Sampling, CosineHemisphereMeanCosineIsTwoThirds) {
  Rng rng(11);
  const int n = 200000;
  double sumCos = 0.0, sumCos2 = 0.0;
  for (int i = 0; i < n; ++i) {
    Vec3 d = cosineHemisphere(rng.uniform(), rng.uniform());
    ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
    ASSERT_GE(d.z, 0.0f);
    sumCos += d.z;
    sumCos2 += d.z * d.z;
  }
  // pdf cos/pi: E[cos] = 2/3, E[cos^2] = 1/2, so var = 1/18.
  double tol = 4.0 * std::sqrt(1.0 / 18.0 / n);
  EXPECT_NEAR(sumCos / n, 2.0 / 3.0, tol);
  EXPECT_NEAR(sumCos2 / n, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / n));
  // Uniform hemisphere for contrast: E[cos] = 1/2.
  double uni = 0.0;
  for (int i = 0; i < n; ++i) uni += uniformHemisphere(rng.uniform(), rng.uniform()).z;
  EXPECT_NEAR(uni / n, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / n));
}

void expectOrthonormal(const Vec3& n) {
  Vec3 t, b;
  orthonormalBasis(n, t, b);
  EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f) << n.x << "," << n.y << "," << n.z;
  EXPECT_NEAR(glm::length(b), 1.0f, 1e-5f) << n.x << "," << n.y << "," << n.z;
  EXPECT_NEAR(glm::dot(t, b), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(b, n), 0.0f, 1e-5f);
  // Right-handed: t x b = n.
  EXPECT_NEAR(glm::length(glm::cross(t, b) - n), 0.0f, 1e-5f) << n.x << "," << n.y << "," << n.z;
  // toWorld maps +z onto n.
  EXPECT_NEAR(glm::length(toWorld(Vec3(0, 0, 1), n) - n), 0.0f, 1e-6f);
}

TEST(Basis, OrthonormalForManyNormals) {
  for (Vec3 n : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0),
                 Vec3(0, -1, 0), Vec3(1, 0, -0.0f), glm::normalize(Vec3(1e-4f, 0, -1)),
                 glm::normalize(Vec3(0, 1e-6f, -1)), glm::normalize(Vec3(1, 1, 1))}) {
    expectOrthonormal(n);
  }
  Rng rng(3);
  for (int i = 0; i < 2000; ++i) expectOrthonormal(uniformSphere(rng.uniform(), rng.uniform()));
}

double angleBetween(const Vec3& a, const Vec3& b) {
  glm::dvec3 da(a), db(b);
  return std::atan2(glm::length(glm::cross(da, db)), glm::dot(da, db));
}

TEST(Octahedral, RoundTripIsAccurate) {
  std::vector<Vec3> dirs = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0),
                            Vec3(0, 0, 1), Vec3(0, 0, -1), glm::normalize(Vec3(1, 1, -1)),
                            glm::normalize(Vec3(-1, -1, -1)), glm::normalize(Vec3(-1, 1e-5f, -1)),
                            glm::normalize(Vec3(1e-6f, -1e-6f, -1))};
  Rng rng(5);
  for (int i = 0; i < 20000; ++i) dirs.push_back(uniformSphere(rng.uniform(), rng.uniform()));
  double worst = 0.0;
  for (const Vec3& d : dirs) {
    Vec3 back = decodeOctahedral(encodeOctahedral(d));
    EXPECT_NEAR(glm::length(back), 1.0f, 1e-5f);
    double err = angleBetween(d, back);
    worst = std::max(worst, err);
    ASSERT_LT(err, 1e-3) << d.x << "," << d.y << "," << d.z;
  }
  // The header promises ~0.005 degrees worst case; allow 2x.
  EXPECT_LT(worst, 0.01 * kPi / 180.0);
  // Axes come back exactly.
  Vec3 down = decodeOctahedral(encodeOctahedral(Vec3(0, 0, -1)));
  EXPECT_NEAR(down.z, -1.0f, 1e-6f);
  Vec3 up = decodeOctahedral(encodeOctahedral(Vec3(0, 0, 1)));
  EXPECT_NEAR(up.z, 1.0f, 1e-6f);
}

TEST(Offset, MovesPastTheErrorBoundToDirsSide) {
  // Exactly `error` along +/-ng, then one more ulp away on every axis ng moves.
  const Vec3 p(100.0f, 0.0f, 3.0f), ng(0.0f, 0.0f, 1.0f);
  const float error = gammaBound(7) * 100.0f;
  const Vec3 above = offsetRayOrigin(p, ng, error, Vec3(0.6f, 0.0f, 0.8f));
  const Vec3 below = offsetRayOrigin(p, ng, error, Vec3(0.6f, 0.0f, -0.8f));
  EXPECT_EQ(above.z, std::nextafter(3.0f + error, kInf));
  EXPECT_EQ(below.z, std::nextafter(3.0f - error, -kInf));
  EXPECT_EQ(above.x, p.x);
  EXPECT_EQ(above.y, p.y);
  // No absolute floor: the same hit scaled by 1e-6 moves 1e-6 as far (to rounding).
  const float s = 1e-6f;
  const Vec3 small = offsetRayOrigin(p * s, ng, error * s, Vec3(0.0f, 0.0f, 1.0f));
  EXPECT_NEAR((small.z - 3.0f * s) / s, above.z - 3.0f, 0.01f * (above.z - 3.0f));
  // A zero error still leaves the plane: one ulp, even at 0.
  const Vec3 off0 = offsetRayOrigin(Vec3(1.0f, 0.0f, 1.0f), Vec3(0.0f, 1.0f, 0.0f), 0.0f, Vec3(0, 1, 0));
  EXPECT_GT(off0.y, 0.0f);
}

TEST(Offset, GammaBoundIsHighamsConstant) {
  const double u = std::numeric_limits<float>::epsilon() * 0.5;
  EXPECT_FLOAT_EQ(gammaBound(7), static_cast<float>(7 * u / (1 - 7 * u)));
  EXPECT_GT(gammaBound(7), 7.0f * 0x1p-24f);
}

}  // namespace
}  // namespace penumbra
