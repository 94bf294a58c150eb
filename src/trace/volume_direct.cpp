// Single scattering by light sampling along a camera (or specular) ray's medium stretch.
#include "trace/volume_direct.h"
#include "core/light_sample.h"
#include "core/lights/environment_map.h"
#include "core/media/density_grid.h"
#include "core/media/homogeneous.h"
#include "core/media/phase_function.h"
#include "core/media/tracking.h"
#include "core/permutation.h"
#include "core/sampling.h"
#include "trace/medium_shadow.h"

namespace penumbra {

namespace {

// The point equiangular samples centre on: a delta light's position, or a point drawn
// on an area light as seen from the stretch's start (given the point, both techniques'
// densities are known, so any point keeps the estimate unbiased). Lights at infinity
// have none.
// `draw` gives the area light's numbers (u1, u2); it is called only for an area light.
template <class Draw>
bool equiangularCentre(const Light& light, const Ray& ray, float a, Draw&& draw, Vec3& c) {
  const LightSupport support = lightTraits(light).support;
  if (support == LightSupport::Position) {
    c = light.position;
    return true;
  }
  if (support != LightSupport::Area) return false;
  const Vec2 u = draw();
  const LightIncidence in = sampleLight(prepareLight(light, ray.origin + a * ray.dir), u.x, u.y);
  c = in.point;
  return in.valid;
}

}  // namespace

Color volumeDirect(const ShadingContext& ctx, const Ray& ray, float a, float b, int medium, Rng& rng,
                   ThreadState& ts) {
  const Medium& m = ctx.scene.media[static_cast<size_t>(medium)];
  if (!(maxComponent(m.sigmaS) > 0.0f) || !gridSpan(m, ray, a, b)) return Color(0.0f);
  const Color st = m.sigmaT();
  const FreeFlight flight((st.r + st.g + st.b) / 3.0f * (m.density ? m.density->maxDensity : 1.0f), a, b);
  // sigma_s T(a, t) p(wi, ray) L_i T_shadow at distance t: the integrand, before its pdf.
  auto scatterAt = [&](uint32_t li, float t, Vec2 u) {
    ++ts.counts.mediumSamples;
    const Light& light = ctx.scene.lights[li];
    const float u1 = u.x, u2 = u.y;
    const Vec3 x = ray.origin + t * ray.dir;
    const Color sigmaS = sigmaSAt(m, x);
    if (!(maxComponent(sigmaS) > 0.0f)) return Color(0.0f);
    LightIncidence in;
    if (lightTraits(light).direct == DirectSampling::EnvironmentMis) {
      const EnvironmentSample e = sampleEnvironmentSphere(light, u1, u2);
      if (!e.valid) return Color(0.0f);
      in.wi = e.wi;
      in.radiance = e.radiance / e.pdf;
    } else {
      in = sampleLight(prepareLight(light, x), isDeltaLight(light) ? 0.5f : u1, isDeltaLight(light) ? 0.5f : u2);
      if (!in.valid) return Color(0.0f);
    }
    // Propagation directions: from the light along -wi, then back along -ray.dir.
    Color f = sigmaS * henyeyGreenstein(m.g, glm::dot(in.wi, ray.dir)) * in.radiance;
    if (!(maxComponent(f) > 0.0f)) return Color(0.0f);
    f *= stretchTransmittance(m, ray, a, t, ts);
    if (!ctx.choices.shadows || !(maxComponent(f) > 0.0f)) return f;
    Ray shadow{x, in.wi};
    float margin = 0.0f;
    if (std::isfinite(in.distance)) {
      const Vec3 d = in.point - x;
      const float len = glm::length(d);
      if (!(len > in.margin)) return f;  // at the light
      shadow.dir = d / len;
      shadow.tMax = len - in.margin;
      margin = in.margin;
    }
    return f * lightTransmittance(ctx, shadow, margin, li, medium, ts);
  };
  // n samples of each technique per light, stratified in distance and in the light's
  // (u1, u2), the strata of each dimension paired by a permutation of its own (a shared
  // index would correlate them); one sample draws what the single-sample estimator did.
  const int n = std::max(ctx.choices.volumeSamples, 1);
  const Stratified2D strata(n, rng);
  Color sum(0.0f);
  uint32_t lightSeed = 0;
  // A far sample can underflow both its pdf and its integrand (T = 0): it adds nothing.
  auto add = [&](uint32_t li, float t, float pdf, int j) {
    if (!(std::isfinite(t) && pdf > 0.0f)) return;
    const Vec2 u = n > 1 ? strata(int(permutationElement(uint32_t(j), uint32_t(n), lightSeed)), rng)
                         : Vec2{rng.uniform(), rng.uniform()};
    sum += scatterAt(li, t, u) / pdf;
  };
  for (uint32_t li = 0; li < ctx.scene.lights.size(); ++li) {
    const Light& light = ctx.scene.lights[li];
    if (!(maxComponent(light.radiance()) > 0.0f)) continue;
    uint32_t distanceSeed = 0, equiangularSeed = 0, centreSeed = 0;
    if (n > 1) {
      lightSeed = rng.nextU32();
      distanceSeed = rng.nextU32();
      equiangularSeed = rng.nextU32();
      centreSeed = rng.nextU32();
    }
    auto stratum = [&](int j, uint32_t seed, float u) {
      if (n == 1) return u;
      return (static_cast<float>(permutationElement(uint32_t(j), uint32_t(n), seed)) + u) / static_cast<float>(n);
    };
    for (int j = 0; j < n; ++j) {
      // An area light's centre point is stratified over the light as its samples are.
      auto centreNumbers = [&] {
        return n > 1 ? strata(int(permutationElement(uint32_t(j), uint32_t(n), centreSeed)), rng)
                     : Vec2{rng.uniform(), rng.uniform()};
      };
      Vec3 centre(0.0f);
      const bool equiangular = equiangularCentre(light, ray, a, centreNumbers, centre);
      const EquiangularFrame eq(ray.origin, ray.dir, centre, a, b);
      const DistanceSample td = flight.sample(stratum(j, distanceSeed, rng.uniform()));
      if (equiangular && eq.thetaB > eq.thetaA) {
        // One sample of each technique, each weighted by the balance heuristic: f / (p_e + p_d).
        const DistanceSample te =
            sampleEquiangular(ray.origin, ray.dir, centre, a, b, stratum(j, equiangularSeed, rng.uniform()));
        if (te.pdf > 0.0f) add(li, te.t, te.pdf + flight.pdf(te.t), j);
        if (td.pdf > 0.0f) add(li, td.t, float(eq.pdf(td.t)) + td.pdf, j);
      } else if (td.pdf > 0.0f) {
        add(li, td.t, td.pdf, j);
      }
    }
  }
  if (n > 1) sum /= static_cast<float>(n);
  return sum;
}

}  // namespace penumbra
