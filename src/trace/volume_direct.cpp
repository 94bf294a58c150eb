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

#include <optional>

namespace penumbra {

float FreeFlight::rateOf(const Medium& m) {
  const Color st = m.sigmaT();
  return (st.r + st.g + st.b) / 3.0f * (m.density ? m.density->maxDensity : 1.0f);
}

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
  const FreeFlight flight(m, a, b);
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
  // n samples of each technique per light, stratified in distance, in the equiangular
  // centre's and in the light sample's numbers, each dimension's strata paired with the
  // others' through a permutation of its own seed (a shared index would correlate them).
  // One sample draws uniform numbers, in the single-sample estimator's order.
  const int n = std::max(ctx.choices.volumeSamples, 1);
  const Stratified2D strata(n, rng);
  auto draw1 = [&](int j, uint32_t seed) {
    const float u = rng.uniform();
    return n > 1 ? (static_cast<float>(permutationElement(uint32_t(j), uint32_t(n), seed)) + u) / static_cast<float>(n)
                 : u;
  };
  auto draw2 = [&](int j, uint32_t seed) {
    return n > 1 ? strata(int(permutationElement(uint32_t(j), uint32_t(n), seed)), rng)
                 : Vec2{rng.uniform(), rng.uniform()};
  };
  enum Dimension { kLight, kDistance, kEquiangular, kCentre, kDimensions };
  Color sum(0.0f);
  for (uint32_t li = 0; li < ctx.scene.lights.size(); ++li) {
    const Light& light = ctx.scene.lights[li];
    if (!(maxComponent(light.radiance()) > 0.0f)) continue;
    uint32_t seeds[kDimensions] = {};
    if (n > 1) {
      for (uint32_t& seed : seeds) seed = rng.nextU32();
    }
    // A far sample can underflow both its pdf and its integrand (T = 0): it adds nothing.
    auto add = [&](float t, float pdf, int j) {
      if (std::isfinite(t) && pdf > 0.0f) sum += scatterAt(li, t, draw2(j, seeds[kLight])) / pdf;
    };
    for (int j = 0; j < n; ++j) {
      Vec3 centre(0.0f);
      std::optional<EquiangularFrame> eq;
      if (equiangularCentre(light, ray, a, [&] { return draw2(j, seeds[kCentre]); }, centre)) {
        eq.emplace(ray.origin, ray.dir, centre, a, b);
      }
      const DistanceSample td = flight.sample(draw1(j, seeds[kDistance]));
      if (eq && eq->thetaB > eq->thetaA) {
        // One sample of each technique, each weighted by the balance heuristic: f / (p_e + p_d).
        const DistanceSample te = eq->sample(draw1(j, seeds[kEquiangular]), a, b);
        if (te.pdf > 0.0f) add(te.t, te.pdf + flight.pdf(te.t), j);
        if (td.pdf > 0.0f) add(td.t, float(eq->pdf(td.t)) + td.pdf, j);
      } else if (td.pdf > 0.0f) {
        add(td.t, td.pdf, j);
      }
    }
  }
  if (n > 1) sum /= static_cast<float>(n);
  return sum;
}

}  // namespace penumbra
