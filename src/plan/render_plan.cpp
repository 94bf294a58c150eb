// Each pass's rule: on only where the view reads it and the scene can make it
// contribute, with the reason in words; then the user's --enable / --disable.
#include "plan/render_plan.h"
#include "plan/gate_decision.h"
#include "plan/lookup_decision.h"
#include "plan/media_facts.h"
#include "plan/transport_model.h"
#include "core/bsdf.h"
#include "core/error.h"
#include "core/light_sample.h"
#include "emit/emit.h"
#include "emit/emit_physical.h"
#include "emit/caustic_aim.h"
#include "emit/light_reach.h"
#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

namespace penumbra {
namespace {

constexpr const char* kNames[kPassCount] = {
    "gate", "indirect-photons", "global-photons", "caustic-photons", "volume-photons", "shadow-rays", "reflection",
    "refraction", "textures", "light-samples", "packets", "precompute"};

PassDecision on(std::string reason, uint64_t budget = 0) { return {true, std::move(reason), budget, {}, {}}; }
PassDecision off(std::string reason) { return {false, std::move(reason), 0, {}, {}}; }

struct SceneFacts {
  // photonLight: one that emits shadow and classic photons (neither directional nor
  // environment); physicalLight: one whose photons keep the physical maps on (all but
  // directional lights), so without a photonLight it is a sky.
  bool photonLight = false, physicalLight = false, areaLight = false, anyLight = false;
  bool reflective = false, transparent = false;
  int areaLights = 0;
};

SceneFacts factsOf(const Scene& scene, const TransportModel& model) {
  SceneFacts f;
  for (const Light& l : scene.lights) {
    if (maxComponent(l.radiance()) <= 0.0f) continue;
    f.anyLight = true;
    f.photonLight = f.photonLight || answersGate(l);
    f.physicalLight = f.physicalLight || lightTraits(l).opensPhysicalMaps;
    if (lightSampleCount(l, 2) > 1) { f.areaLight = true; ++f.areaLights; }
  }
  for (const Material& m : scene.materials) {
    f.transparent = f.transparent || m.transparent;
    f.reflective = f.reflective || model.reflects(m, scene.photons);
  }
  return f;
}

// The volume map (the model has one): on only where a medium scatters light from a
// light, so a scene without a medium runs none of it; the reason names the media.
PassDecision volumeDecision(const Scene& scene, const TransportModel& model, const SceneFacts& f, Aov aov,
                            const std::string& view) {
  const uint64_t budget = scene.photons.volumePhotons;
  const std::vector<std::string> media = scatteringMedia(scene);
  if (!scene.hasMedia()) return off("no medium");
  if (!readsLight(aov)) return off(view);
  if (!model.readsMap(MapKind::Volume, aov)) return off("this view does not read it (single scattering is direct light)");
  if (const char* cannot = model.cannotStore(MapKind::Volume, scene)) return off(cannot);
  if (!f.anyLight) return off("no light");
  if (budget == 0) return off("photons.volume is 0");
  return on(fmt::format("{} scatter{}: {} photons per pass", mediaPhrase(media), media.size() == 1 ? "s" : "", budget),
            budget);
}

void decide(RenderPlan& plan, const Scene& scene, Aov aov) {
  const TransportModel& model = *plan.model;
  const SceneFacts f = factsOf(scene, model);
  const PhotonSettings& ps = scene.photons;
  const bool light = readsLight(aov);
  const std::string view = fmt::format("the {} view reads no light", aov == Aov::Depth ? "depth" : "normal");
  const bool direct = light && aov != Aov::Indirect && aov != Aov::Caustic;

  // Shadow rays, and the gate that replaces some of them.
  if (!direct) plan[Pass::ShadowRays] = off(light ? "this view has no direct light" : view);
  else if (!f.anyLight) plan[Pass::ShadowRays] = off("no light");
  else if (!scene.render.shadows) plan[Pass::ShadowRays] = off("render.shadows is false");
  else plan[Pass::ShadowRays] = on("every light a shading point faces");
  PassDecision& gate = plan[Pass::Gate];
  if (!plan[Pass::ShadowRays].on) {
    gate = off("no shadow rays to replace");
  } else if (ps.gateMode == GateMode::Auto) {
    const GateDecision d = decideGate(scene);
    gate = d.gate ? on(d.reason, ps.shadowPhotons) : off(d.reason);
  } else {
    gate = ps.gateMode == GateMode::On ? on("photons.gate is on", ps.shadowPhotons) : off("photons.gate is off");
    if (gate.on && !f.photonLight) gate = off("only directional or environment lights: they emit no shadow photons");
  }
  if (gate.on) gate.perLight = splitBudget(scene, gate.budget);

  // The model's light maps; the other model's stay off.
  const MapCounts budgets = budgetsOf(scene);
  for (MapKind k : kAllMaps) {
    if (k == MapKind::Shadow) continue;
    PassDecision& d = plan[photonPass(k)];
    const auto& own = model.lightMaps();
    if (std::find(own.begin(), own.end(), k) == own.end()) {
      d = off(fmt::format("the {} model has no {} map", model.name(), mapName(k)));
    } else if (k == MapKind::Volume) {
      d = volumeDecision(scene, model, f, aov, view);
    } else if (!model.readsMap(k, aov)) {
      d = off(light ? "this view does not read it" : view);
    } else if (budgets[k] == 0) {
      d = off(fmt::format("photons.{} is 0", mapName(k)));
    } else if (!f.photonLight && !(f.physicalLight && k != MapKind::Indirect)) {
      d = off(f.physicalLight ? "only directional or environment lights: no classic photons" : "only directional lights: no photons");
    } else if (const char* cannot = model.cannotStore(k, scene)) {
      d = off(cannot);
    } else {
      d = on(fmt::format("{} photons", budgets[k]), budgets[k]);
    }
  }
  if (plan[Pass::IndirectPhotons].on) plan[Pass::IndirectPhotons].perLight = splitBudget(scene, ps.indirectPhotons);

  // Recursion, textures, samples, packets, lookups.
  const bool deeper = scene.render.maxDepth > 0;
  plan[Pass::Reflection] = !light ? off(view) : !deeper ? off("render.max_depth is 0")
                           : f.reflective ? on("mirror or glass material") : off("no mirror or glass material");
  plan[Pass::Refraction] = !light ? off(view) : !deeper ? off("render.max_depth is 0")
                           : f.transparent ? on("transparent material") : off("no transparent material");
  plan[Pass::Textures] = scene.textures.empty() ? off("no texture")
                         : !light ? off(view)
                                  : on(fmt::format("{} texture(s)", scene.textures.size()));
  plan[Pass::LightSamples] = !direct || !f.areaLight ? off(f.areaLight ? "this view has no direct light" : "no area light")
                             : on(fmt::format("{} per area light ({} area lights)", scene.render.lightSamples, f.areaLights),
                                  static_cast<uint64_t>(scene.render.lightSamples));
  plan[Pass::Packets] = scene.render.packets ? on("render.packets is true (the same image, faster)")
                                             : off("render.packets is false");
  const bool maps = gate.on || plan[photonPass(model.indirectLookup(ps).map)].on;
  PassDecision& precompute = plan[Pass::Precompute];
  if (ps.lookup == PhotonLookup::Exact) {
    precompute = off("photons.lookup is exact");
  } else if (!maps) {
    precompute = off("no gate or indirect map to precompute");
  } else if (ps.lookup == PhotonLookup::Precomputed) {
    precompute = on("photons.lookup is precomputed");
  } else {
    const IndirectLookup gather = model.indirectLookup(ps);
    const bool gathers = plan[photonPass(gather.map)].on;
    // Camera hits repeat with every pass; a model whose passes reuse one emission
    // (classic) is priced at one, as its auto lookup always was.
    const int cameraPasses = model.freshPhotonsEachPass() ? ps.passes : 1;
    const LookupDecision d = decideLookup(scene, gate.on ? gatedLightCount(scene) : 0, gather,
                                          gathers ? double(budgets[gather.map]) : 0.0, cameraPasses);
    precompute = d.precomputed ? on(d.reason) : off(d.reason);
  }
}

}  // namespace

const char* passName(Pass pass) { return kNames[static_cast<size_t>(pass)]; }

Pass parsePass(const std::string& name) {
  std::string known;
  for (size_t i = 0; i < kPassCount; ++i) {
    if (name == kNames[i]) return static_cast<Pass>(i);
    known += (i ? ", " : "") + std::string(kNames[i]);
  }
  throw InputError("unknown pass '" + name + "' (known: " + known + ")");
}

RenderPlan makePlan(const Scene& scene, Aov aov, const PlanOverrides& overrides) {
  RenderPlan plan;
  plan.aov = aov;
  plan.model = &transportOf(scene);
  decide(plan, scene, aov);
  const PhotonSettings& ps = scene.photons;
  for (Pass p : overrides.enable) {
    PassDecision& d = plan[p];
    if (d.on) {  // pinned on: nothing later (the light split) may turn it off
      d.overridden = true;
      continue;
    }
    d.on = true;
    d.overridden = true;
    // Forcing a pass on that the scene cannot use costs time but adds nothing, except
    // the gate (its verdicts replace shadow rays) and fewer packets (same image).
    d.changesImage = p == Pass::Gate || p == Pass::Precompute || (p == Pass::ShadowRays && !scene.render.shadows);
    d.reason = "on (--enable " + std::string(passName(p)) + "; was: " + d.reason + ")";
    if (p == Pass::Gate) { d.budget = ps.shadowPhotons; d.perLight = splitBudget(scene, d.budget); }
    if (p == Pass::IndirectPhotons) { d.budget = ps.indirectPhotons; d.perLight = splitBudget(scene, d.budget); }
    if (p == Pass::GlobalPhotons) d.budget = ps.globalPhotons;
    if (p == Pass::CausticPhotons) d.budget = ps.causticPhotons;
    if (p == Pass::VolumePhotons) d.budget = ps.volumePhotons;
    if (p == Pass::LightSamples) d.budget = static_cast<uint64_t>(scene.render.lightSamples);
  }
  for (Pass p : overrides.disable) {
    PassDecision& d = plan[p];
    if (!d.on) continue;
    d.on = false;
    d.overridden = true;
    d.changesImage = p != Pass::Packets;
    d.reason = "off (--disable " + std::string(passName(p)) + (d.changesImage ? "; changes the image" : "") + ")";
  }
  return plan;
}

FrameChoices choicesOf(const RenderPlan& plan, const Scene& scene) {
  FrameChoices c;
  c.gate = plan[Pass::Gate].on;
  // Off: lights reach every surface facing them (render.shadows = false).
  c.shadows = plan[Pass::ShadowRays].overridden ? plan[Pass::ShadowRays].on : scene.render.shadows;
  c.reflection = plan[Pass::Reflection].on;
  c.refraction = plan[Pass::Refraction].on;
  const bool oneSample = !plan[Pass::LightSamples].on && plan[Pass::LightSamples].overridden;
  c.lightSamples = oneSample ? 1 : scene.render.lightSamples;
  c.volumeSamples = scene.render.volumeSamples;
  c.packets = plan[Pass::Packets].on;
  c.integrator = &(plan.model ? *plan.model : transportOf(scene)).integrator();
  return c;
}

void splitByReach(RenderPlan& plan, const Scene& scene, const TraceScene& tracer) {
  const bool density = scene.photons.estimator == IndirectEstimator::Density;
  struct Target {
    Pass pass;
    ReachRule rule;
    const char* where;
  };
  std::vector<Target> targets = {
      {Pass::GlobalPhotons, ReachRule::Scattering, "a surface that scatters photons"},
      {Pass::CausticPhotons, ReachRule::Specular, "a specular surface (spots and environments; other lights aim)"}};
  // Not the classic estimator: it averages photon colours (not a density), so each
  // photon must carry its light's colour at the weight the power split gives it.
  if (density) targets.push_back({Pass::IndirectPhotons, ReachRule::Bouncing, "a surface that bounces photons (p_r or p_t > 0)"});
  for (const Target& t : targets) {
    PassDecision& d = plan[t.pass];
    if (!d.on || d.overridden || d.budget == 0) continue;
    // The pilots follow first hits only: in a scattering medium a light's photons reach
    // surfaces by scattering too (L V D is the global map's), so power alone splits it.
    const bool scattered = t.pass == Pass::GlobalPhotons && !scatteringMedia(scene).empty();
    d.reach = scattered ? std::vector<float>(scene.lights.size(), 1.0f) : measureReach(scene, tracer, t.rule);
    if (t.pass == Pass::IndirectPhotons) d.perLight = splitBudget(scene, d.budget, d.reach);
    else d.perLight = splitPhysicalBudget(scene, tracer, t.pass == Pass::CausticPhotons, d.budget, d.reach);
    int none = 0, emitting = 0;
    std::vector<std::string> shares;
    for (size_t l = 0; l < scene.lights.size(); ++l) {
      const bool aimed = t.pass == Pass::CausticPhotons && aimsCausticPhotons(scene.lights[l]);
      if (aimed || !(maxComponent(scene.lights[l].radiance()) > 0.0f)) continue;
      ++emitting;
      none += d.reach[l] == 0.0f;
      shares.push_back(fmt::format("light {} {:.0f}%", l, 100.0 * d.reach[l]));
    }
    if (shares.size() > 4) shares.clear();  // many lights: the counts say it (per_light in --stats)
    uint64_t given = 0;
    for (uint64_t c : d.perLight) given += c;
    const std::string pilot = fmt::format("{} pilot photons per light", kReachPilots);
    if (given == 0) {
      d = off(fmt::format("no light's photons reach {} ({})", t.where, pilot));
    } else if (t.pass == Pass::GlobalPhotons && !scattered && measureRebound(scene, tracer) == 0.0f) {
      d = off(fmt::format("no light's photons land on a second surface, where the global map stores them ({}): "
                          "every bounce leaves the scene",
                          pilot));
    } else if (emitting > 1 || none > 0) {
      d.reason += fmt::format("; split by the power reaching {} ({}{}{})", t.where, pilot,
                              shares.empty() ? "" : ": " + fmt::format("{}", fmt::join(shares, ", ")),
                              none ? fmt::format("; {} of {} lights reach none and emit none", none, emitting) : "");
    }
  }
}

std::string planText(const RenderPlan& plan) {
  std::string s;
  for (size_t i = 0; i < kPassCount; ++i) {
    const PassDecision& d = plan.passes[i];
    s += fmt::format("{:<17} {:<4} {}\n", kNames[i], d.on ? "on" : "off", d.reason);
  }
  return s;
}

std::string planJson(const RenderPlan& plan) {
  nlohmann::json j = nlohmann::json::object();
  for (size_t i = 0; i < kPassCount; ++i) {
    const PassDecision& d = plan.passes[i];
    nlohmann::json p = {{"on", d.on}, {"reason", d.reason}};
    if (d.budget > 0) p["budget"] = d.budget;
    if (!d.perLight.empty()) p["per_light"] = d.perLight;
    if (d.overridden) p["overridden"] = true;
    if (d.changesImage) p["changes_image"] = true;
    j[kNames[i]] = p;
  }
  return j.dump();
}

}  // namespace penumbra
