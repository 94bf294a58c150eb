// The gate's cost model: what its shadow photons and lookups cost against the
// shadow rays it would avoid, both estimated from the scene before any work.
#include "plan/gate_decision.h"
#include "plan/cost_model.h"
#include "core/light_sample.h"
#include "core/light_strata.h"
#include <algorithm>
#include <fmt/format.h>

namespace penumbra {

double avoidableShare(const Light& light, bool precomputed) {
  return precomputed && lightStrata(light) > 1 ? cost::kAvoidableStratified : cost::kAvoidable;
}

int gatedLightCount(const Scene& scene) {
  return static_cast<int>(std::count_if(scene.lights.begin(), scene.lights.end(), answersGate));
}

GateDecision decideGate(const Scene& scene) {
  using namespace cost;
  GateDecision d;
  const PhotonSettings& ps = scene.photons;
  // Shadow tests per shading point: one per delta light, light_samples per area
  // light; directional and environment lights emit no shadow photons, so the gate
  // never answers them.
  const bool precomputed = ps.lookup != PhotonLookup::Exact;
  double testsPerPoint = 0.0, avoidablePerPoint = 0.0;
  int stratified = 0;
  for (const Light& l : scene.lights) {
    if (!answersGate(l)) continue;
    const double tests = lightSampleCount(l, scene.render.lightSamples);
    testsPerPoint += tests;
    avoidablePerPoint += tests * avoidableShare(l, precomputed);
    if (precomputed && lightStrata(l) > 1) ++stratified;
  }
  const int gatedLights = gatedLightCount(scene);
  if (!scene.render.shadows || gatedLights == 0 || ps.shadowPhotons == 0) {
    d.reason = "auto: off: no shadow tests the gate could answer";
    return d;
  }
  // Camera hits bound the shading points from below; reflections add to both sides.
  const double points = double(scene.camera.width) * scene.camera.height * scene.camera.spp;
  const double lookupNs = precomputed ? kLookupNs : kExactVoteNs * gatedLights;
  d.savedMs = points * avoidablePerPoint * kShadowRayNs * 1e-6;
  d.costMs = (double(ps.shadowPhotons) * kShadowPhotonNs + points * lookupNs) * 1e-6;
  d.gate = d.savedMs > d.costMs;
  d.stratified = d.gate && stratified > 0;
  const std::string strata =
      stratified > 0 ? fmt::format(", a verdict per stratum ({} a light) on {} area light{}", kMaxLightStrata,
                                   stratified, stratified == 1 ? "" : "s")
                     : "";
  d.reason = fmt::format("auto: {}: would save ~{:.0f} ms of shadow rays for ~{:.0f} ms of photons "
                         "and lookups ({:.0f} shadow tests per shading point{})",
                         d.gate ? "on" : "off", d.savedMs, d.costMs, testsPerPoint, strata);
  return d;
}

}  // namespace penumbra
