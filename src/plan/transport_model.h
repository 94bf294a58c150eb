// A light-transport model as the plan sees it: the views it renders, the photon maps
// that carry its light and which view reads each, how it emits them, how many passes
// a frame takes, what its lookups precompute, and the integrator that shades. The
// model is chosen once per scene (transportOf); no stage tests it again.
#pragma once
#include "core/map_kind.h"
#include "core/scene.h"
#include "core/stats.h"
#include "core/view.h"
#include "emit/emit.h"
#include "gather/lookup_cache/lookup_cache.h"
#include "gather/radiance_estimate.h"
#include "io/image_io.h"
#include "trace/integrator.h"
#include <vector>

namespace penumbra {

struct Emission;

// What the precomputed lookups estimate from a model's light map, besides the gate.
struct IndirectLookup {
  MapKind map;          // the map read per cell
  CachedIndirect kind;  // the estimate stored per cell
  int k;                // neighbours per estimate
  float maxRadius;      // 0: none (a progressive pass gathers in its own fixed radius)
  double nsPerNeighbour;  // an exact gather's cost per neighbour found, from a cached map (plan/cost_model.h)
};

class TransportModel {
 public:
  virtual ~TransportModel() = default;
  // Its row of core/shading_model.h: render.model's value and its BSDF family.
  virtual ShadingModel id() const = 0;
  const ShadingModelInfo& info() const { return shadingModelInfo(id()); }
  const char* name() const { return info().name; }
  virtual const Integrator& integrator() const = 0;
  // The views it renders (depth and normal need no model: every model has them).
  virtual bool hasView(Aov aov) const = 0;

  // The maps that carry its light, beside the gate's shadow map (which both models
  // emit for the gate), and which views read each.
  virtual const std::vector<MapKind>& lightMaps() const = 0;
  virtual bool readsMap(MapKind map, Aov aov) const = 0;
  // Why `map` would store nothing in `scene` (null: it can store).
  virtual const char* cannotStore(MapKind map, const Scene& scene) const = 0;
  // A material that sends the recursion on (a mirror or glass in this model's terms).
  virtual bool reflects(const Material& m, const PhotonSettings& ps) const = 0;

  // Of the maps the plan wants, those progressive pass `pass` emits (a map of the
  // other model never; the gate's photons once).
  virtual PerMap<bool> emittedMaps(const PerMap<bool>& wanted, uint32_t pass) const = 0;
  // Emits options.maps (as emittedMaps chose them) for pass `pass` into `e`.
  virtual void emit(const Scene& scene, const TraceScene& tracer, const EmitOptions& options, uint32_t pass,
                    Emission& e) const = 0;
  // Frames a view averages: photons.passes for views that read light.
  virtual int passes(const Scene& scene, Aov aov) const = 0;
  // Whether each pass emits fresh photons (a consistent estimator) or every pass
  // reads pass 0's maps and only takes new camera samples.
  virtual bool freshPhotonsEachPass() const = 0;
  virtual IndirectLookup indirectLookup(const PhotonSettings& ps) const = 0;
  // Each light map's gather (k nearest, radius) in progressive pass `pass` of `passes`.
  virtual PerMap<PhotonGather> gathers(const PhotonSettings& ps, uint32_t pass, uint32_t passes) const = 0;

  // The image's settings line (its photon part) and EXR keys for the settings only
  // this model reads.
  virtual std::string photonSummary(const Scene& scene, const MapCounts& budgets, const RenderStats& stats,
                                    bool gate) const = 0;
  virtual void addModelSettings(const Scene& scene, const MapCounts& budgets, const RenderStats& stats,
                                ImageMetadata& m) const = 0;
};

const TransportModel& classicTransport();   // plan/classic_transport.cpp
const TransportModel& physicalTransport();  // plan/physical_transport.cpp

// The model the scene chose (modelOf): the one place the plan turns the choice into code.
inline const TransportModel& transportOf(const Scene& scene) {
  return modelOf(scene.render).id == ShadingModel::Physical ? physicalTransport() : classicTransport();
}

}  // namespace penumbra
