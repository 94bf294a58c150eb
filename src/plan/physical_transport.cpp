// The physical model: BSDFs and lights in radiometric units, direct light by shadow
// rays (or the gate), Jensen's caustic, global and volume maps, and progressive passes
// whose gather radii shrink so that the mean of the passes converges.
#include "core/bsdf.h"
#include "emit/emit_physical.h"
#include "plan/cost_model.h"
#include "plan/media_facts.h"
#include "plan/photon_stage.h"
#include "plan/transport_model.h"
#include <fmt/format.h>

namespace penumbra {
namespace {

class PhysicalTransport final : public TransportModel {
 public:
  ShadingModel id() const override { return ShadingModel::Physical; }
  const Integrator& integrator() const override { return physicalIntegrator(); }
  bool hasView(Aov) const override { return true; }

  const std::vector<MapKind>& lightMaps() const override {
    static const std::vector<MapKind> kMaps = {MapKind::Global, MapKind::Caustic, MapKind::Volume};
    return kMaps;
  }
  // Light scattered more than once in a medium is indirect; single scattering is the
  // camera's light sampling (direct), so no view but these reads the volume map.
  bool readsMap(MapKind map, Aov aov) const override {
    if (map == MapKind::Global || map == MapKind::Volume) return aov == Aov::Beauty || aov == Aov::Indirect;
    return map == MapKind::Caustic && (aov == Aov::Beauty || aov == Aov::Caustic);
  }
  const char* cannotStore(MapKind map, const Scene& scene) const override {
    if (map == MapKind::Global) {
      bool smooth = false;
      for (const Material& m : scene.materials) {
        smooth = smooth || hasGatheredLobe(makeBsdf(m, info().bsdf, scene.photons.sampling));
      }
      if (!smooth) return "no diffuse or glossy surface to store a photon on";
    } else if (map == MapKind::Volume) {
      if (scatteringMedia(scene).empty()) return scene.hasMedia() ? "no medium scatters (every sigma_s is 0)" : "no medium";
    } else if (specularTargets(scene).empty()) {
      return "no specular surface for a caustic";
    }
    return scene.photons.maxBounces == 0 ? "photons.max_bounces is 0" : nullptr;
  }
  bool reflects(const Material& m, const PhotonSettings& ps) const override {
    return m.transparent || hasTracedLobe(makeBsdf(m, info().bsdf, ps.sampling));
  }

  PerMap<bool> emittedMaps(const PerMap<bool>& wanted, uint32_t pass) const override {
    PerMap<bool> maps;
    // The gate's shadow photons do not change between passes: pass 0 only.
    maps[MapKind::Shadow] = wanted[MapKind::Shadow] && pass == 0;
    maps[MapKind::Global] = wanted[MapKind::Global];
    maps[MapKind::Caustic] = wanted[MapKind::Caustic];
    maps[MapKind::Volume] = wanted[MapKind::Volume];
    return maps;
  }
  void emit(const Scene& scene, const TraceScene& tracer, const EmitOptions& options, uint32_t pass,
            Emission& e) const override {
    if (options.maps[MapKind::Shadow]) emitPhotons(scene, tracer, options, e.photons);
    emitPhysicalPhotons(scene, tracer, pass, options, e.photons);
  }
  int passes(const Scene& scene, Aov aov) const override {
    return readsLight(aov) ? std::max(1, scene.photons.passes) : 1;
  }
  bool freshPhotonsEachPass() const override { return true; }
  IndirectLookup indirectLookup(const PhotonSettings& ps) const override {
    // Irradiance answers the Lambertian part; a glossy lobe still gathers.
    return {MapKind::Global, CachedIndirect::Irradiance, ps.kGlobal, 0.0f, cost::kPhysicalGatherNsPerNeighbour};
  }
  // Progressive pass `pass` (Knaus & Zwicker 2011): each map gathers k x passRadiusShare
  // nearest photons, so every point's radius shrinks from its own k-nearest one;
  // photons.radius > 0 instead fixes one radius for all points, shrunk by the same
  // share. A frame of one pass gathers the k nearest at any distance. The volume
  // map's beam keeps its own k and radius (photons.k_volume, photons.volume_radius)
  // and shrinks by the same schedule.
  PerMap<PhotonGather> gathers(const PhotonSettings& ps, uint32_t pass, uint32_t passes) const override {
    const MapKind caustic = MapKind::Caustic, global = MapKind::Global;
    PerMap<PhotonGather> g;
    g[caustic] = {ps.kCaustic, 0.0f};
    g[global] = {ps.kGlobal, 0.0f};
    g[MapKind::Volume] = volumeGather(ps, passes <= 1 ? 0 : pass);
    if (passes <= 1) return g;
    if (ps.radius > 0.0f) {
      const float radius = static_cast<float>(ps.radius * std::sqrt(passRadiusShare(pass, ps.alpha)));
      g[caustic] = g[global] = PhotonGather{0, radius};
      return g;
    }
    g[caustic] = PhotonGather{passK(ps.kCaustic, pass, ps.alpha), 0.0f};
    g[global] = PhotonGather{passK(ps.kGlobal, pass, ps.alpha), 0.0f};
    return g;
  }

