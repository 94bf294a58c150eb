// The classic model: the report's Whitted tracer, with the shadow map's gate and
// the indirect map in place of the ambient term. Its passes take new camera samples
// over the same maps (its estimates do not converge with more photons per pass).
#include "plan/cost_model.h"
#include "plan/photon_stage.h"
#include "plan/transport_model.h"
#include "core/bsdf.h"
#include <fmt/format.h>

namespace penumbra {
namespace {

class ClassicTransport final : public TransportModel {
 public:
  ShadingModel id() const override { return ShadingModel::Classic; }
  const Integrator& integrator() const override { return whittedIntegrator(); }
  bool hasView(Aov aov) const override { return aov != Aov::Direct && aov != Aov::Caustic; }

  const std::vector<MapKind>& lightMaps() const override {
    static const std::vector<MapKind> kMaps = {MapKind::Indirect};
    return kMaps;
  }
  bool readsMap(MapKind map, Aov aov) const override {
    return map == MapKind::Indirect && (aov == Aov::Beauty || aov == Aov::Indirect);
  }
  const char* cannotStore(MapKind, const Scene& scene) const override {
    // The density estimator stores only photons that bounced; the classic one every hit.
    if (scene.photons.estimator != IndirectEstimator::Density) return nullptr;
    for (const Material& m : scene.materials) {
      if (m.pR > 0.0f || m.pT > 0.0f) return nullptr;
    }
    return "no surface can bounce a photon: every p_r and p_t is 0";
  }
  bool reflects(const Material& m, const PhotonSettings& ps) const override {
    return m.transparent || makeBsdf(m, info().bsdf, ps.sampling).kr > 0.0f;
  }

  PerMap<bool> emittedMaps(const PerMap<bool>& wanted, uint32_t) const override {
    PerMap<bool> maps;
    maps[MapKind::Shadow] = wanted[MapKind::Shadow];
    maps[MapKind::Indirect] = wanted[MapKind::Indirect];
    return maps;
  }
  void emit(const Scene& scene, const TraceScene& tracer, const EmitOptions& options, uint32_t,
            Emission& e) const override {
    if (options.maps[MapKind::Shadow] || options.maps[MapKind::Indirect]) {
      emitPhotons(scene, tracer, options, e.photons);
    }
  }
  int passes(const Scene& scene, Aov aov) const override {
    return readsLight(aov) ? std::max(1, scene.photons.passes) : 1;
  }
  bool freshPhotonsEachPass() const override { return false; }
  IndirectLookup indirectLookup(const PhotonSettings& ps) const override {
    const CachedIndirect kind = ps.estimator == IndirectEstimator::Density ? CachedIndirect::Density
                                                                           : CachedIndirect::Classic;
    return {MapKind::Indirect, kind, ps.kIndirect, ps.maxRadius, cost::kGatherNsPerNeighbour};
  }
  PerMap<PhotonGather> gathers(const PhotonSettings& ps, uint32_t, uint32_t) const override {
    PerMap<PhotonGather> g;
    g[MapKind::Indirect] = {ps.kIndirect, ps.maxRadius};
    return g;
  }

  std::string photonSummary(const Scene& scene, const MapCounts&, const RenderStats& stats, bool gate) const override {
    const PhotonSettings& ps = scene.photons;
    return fmt::format(
        "shadow_photons={} indirect_photons={} k_shadow={} k_indirect={} "
        "max_radius={} max_bounces={} sampling={} gate={} estimator={}",
        stats.emitted[MapKind::Shadow], stats.emitted[MapKind::Indirect], ps.kShadow, ps.kIndirect, ps.maxRadius,
        ps.maxBounces, samplingName(ps.sampling), gate ? "on" : "off", estimatorName(ps.estimator));
  }
  void addModelSettings(const Scene& scene, const MapCounts& budgets, const RenderStats&,
                        ImageMetadata& m) const override {
    const PhotonSettings& ps = scene.photons;
    auto add = [&m](const char* key, const auto& value) {
      m.emplace_back(std::string("penumbra:") + key, fmt::format("{}", value));
    };
    const Color& a = scene.render.ambient;
    add("ambient", fmt::format("{} {} {}", a.r, a.g, a.b));
    add("photons.indirect", budgets[MapKind::Indirect]);
    add("photons.k_indirect", ps.kIndirect);
    add("photons.max_radius", ps.maxRadius);
    add("photons.sampling", samplingName(ps.sampling));
    add("photons.estimator", estimatorName(ps.estimator));
  }

 private:
  static const char* samplingName(HemisphereSampling s) {
    return s == HemisphereSampling::Cosine ? "cosine" : "uniform";
  }
  static const char* estimatorName(IndirectEstimator e) {
    return e == IndirectEstimator::Classic ? "classic" : "density";
  }
};

}  // namespace

const TransportModel& classicTransport() {
  static const ClassicTransport kClassic;
  return kClassic;
}

}  // namespace penumbra
