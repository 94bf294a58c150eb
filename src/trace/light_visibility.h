// How much of a light reaches a shading point: the photon-map ambiguity gate
// decides when a shadow ray is needed; shadow rays through glass are tinted.
#pragma once
#include "core/bsdf.h"
#include "core/light_sample.h"
#include "core/light_strata.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "gather/lookup_cache/lookup_cache.h"
#include "trace/shading.h"
#include <optional>
#include <vector>

namespace penumbra {

// The gate's vote parameters for this scene and model (also what a lookup cache
// precomputes): a shadow photon behind glass votes "blocked" where glass blocks.
GateParams gateParamsFor(const Scene& scene, GlassShadows glass);

// A shading point's precomputed answer (null: ask the photon map).
using CachedAnswer = LookupCache::Answer;

// The row of precomputed verdicts that answers light li's strata at a shading point
// (LookupCache::stratumVerdict), or null where there is none (no cell, no gate, an
// exact vote, a light of one stratum).
const uint8_t* gateStrata(const ShadingContext& ctx, uint32_t li, const CachedAnswer* cached);

// A mixed light's stratum verdicts at one shading point, each read from the cell's
// row at most once: every sample in a stratum shares its verdict (a split line's
// too, since the point does not move).
class PointStrata {
 public:
  PointStrata(const LookupCache& cache, const uint8_t* row, uint32_t light, const Vec3& p)
      : cache_(&cache), row_(row), light_(light), p_(p) {
    for (uint8_t& v : known_) v = kUnknown;
  }
  GateVerdict operator()(int stratum) {
    uint8_t& v = known_[stratum];
    if (v == kUnknown) v = static_cast<uint8_t>(cache_->stratumVerdict(row_, light_, stratum, p_));
    return static_cast<GateVerdict>(v);
  }
  // The verdict strata 0..count share at the point, or Mixed where they differ.
  GateVerdict common(int count) {
    const GateVerdict first = (*this)(0);
    for (int k = 1; k < count && first != GateVerdict::Mixed; ++k)
      if ((*this)(k) != first) return GateVerdict::Mixed;
    return first;
  }

