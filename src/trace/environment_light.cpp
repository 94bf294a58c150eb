// Environment direct light (light and BSDF samples, power heuristic) and the
// radiance of rays that leave the scene.
#include "trace/environment_light.h"
#include "core/lights/environment_map.h"
#include "core/sampling.h"
#include "trace/light_visibility.h"

namespace penumbra {

namespace {

// Veach's power heuristic (beta = 2) for a sample of strategy a, given both densities
// times their sample counts.
float powerHeuristic(float a, float b) {
  const float a2 = a * a, b2 = b * b;
  return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

LightIncidence towards(const Vec3& wi, bool valid) {
  LightIncidence in;
  in.wi = wi;
  in.distance = kInf;  // shadow rays run to infinity: nothing lies beyond an environment
  in.valid = valid;
  return in;
}

}  // namespace

Color directFromEnvironment(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t li, const Bsdf& bsdf,
                            const BsdfFrame& frame, const Vec3& wo, ThreadState& ts, std::string* note) {
  const Light& light = ctx.scene.lights[li];
  const int n = ctx.choices.lightSamples;
  const bool mis = bsdf.type == BsdfType::Opaque || bsdf.type == BsdfType::MetalRough;
  const int nb = mis ? n : 0;
  const bool shadows = ctx.choices.shadows;
  Rng rng(hashKey(ts.sampleKey, ts.shadingPoint, li));
  Color lightSum(0.0f), bsdfSum(0.0f);
  int cast = 0, blocked = 0;  // shadow rays, for --trace-pixel's note
  const Stratified2D lightStrata(n, rng), bsdfStrata(nb, rng);
  for (int j = 0; j < n; ++j) {
    const Vec2 u = n > 1 ? lightStrata(j, rng) : Vec2(rng.uniform(), rng.uniform());
    const EnvironmentSample e = sampleEnvironment(light, s.ns, u.x, u.y);
    const LightIncidence in = towards(e.wi, e.valid);
    if (!facesLight(s, in)) continue;
    const Color f = evaluateBsdf(bsdf, frame, wo, in.wi);
    if (maxComponent(f) <= 0.0f || maxComponent(e.radiance) <= 0.0f) continue;
    const float w = mis ? powerHeuristic(n * e.pdf, nb * pdfBsdf(bsdf, frame, wo, in.wi)) : 1.0f;
    const Color t = shadows ? shadowRay(ctx, s, li, in, ts) : Color(1.0f);
    ++cast;
    blocked += maxComponent(t) <= 0.0f;
    lightSum += t * f * e.radiance * (w / e.pdf);
  }
  for (int j = 0; j < nb; ++j) {
    const float uLobe = rng.uniform();
    const Vec2 u = nb > 1 ? bsdfStrata(j, rng) : Vec2(rng.uniform(), rng.uniform());
    const BsdfSample bs = sampleBsdf(bsdf, frame, wo, uLobe, u.x, u.y);
    // A delta lobe's direction is followed as a reflection ray, which sees the
    // environment when it leaves the scene: not a sample of this estimate.
    if (!bs.valid || (bs.flags & kBsdfSpecular)) continue;
    const LightIncidence in = towards(bs.wi, true);
    if (!facesLight(s, in)) continue;
    const float pb = pdfBsdf(bsdf, frame, wo, in.wi);
    const Color L = environmentRadiance(light, in.wi);
    if (!(pb > 0.0f) || maxComponent(L) <= 0.0f) continue;
    const Color f = evaluateBsdf(bsdf, frame, wo, in.wi);
    if (maxComponent(f) <= 0.0f) continue;
    const float w = powerHeuristic(nb * pb, n * environmentPdf(light, s.ns, in.wi));
    const Color t = shadows ? shadowRay(ctx, s, li, in, ts) : Color(1.0f);
    ++cast;
    blocked += maxComponent(t) <= 0.0f;
    bsdfSum += t * f * L * (w / pb);
  }
  if (note) *note = "environment: " + std::to_string(blocked) + " of " + std::to_string(cast) + " rays blocked";
  return lightSum / static_cast<float>(n) + (nb > 0 ? bsdfSum / static_cast<float>(nb) : Color(0.0f));
}

bool missSeesEnvironment(const Scene& scene, RayKind kind) {
  return environmentOf(scene) && !(kind == RayKind::Camera && scene.render.environmentBackground);
}

Color missRadiance(const Scene& scene, const Vec3& dir, RayKind kind) {
  if (missSeesEnvironment(scene, kind)) return environmentRadiance(*environmentOf(scene), dir);
  return environmentOf(scene) ? *scene.render.environmentBackground : scene.render.background;
}

}  // namespace penumbra
