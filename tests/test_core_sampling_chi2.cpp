// Chi-squared goodness of fit of the samplers against their densities: sampleBsdf
// against pdfBsdf (the physical model's Lambert and normalised Phong lobes, with and
// without a mirror lobe, whose delta samples are left out) and against the classic
// model's documented photon bounce; sampleLight against the solid-angle pdf its
// radiance divides by (quad and disk: d^2 / (A cos_l); sphere: uniform over the cone).
//
// Each case draws kSamples directions with a fixed seed and bins them on a
// (theta, phi) grid about an axis (the shading normal; the direction to the light);
// each cell's expected count is kSamples x the pdf integrated over the cell
// (midpoint rule on a sub-grid, solid angle sin(theta) dtheta dphi). Invalid and
// delta samples are not binned: the histogram is tested against the pdf's shape
// (its share of the binned samples) and the binned fraction against the pdf's
// integral. Cells expecting < 5 are pooled; the p-value comes from the regularized
// incomplete gamma function (support/chi2.h). Every case must pass at the Sidak
// level for a family-wise 1% false alarm rate over all kCases cases in this file.
#include "core/bsdf.h"
#include "core/light_sample.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "support/bsdf_sampling.h"
#include "support/chi2.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

namespace penumbra {
namespace {

constexpr int kThetaBins = 10, kPhiBins = 20;
constexpr int kSamples = 500000;
constexpr double kFamilyAlpha = 0.01;

// Directions on a (theta, phi) grid about `axis`, theta in [0, thetaMax].
struct Grid {
  glm::dvec3 axis, t, b;
  double thetaMax;
  Grid(const Vec3& a, double thetaRange) : thetaMax(thetaRange) {
    Vec3 tf, bf;
    orthonormalBasis(a, tf, bf);
    axis = glm::dvec3(a);
    t = glm::dvec3(tf);
    b = glm::dvec3(bf);
  }
  int cells() const { return kThetaBins * kPhiBins; }
  int cellOf(const Vec3& wf) const {
    const glm::dvec3 w = glm::normalize(glm::dvec3(wf));
    const double x = glm::dot(w, t), y = glm::dot(w, b), z = glm::dot(w, axis);
    const double theta = std::atan2(std::sqrt(x * x + y * y), z);
    double phi = std::atan2(y, x);
    if (phi < 0.0) phi += 2.0 * kPiD;
    const int i = std::clamp(int(theta / thetaMax * kThetaBins), 0, kThetaBins - 1);
    const int j = std::clamp(int(phi / (2.0 * kPiD) * kPhiBins), 0, kPhiBins - 1);
    return i * kPhiBins + j;
  }
  Vec3 direction(double theta, double phi) const {
    return Vec3(std::sin(theta) * (std::cos(phi) * t + std::sin(phi) * b) + std::cos(theta) * axis);
  }
  // Integral of pdf over each cell in solid angle, on sub x sub midpoints per cell.
  std::vector<double> integrate(const std::function<double(const Vec3&)>& pdf, int sub) const {
    std::vector<double> mass(cells(), 0.0);
    const double dTheta = thetaMax / (kThetaBins * sub), dPhi = 2.0 * kPiD / (kPhiBins * sub);
    for (int i = 0; i < kThetaBins * sub; ++i) {
      const double theta = (i + 0.5) * dTheta, weight = std::sin(theta) * dTheta * dPhi;
      for (int j = 0; j < kPhiBins * sub; ++j) {
        const double phi = (j + 0.5) * dPhi;
        mass[(i / sub) * kPhiBins + j / sub] += pdf(direction(theta, phi)) * weight;
      }
    }
    return mass;
  }
};

// The shape: Pearson's test of the binned samples against their share of the
// integrated pdf. The mass: the fraction binned (valid, not delta) against the
// pdf's integral, which the shape alone would miss (a pdf off by a constant
// factor), within 5 standard errors plus the midpoint rule's error (< 3e-4 here).
chi2::Result runTest(const std::vector<double>& binned, double unbinned, const std::vector<double>& mass,
                     const std::string& name) {
  double total = 0.0, count = 0.0;
  for (size_t i = 0; i < mass.size(); ++i) {
    total += mass[i];
    count += binned[i];
  }
  const double fraction = count / (count + unbinned);
  const double p = std::clamp(total, 0.0, 1.0);
  EXPECT_NEAR(fraction, total, 5.0 * std::sqrt(p * (1.0 - p) / (count + unbinned)) + 3e-4)
      << name << ": the share of samples the pdf covers";
  std::vector<double> expected(mass.size());
  for (size_t i = 0; i < mass.size(); ++i) expected[i] = count * mass[i] / total;
  return chi2::test(binned, expected, count);
}

struct BsdfCase {
  const char* name;
  Bsdf bsdf;
  double woDegrees;
  bool classicReference = false;  // test against the classic photon bounce, not pdfBsdf
};

Bsdf classic(float pR, float pT, HemisphereSampling bounce) {
  Material m;
  m.diffuse = Color(0.7f, 0.5f, 0.3f);
  m.specular = Color(0.3f);
  m.shininess = 20.0f;
  m.pR = pR;
  m.pT = pT;
  return makeBsdf(m, BsdfFamily::Phong, bounce);
}

std::vector<BsdfCase> bsdfCases() {
  const Bsdf lambert = physical(opaque(Color(0.8f)));
  const Bsdf plastic = physical(opaque(Color(0.5f, 0.4f, 0.3f), Color(0.4f), 20.0f));
  const Bsdf glossy = physical(opaque(Color(0.0f), Color(0.9f), 60.0f));
  const Bsdf broad = physical(opaque(Color(0.1f), Color(0.8f), 3.0f));
  const Bsdf mirrored = physical(opaque(Color(0.6f), Color(0.3f), 10.0f, 0.3f));
  return {
      {"lambert_0", lambert, 0.0},
      {"lambert_70", lambert, 70.0},
      {"plastic_10", plastic, 10.0},
      {"plastic_45", plastic, 45.0},
      {"plastic_80", plastic, 80.0},  // the lobe is cut by the horizon
      {"glossy60_30", glossy, 30.0},
      {"glossy60_85", glossy, 85.0},
      {"broad3_60", broad, 60.0},
      {"mirror_plus_glossy_30", mirrored, 30.0},  // kr = 0.3: delta samples unbinned
      // The classic model's sampleBsdf is the photon bounce (p_r diffuse, p_t
      // refraction, else absorbed) and pdfBsdf is 0 for it, so it is tested
      // against the bounce the report documents: p_r x uniform or cosine.
      {"classic_uniform_40", classic(0.6f, 0.0f, HemisphereSampling::Uniform), 40.0, true},
      {"classic_cosine_40", classic(0.5f, 0.3f, HemisphereSampling::Cosine), 40.0, true},
      // GGX metallic-roughness at alpha 0.1, 0.5 and 1: metals and dielectrics.
      {"metal_a0.1_30", metalRough(Color(0.9f, 0.6f, 0.3f), 1.0f, 0.1f), 30.0},
      {"metal_a0.5_60", metalRough(Color(0.9f, 0.6f, 0.3f), 1.0f, 0.5f), 60.0},
      {"metal_a1_0", metalRough(Color(0.9f, 0.6f, 0.3f), 1.0f, 1.0f), 0.0},
      {"plastic_a0.1_45", metalRough(Color(0.2f, 0.5f, 0.8f), 0.0f, 0.1f), 45.0},
      {"plastic_a0.5_80", metalRough(Color(0.2f, 0.5f, 0.8f), 0.0f, 0.5f), 80.0},
      {"half_metal_a1_20", metalRough(Color(0.7f), 0.5f, 1.0f), 20.0},
  };
}

struct LightCase {
  const char* name;
  Light light;
  Vec3 p;
};

Light quad(const Vec3& corner, const Vec3& e1, const Vec3& e2) {
  Light l;
  l.type = LightType::Quad;
  l.position = corner;
  l.edge1 = e1;
  l.edge2 = e2;
  l.color = Color(1.0f, 0.8f, 0.6f);
  l.intensity = 5.0f;
  return l;
}

Light sphere(const Vec3& centre, float radius) {
  Light l;
  l.type = LightType::Sphere;
  l.position = centre;
  l.radius = radius;
  l.color = Color(1.0f, 0.8f, 0.6f);
  l.intensity = 5.0f;
  return l;
}

// A disc of radius r about `centre` emitting along `normal`.
Light disk(const Vec3& centre, const Vec3& normal, float radius) {
  Light l = sphere(centre, radius);
  l.type = LightType::Disk;
  l.direction = glm::normalize(normal);
  return l;
}

std::vector<LightCase> lightCases() {
  // A 2 x 1 quad at y = 2 emitting downwards (edge1 x edge2 points to -y).
  const Light q = quad(Vec3(-1.0f, 2.0f, -0.5f), Vec3(2.0f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 1.0f));
  const Light s = sphere(Vec3(0.3f, 1.0f, -0.2f), 0.5f);
  const Light d = disk(Vec3(0.2f, 2.0f, -0.3f), Vec3(0.2f, -1.0f, 0.1f), 0.6f);
  return {
      {"disk_below", d, Vec3(0.0f, 0.0f, 0.1f)},
      {"disk_close", d, Vec3(0.5f, 1.4f, -0.1f)},
      {"disk_grazing", d, Vec3(4.0f, 2.5f, 0.3f)},
      {"quad_below", q, Vec3(0.1f, 0.0f, 0.2f)},
      {"quad_close", q, Vec3(0.4f, 1.6f, 0.1f)},   // solid-angle pdf varies ~10x over it
      {"quad_grazing", q, Vec3(4.0f, 1.5f, 0.3f)},  // seen almost edge on
      {"sphere_close", s, Vec3(0.35f, 0.4f, -0.2f)},  // d = 1.2 r
      {"sphere_mid", s, Vec3(-1.0f, -0.5f, 0.6f)},
      {"sphere_far", s, Vec3(20.0f, -30.0f, 10.0f)},  // a cone of ~1 degree
  };
}

const int kCases = int(bsdfCases().size() + lightCases().size());
const double kLevel = chi2::sidakLevel(kFamilyAlpha, kCases);

// The classic photon bounce's density: p_r x (uniform 1 / 2 pi, or cos / pi) about ng.
double classicBouncePdf(const Bsdf& b, const BsdfFrame& f, const Vec3& wi) {
  const double c = glm::dot(glm::dvec3(f.ng), glm::dvec3(wi));
  if (c <= 0.0) return 0.0;
  return b.pR * (b.uniformBounce ? 1.0 / (2.0 * kPiD) : c / kPiD);
}

void expectPasses(const chi2::Result& r, const std::string& name) {
  EXPECT_TRUE(r.failure.empty()) << name << ": " << r.failure;
  EXPECT_GE(r.pValue, kLevel) << name << ": chi2 " << r.statistic << " on " << r.dof << " dof, p = " << r.pValue
                              << " below " << kLevel << ";" << r.worst;
}

TEST(Chi2Cdf, MatchesTabulatedValues) {
  // chi2(2) has CDF 1 - exp(-x / 2); the rest are table quantiles to 4-5 digits.
  EXPECT_NEAR(chi2::cdf(5.0, 2), 1.0 - std::exp(-2.5), 1e-12);
  EXPECT_NEAR(chi2::cdf(3.841459, 1), 0.95, 1e-6);
  EXPECT_NEAR(chi2::cdf(23.20925, 10), 0.99, 1e-6);
  EXPECT_NEAR(chi2::cdf(135.8067, 100), 0.99, 1e-6);
  EXPECT_NEAR(chi2::pValue(67.32756, 100), 0.995, 1e-6);
  EXPECT_NEAR(chi2::cdf(0.5, 3) + chi2::pValue(0.5, 3), 1.0, 1e-14);
  EXPECT_NEAR(chi2::sidakLevel(0.01, 1), 0.01, 1e-15);
}

TEST(Chi2Sampling, SampleBsdfFollowsItsPdf) {
  const BsdfFrame frame = frameOf(kNormal);
  uint64_t seed = 1;
  for (const BsdfCase& c : bsdfCases()) {
    const Vec3 wo = atAngle(kNormal, c.woDegrees * kPiD / 180.0);
    const Grid grid(frame.ns, kPiD);
    std::vector<double> binned(grid.cells(), 0.0);
    double unbinned = 0.0;
    Rng rng(seed++);
    for (int n = 0; n < kSamples; ++n) {
      const float ul = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
      const BsdfSample s = sampleBsdf(c.bsdf, frame, wo, ul, u1, u2);
      if (s.valid && !(s.flags & kBsdfSpecular)) binned[grid.cellOf(s.wi)] += 1.0;
      else unbinned += 1.0;
    }
    const std::vector<double> mass = grid.integrate(
        [&](const Vec3& wi) {
          return c.classicReference ? classicBouncePdf(c.bsdf, frame, wi) : double(pdfBsdf(c.bsdf, frame, wo, wi));
        },
        16);
    expectPasses(runTest(binned, unbinned, mass, c.name), c.name);
  }
}

// The pdf in solid angle that sampleLight's radiance divides by, evaluated
// independently: the quad's d^2 / (A cos_l) where the ray meets its emitting side,
// the sphere's 1 / (2 pi (1 - cos_max)) inside its cone; 0 elsewhere.
// `slack` widens the edges for a sampled direction's own pdf (rounding at the rim).
double lightPdf(const Light& l, const Vec3& pf, const Vec3& wf, double slack = 0.0) {
  const glm::dvec3 p(pf), w(wf);
  if (l.type == LightType::Quad) {
    const glm::dvec3 c(l.position), e1(l.edge1), e2(l.edge2), n = glm::cross(e1, e2);
    const double area = glm::length(n), denom = glm::dot(n, w);
    if (denom >= 0.0) return 0.0;  // parallel, or the back of the quad
    const double t = glm::dot(n, c - p) / denom;
    if (t <= 0.0) return 0.0;
    const glm::dvec3 q = p + t * w - c;
    // q = u e1 + v e2 with e1 and e2 orthogonal here.
    const double u = glm::dot(q, e1) / glm::dot(e1, e1), v = glm::dot(q, e2) / glm::dot(e2, e2);
    if (u < -slack || u > 1.0 + slack || v < -slack || v > 1.0 + slack) return 0.0;
    const double cosLight = -denom / area;
    return t * t / (area * cosLight);
  }
  if (l.type == LightType::Disk) {
    const glm::dvec3 c(l.position), n(l.direction);
    const double denom = glm::dot(n, w);
    if (denom >= 0.0) return 0.0;  // parallel, or its back
    const double t = glm::dot(n, c - p) / denom;
    if (t <= 0.0) return 0.0;
    const glm::dvec3 q = p + t * w - c;
    if (glm::length(q) > l.radius * (1.0 + slack)) return 0.0;
    return t * t / (kPiD * double(l.radius) * l.radius * -denom);
  }
  const glm::dvec3 toCentre = glm::dvec3(l.position) - p;
  const double d2 = glm::dot(toCentre, toCentre), r2 = double(l.radius) * l.radius;
  const double cosMax = std::sqrt(1.0 - r2 / d2);
  if (glm::dot(w, toCentre) / std::sqrt(d2) < cosMax - slack) return 0.0;
  return 1.0 / (2.0 * kPiD * (1.0 - cosMax));
}

// The widest angle between `axis` and a direction towards the light.
double lightConeAngle(const Light& l, const Vec3& p, const Vec3& axis) {
  if (l.type == LightType::Sphere) {
    const double d = glm::length(glm::dvec3(l.position) - glm::dvec3(p));
    return std::asin(l.radius / d);
  }
  double widest = 0.0;
  if (l.type == LightType::Disk) {  // over its rim, finely
    Vec3 t, b;
    orthonormalBasis(l.direction, t, b);
    for (int k = 0; k < 3600; ++k) {
      const double phi = 2.0 * kPiD * k / 3600;
      const Vec3 rim = l.position + l.radius * float(std::cos(phi)) * t + l.radius * float(std::sin(phi)) * b;
      const glm::dvec3 d = glm::normalize(glm::dvec3(rim) - glm::dvec3(p));
      widest = std::max(widest, std::acos(std::clamp(glm::dot(d, glm::dvec3(axis)), -1.0, 1.0)));
    }
    return widest;
  }
  for (const Vec3& corner : {l.position, l.position + l.edge1, l.position + l.edge2,
                             l.position + l.edge1 + l.edge2}) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(corner) - glm::dvec3(p));
    widest = std::max(widest, std::acos(std::clamp(glm::dot(d, glm::dvec3(axis)), -1.0, 1.0)));
  }
  return widest;  // a convex polygon's widest direction from an axis is a corner's
}