  std::string photonSummary(const Scene& scene, const MapCounts& budgets, const RenderStats& stats,
                            bool gate) const override {
    const PhotonSettings& ps = scene.photons;
    return fmt::format(
        "global_photons={} caustic_photons={} k_global={} k_caustic={} "
        "passes={} alpha={} radius={} max_bounces={} shadow_photons={} "
        "k_shadow={} gate={}",
        budgets[MapKind::Global], budgets[MapKind::Caustic], ps.kGlobal, ps.kCaustic, stats.passes, ps.alpha, ps.radius,
        ps.maxBounces, stats.emitted[MapKind::Shadow], ps.kShadow, gate ? "on" : "off") +
           // Only a scene with a medium says anything of media: the others' lines stay as they were.
           (scene.hasMedia() ? fmt::format(" volume_photons={} k_volume={} volume_radius={}", budgets[MapKind::Volume],
                                           ps.kVolume, ps.volumeRadius)
                             : std::string());
  }
  void addModelSettings(const Scene& scene, const MapCounts& budgets, const RenderStats& stats,
                        ImageMetadata& m) const override {
    const PhotonSettings& ps = scene.photons;
    auto add = [&m](const char* key, const auto& value) {
      m.emplace_back(std::string("penumbra:") + key, fmt::format("{}", value));
    };
    add("photons.global", budgets[MapKind::Global]);
    add("photons.caustic", budgets[MapKind::Caustic]);
    add("photons.k_global", ps.kGlobal);
    add("photons.k_caustic", ps.kCaustic);
    add("photons.passes", stats.passes);
    add("photons.alpha", ps.alpha);
    add("photons.radius", ps.radius);
    if (stats.passes > 1) add("photons.final_global_radius", stats.gatherRadius[MapKind::Global]);
    if (stats.passes > 1) add("photons.final_caustic_radius", stats.gatherRadius[MapKind::Caustic]);
    if (!scene.hasMedia()) return;
    add("photons.volume", budgets[MapKind::Volume]);
    add("photons.k_volume", ps.kVolume);
    add("photons.volume_radius", ps.volumeRadius);
    if (stats.passes > 1) add("photons.final_volume_radius", stats.gatherRadius[MapKind::Volume]);
  }

 private:
  // Pass `pass`'s beam: passK of photons.k_volume, or a fixed photons.volume_radius
  // shrunk like the surface maps' (0: the volume map picks its radius from k).
  static PhotonGather volumeGather(const PhotonSettings& ps, uint32_t pass) {
    const double share = passRadiusShare(pass, ps.alpha);
    const float radius = ps.volumeRadius > 0.0f ? static_cast<float>(ps.volumeRadius * std::sqrt(share)) : 0.0f;
    return {passK(ps.kVolume, pass, ps.alpha), radius};
  }
};

}  // namespace

const TransportModel& physicalTransport() {
  static const PhysicalTransport kPhysical;
  return kPhysical;
}

}  // namespace penumbra
