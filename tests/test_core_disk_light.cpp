// The disk light against its analytic answers: the irradiance of a Lambertian disc on
// its axis (pi L R^2 / (R^2 + h^2)) in closed form and by sampling, off the axis against
// a brute-force double integral, its photons' power and spread, and its surface's area.
#include "core/light_sample.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

constexpr double kPiD = 3.14159265358979323846;

Light disk(const Vec3& centre, const Vec3& normal, float radius, float radiance) {
  Light l;
  l.type = LightType::Disk;
  l.position = centre;
  l.direction = glm::normalize(normal);
  l.radius = radius;
  l.intensity = radiance;
  return l;
}

// E = L integral of cos_r cos_l / d^2 over the disc, on a polar midpoint grid in double.
double bruteForceIrradiance(const Light& l, const Vec3& pf, const Vec3& nf) {
  const glm::dvec3 p(pf), n(nf), c(l.position), nl(l.direction);
  Vec3 tf, bf;
  orthonormalBasis(l.direction, tf, bf);
  const glm::dvec3 t(tf), b(bf);
  const int rings = 600, spokes = 600;
  const double R = l.radius, dr = R / rings, dphi = 2.0 * kPiD / spokes;
  double sum = 0.0;
  for (int i = 0; i < rings; ++i) {
    const double r = (i + 0.5) * dr;
    for (int j = 0; j < spokes; ++j) {
      const double phi = (j + 0.5) * dphi;
      const glm::dvec3 d = c + r * (std::cos(phi) * t + std::sin(phi) * b) - p;
      const double d2 = glm::dot(d, d), dl = std::sqrt(d2);
      const double cosR = glm::dot(n, d) / dl, cosL = -glm::dot(nl, d) / dl;
      if (cosR > 0.0 && cosL > 0.0) sum += cosR * cosL / d2 * r * dr * dphi;
    }
  }
  return l.intensity * sum;
}

// The sampled estimate of E: the mean of L / pdf x cos over n samples.
double sampledIrradiance(const Light& l, const Vec3& p, const Vec3& n, int count) {
  const LightSampler s = prepareLight(l, p);
  Rng rng(11);
  double sum = 0.0;
  for (int i = 0; i < count; ++i) {
    const float u1 = rng.uniform(), u2 = rng.uniform();
    const LightIncidence in = sampleLight(s, u1, u2);
    if (in.valid) sum += double(in.radiance.r) * std::max(0.0, double(glm::dot(n, in.wi)));
  }
  return sum / count;
}

TEST(DiskLight, OnItsAxisIrradianceIsPiLR2OverR2PlusH2) {
  const float L = 3.0f, R = 0.5f;
  const Light l = disk(Vec3(0.2f, 2.0f, -0.1f), Vec3(0, -1, 0), R, L);
  for (float h : {0.1f, 0.5f, 1.0f, 2.0f, 8.0f}) {
    const Vec3 p = l.position + h * l.direction, n = -l.direction;  // facing the disc
    const double want = kPiD * L * R * R / (double(R) * R + double(h) * h);
    Color E;
    ASSERT_TRUE(unoccludedIrradiance(prepareLight(l, p), n, n, E)) << h;
    EXPECT_NEAR(E.r, want, 1e-5 * want) << "closed form, h " << h;
    // Below h ~ R / 2 the estimate's spread (L A h^2 / d^4) needs far more samples.
    if (h >= 0.5f) {
      EXPECT_NEAR(sampledIrradiance(l, p, n, 400000), want, 0.005 * want) << "sampled, h " << h;
    }
  }
}