TEST(Chi2Sampling, SampleLightFollowsTheSolidAnglePdfOfItsRadiance) {
  uint64_t seed = 1000;
  for (const LightCase& c : lightCases()) {
    const Light& l = c.light;
    const Vec3 centre = l.type == LightType::Quad ? l.position + 0.5f * (l.edge1 + l.edge2) : l.position;
    const Vec3 axis = glm::normalize(centre - c.p);
    // The sphere's cone edge on a cell boundary; a quad or disk inside the grid with a margin.
    const double range = lightConeAngle(l, c.p, axis) * (l.type == LightType::Sphere ? 1.0 : 1.05);
    const Grid grid(axis, range);
    const LightSampler sampler = prepareLight(l, c.p);
    std::vector<double> binned(grid.cells(), 0.0);
    double unbinned = 0.0;
    int weightMismatches = 0;
    Rng rng(seed++);
    for (int n = 0; n < kSamples; ++n) {
      const float u1 = rng.uniform(), u2 = rng.uniform();
      const LightIncidence in = sampleLight(sampler, u1, u2);
      if (!in.valid) {
        unbinned += 1.0;
        continue;
      }
      binned[grid.cellOf(in.wi)] += 1.0;
      // The estimate's weight is L / pdf for the same pdf the histogram is tested against.
      const double pdf = lightPdf(l, c.p, in.wi, 1e-5);
      const double want = l.radiance().r / pdf;
      if (!(std::abs(in.radiance.r - want) <= 1e-3 * want) && ++weightMismatches <= 3) {
        ADD_FAILURE() << c.name << ": radiance " << in.radiance.r << " is not L / pdf = " << want;
      }
    }
    const std::vector<double> mass =
        grid.integrate([&](const Vec3& wi) { return lightPdf(l, c.p, wi); }, 32);
    expectPasses(runTest(binned, unbinned, mass, c.name), c.name);
  }
}

}  // namespace
}  // namespace penumbra