 private:
  static constexpr uint8_t kUnknown = 0xff;
  const LookupCache* cache_;
  const uint8_t* row_;
  uint32_t light_;
  Vec3 p_;
  uint8_t known_[kMaxLightStrata];
};

// The gate's verdict for one light at a shading point (Mixed when the gate is off
// or has no photons of that light): from the cache when there is one, else by the
// k-nearest vote. Counts the query and its outcome.
GateVerdict gateVerdict(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t lightIndex,
                        const CachedAnswer* cached, ThreadState& ts, std::string* note);
// The shadow ray from a shading point towards a light sample: from the lifted origin,
// ignoring occluders within 4 x spread, stopping `margin` short of the light. False
// when the origin is already at the light (nothing can block it).
bool shadowRayTo(const SurfaceRecord& s, const LightIncidence& in, Ray& ray);
// One shadow ray, recorded under --trace-pixel. Classic: glass tints the ray (a
// walk through every surface); physical: glass blocks it like anything else (light
// through glass arrives as caustic photons).
Color shadowRay(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t lightIndex,
                const LightIncidence& in, ThreadState& ts);

// What a lit gate verdict (or a render without shadows) lets through in a scene with
// media. The gate's photons vote on surfaces only: "shadowed" stays exact (an opaque
// blocker absorbs everything, whatever the medium), while "lit" says no surface blocks,
// so the segment stays in the shading point's medium but at invisible boundaries and
// its transmittance still multiplies the light: in closed form when that medium is
// homogeneous and no boundary exists, else walked (trace/medium_shadow.h).
Color litMediaTransmittance(const ShadingContext& ctx, const SurfaceRecord& s, const LightIncidence& in,
                            ThreadState& ts);
inline Color litTransmittance(const ShadingContext& ctx, const SurfaceRecord& s, const LightIncidence& in,
                              ThreadState& ts) {
  return ctx.scene.hasMedia() ? litMediaTransmittance(ctx, s, in, ts) : Color(1.0f);
}

// The closed-form Lambertian light of an area light none of whose samples reached
// the shading point: k_d E (E clipped to the point's horizon) when the gate says
// lit (or `asked`: a lit verdict is already known), else 0. Asks the gate only
// where E > 0, so a light wholly behind the point costs no vote.
Color litClosedForm(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t li,
                    const LightSampler& sampler, const Bsdf& bsdf, bool asked,
                    const CachedAnswer* cached, ThreadState& ts, std::string* note);

// Direct light from light `li` at a shading point: the mean over its samples (one
// for a delta light, render.light_samples for an area light, stratified, from the
// shading point's own random stream) of visibility x f cos x incidence, with f the
// BSDF and `weigh(t, f, in)` one sample's contribution at transmittance t (each
// model multiplies in the order its images were made with). The gate is asked once,
// at the first sample that reaches the surface: shadowed -> nothing; mixed -> one
// ray per sample whose stratum is mixed too (gateStrata); lit -> no ray at all,
// and the Lambertian part in closed form (unoccludedIrradiance), so only a glossy
// lobe still takes the samples. When no
// sample reaches it (a light mostly below the horizon or facing away: a cube lamp's
// far faces) but the closed form says some light does, the gate is asked after all
// (litClosedForm): a lit verdict owes the closed form whatever the samples hit.
// Whether a light sample reaches the surface's side at all (the geometric and the
// shading normal both face it): the test before any gate verdict or shadow ray, in
// directFromLight and in the shadow packets that trace its rays ahead.
inline bool facesLight(const SurfaceRecord& s, const LightIncidence& in) {
  return in.valid && glm::dot(s.ng, in.wi) > 0.0f && glm::dot(s.ns, in.wi) > 0.0f;
}

// A delta light's one sample (exact: no random numbers), in directFromLight and in
// the shadow packets that trace its ray ahead.
inline Vec2 deltaLightSample() { return Vec2(0.5f); }

template <class Weigh>
Color directFromLight(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t li,
                      const CachedAnswer* cached, ThreadState& ts, std::string* note,
                      const Bsdf& bsdf, const BsdfFrame& frame, const Vec3& wo, Weigh&& weigh) {
  const Light& light = ctx.scene.lights[li];
  const bool area = !isDeltaLight(light);
  const int n = lightSampleCount(light, ctx.choices.lightSamples);
  // Only an area light draws random numbers (a delta light's one sample is exact).
  Rng rng(area ? hashKey(ts.sampleKey, ts.shadingPoint, li) : 0);
  const LightSampler sampler = prepareLight(light, s.position);
  const bool shadows = ctx.choices.shadows;
  const Bsdf* lobes = &bsdf;  // after a lit verdict: only what the closed form left out
  Bsdf glossy;
  GateVerdict v = shadows ? GateVerdict::Mixed : GateVerdict::Lit;
  std::optional<PointStrata> strata;  // a mixed light's strata, if precomputed
  // With media the lit closed forms (unoccludedIrradiance) would leave out the
  // transmittance, which varies over the light: the samples carry it instead.
  bool asked = !shadows, closedTried = !area || ctx.scene.hasMedia();
  Color closed(0.0f), sum(0.0f);
  const Stratified2D stratified(n, rng);
  for (int j = 0; j < n; ++j) {
    // One sample of an area light is uniform, not its centre (Stratified2D's n = 1).
    const Vec2 u = !area ? deltaLightSample() : n > 1 ? stratified(j, rng) : Vec2(rng.uniform(), rng.uniform());
    // A quad's sample (parametric strata) names its stratum by its numbers alone, so its
    // verdict comes before the sample is drawn: in a stratum called shadowed it adds nothing.
    const bool parametricStrata = strata && lightTraits(light).strata == StrataKind::Parametric;
    GateVerdict sv = parametricStrata ? (*strata)(stratumOf(u.x, u.y)) : GateVerdict::Mixed;
    if (sv == GateVerdict::Shadowed) {
      ++ts.counts.shadowRaysAvoided;
      continue;
    }
    const LightIncidence in = sampleLight(sampler, u.x, u.y);
    if (!facesLight(s, in)) continue;
    Color f = evaluateBsdf(*lobes, frame, wo, in.wi);
    if (!asked) {
      if (maxComponent(f) <= 0.0f) continue;
      asked = true;
      v = gateVerdict(ctx, s, li, cached, ts, note);
      const uint8_t* row = v == GateVerdict::Mixed ? gateStrata(ctx, li, cached) : nullptr;
      if (row) {
        strata.emplace(*ctx.gateLookup, row, li, s.position);
        // A quad (parametric strata) whose every stratum its cell decides alike is lit or shadowed
        // here as a whole (a sphere's strata include its far side, which no sample meets).
        if (lightTraits(light).strata == StrataKind::Parametric) v = strata->common(ctx.gateLookup->strataOf(li));
        if (note && v != GateVerdict::Mixed) *note += v == GateVerdict::Lit ? "; every stratum lit here" : "; every stratum shadowed here";
        if (v != GateVerdict::Mixed) strata.reset();
      }
      if (v == GateVerdict::Shadowed) {
        ts.counts.shadowRaysAvoided += static_cast<uint64_t>(n - j);
        return Color(0.0f);
      }
    }
    if (v == GateVerdict::Lit && !closedTried) {
      closedTried = true;
      Color E;
      const Color kd = lambertCoefficient(bsdf);
      if (maxComponent(kd) > 0.0f && unoccludedIrradiance(sampler, s.ns, s.ng, E)) {
        closed = kd * E;
        glossy = glossyPart(bsdf);
        lobes = &glossy;
        if (!(bsdfFlags(glossy) & kBsdfGlossy)) {
          if (shadows) ts.counts.shadowRaysAvoided += static_cast<uint64_t>(n - j);
          return closed;
        }
        f = evaluateBsdf(glossy, frame, wo, in.wi);
      }
    }
    if (maxComponent(f) <= 0.0f) continue;
    if (strata) {
      // A mixed light whose sample falls in a stratum its cell calls lit or shadowed
      // here: that sample's ray is answered, only ambiguous strata still cast one.
      if (!parametricStrata) sv = (*strata)(sampleStratum(light, u, in.point));
      if (sv != GateVerdict::Mixed) {
        ++ts.counts.shadowRaysAvoided;
        if (sv == GateVerdict::Lit) sum += weigh(litTransmittance(ctx, s, in, ts), f, in);
        continue;
      }
    }
    if (v == GateVerdict::Lit) {
      if (shadows) ++ts.counts.shadowRaysAvoided;
      sum += weigh(litTransmittance(ctx, s, in, ts), f, in);
      continue;
    }
    const Color t = shadowRay(ctx, s, li, in, ts);
    if (maxComponent(t) > 0.0f) sum += weigh(t, f, in);
  }
  // No sample reached the surface, so the gate was not asked or its lit verdict
  // found no sample to attach the closed form to: every sample added nothing.
  if (!closedTried && (!asked || v == GateVerdict::Lit))
    return litClosedForm(ctx, s, li, sampler, bsdf, asked, cached, ts, note);
  return closed + (n > 1 ? sum / static_cast<float>(n) : sum);
}

// The precomputed answer at a shading point, or null without a lookup cache.
const CachedAnswer* lookupAt(const ShadingContext& ctx, const SurfaceRecord& s,
                             CachedAnswer& storage, ThreadState& ts);

// The term that replaces ambient light: the indirect photon map's estimate, or
// the material's ambient colour times the global ambient when there is no map.
Color ambientTerm(const ShadingContext& ctx, const SurfaceRecord& s, const Material& m,
                  const CachedAnswer* cached, ThreadState& ts);

// ---- Shadow packets: the shadow rays of a packet of camera hits, traced ahead as
// occlusion packets (one per light) and read back by the shading that would cast them.

// The lights (bit li, li < 32) whose shadow ray at a camera hit can be traced ahead:
// delta lights (one exact sample, no random numbers) that emit, with shadows on, a
// plain occlusion test (not the classic model's walk through glass) and no gate to
// consult (the gate decides whether a ray is cast at all). `direct`: the view adds
// direct light (classic beauty; physical beauty and direct); zero otherwise.
uint32_t packetShadowLights(const ShadingContext& ctx, bool direct);

// Reused buffers: one packet's worth of shadow rays and the hits they belong to.
struct PrimaryShadowScratch {
  std::vector<Ray> rays;
  std::vector<int> owner;
  std::vector<uint8_t> blocked;
};

// For n camera rays and their first hits (invalid: a miss), traces for every light
// of `lights` the shadow ray directFromLight would cast at that hit (shading point 1
// of its sample), as packets. Bit li of known[i] says hit i's answer for light li is
// in bit li of blocked[i]; hits that cannot cast one stay unknown and are answered by
// a single ray if shading asks after all, so the image never depends on this.
void tracePrimaryShadows(const ShadingContext& ctx, uint32_t lights, const Ray* rays,
                         const Hit* hits, int n, uint32_t* known, uint32_t* blocked,
                         PrimaryShadowScratch& scratch);

}  // namespace penumbra