// Off the axis and tilted, wherever the disc is above both horizons: the closed form's
// vector irradiance against the integral; cut by a horizon it declines (false).
TEST(DiskLight, OffTheAxisTheClosedFormIsTheIntegral) {
  const Light l = disk(Vec3(0.0f, 1.0f, 0.0f), Vec3(0.3f, -1.0f, 0.2f), 0.6f, 2.0f);
  const struct {
    Vec3 p, n;
  } cases[] = {{Vec3(0.0f, 0.0f, 0.0f), Vec3(0, 1, 0)},
               {Vec3(1.5f, 0.2f, -0.7f), Vec3(0, 1, 0)},
               {Vec3(-0.4f, -0.5f, 0.3f), glm::normalize(Vec3(0.5f, 1.0f, 0.0f))},
               {Vec3(3.0f, -2.0f, 1.0f), glm::normalize(Vec3(-0.4f, 1.0f, -0.2f))}};
  for (const auto& c : cases) {
    Color E;
    ASSERT_TRUE(unoccludedIrradiance(prepareLight(l, c.p), c.n, c.n, E)) << c.p.x;
    const double want = bruteForceIrradiance(l, c.p, c.n);
    EXPECT_NEAR(E.r, want, 1e-4 * want) << c.p.x;
    EXPECT_NEAR(sampledIrradiance(l, c.p, c.n, 400000), want, 0.01 * want) << c.p.x;
  }
  Color E;
  EXPECT_FALSE(unoccludedIrradiance(prepareLight(l, Vec3(0.0f, 1.05f, 2.0f)), Vec3(0, 1, 0), Vec3(0, 1, 0), E))
      << "a horizon through the disc: sample";
  EXPECT_TRUE(unoccludedIrradiance(prepareLight(l, Vec3(0.0f, 3.0f, 0.0f)), Vec3(0, -1, 0), Vec3(0, -1, 0), E));
  EXPECT_EQ(E.r, 0.0f) << "behind its emitting side";
}

// Photons leave the disc (uniform by area: mean squared radius R^2 / 2) on its emitting
// side, cosine-weighted (mean cos 2/3), and count of them carry its power pi (pi R^2) L.
TEST(DiskLight, PhotonsCarryItsPowerFromItsSurface) {
  const Light l = disk(Vec3(1.0f, 2.0f, 3.0f), Vec3(0.2f, -1.0f, 0.1f), 0.4f, 5.0f);
  const SceneSphere bounds{Vec3(0.0f), 10.0f};
  const double power = kPiD * (kPiD * 0.4 * 0.4) * 5.0;
  EXPECT_NEAR(lightPower(l, bounds).r, power, 1e-5 * power);
  const int count = 200000;
  const Color each = classicPhotonPower(l, bounds, float(count));
  Rng rng(5);
  double carried = 0.0, r2 = 0.0, cosine = 0.0;
  for (int i = 0; i < count; ++i) {
    const PhotonRay r = classicPhotonStart(l, bounds, rng);
    carried += double(each.r) * r.weight.r;
    const Vec3 q = r.origin - l.position;
    const float height = glm::dot(q, l.direction);
    ASSERT_GT(height, 0.0f) << "lifted off its emitting side";
    ASSERT_LT(height, 1e-4f);
    r2 += glm::dot(q, q) - height * height;
    cosine += glm::dot(r.dir, l.direction);
  }
  EXPECT_NEAR(carried, power, 0.01 * power);
  EXPECT_NEAR(r2 / count, 0.5 * 0.4 * 0.4, 0.01 * 0.08);
  EXPECT_NEAR(cosine / count, 2.0 / 3.0, 0.01);
}

// Its surface: a fan whose area is pi R^2, every triangle facing its emitting side.
TEST(DiskLight, ItsSurfaceIsAOneSidedFanOfItsArea) {
  const Light l = disk(Vec3(0.0f, 2.0f, 0.0f), Vec3(0.0f, -1.0f, 0.5f), 0.7f, 1.0f);
  const EmitterShape e = emitterOf(l);
  ASSERT_TRUE(e.mesh.has_value());
  EXPECT_FALSE(e.sphere.has_value());
  EXPECT_FALSE(e.twoSided);
  double area = 0.0;
  for (const auto& t : e.mesh->triangles) {
    const glm::dvec3 a(e.mesh->positions[t[0]]), b(e.mesh->positions[t[1]]), c(e.mesh->positions[t[2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    EXPECT_GT(glm::dot(n, glm::dvec3(l.direction)), 0.0);
    area += 0.5 * glm::length(n);
  }
  EXPECT_NEAR(area, kPiD * 0.7 * 0.7, 1e-5 * area);
  EXPECT_NEAR(lightArea(l), kPiD * 0.7 * 0.7, 1e-6);
}

}  // namespace
}  // namespace penumbra
