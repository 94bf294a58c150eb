// Whitted-style shading: Phong per light, gated shadow rays, recursive mirror
// reflection and Fresnel refraction, with the photon maps' indirect term.
#pragma once
#include "core/ray_record.h"
#include "core/scene.h"
#include "core/stats.h"
#include "core/map_kind.h"
#include "gather/photon_map_for.h"
#include "gather/radiance_estimate.h"
#include "geometry/trace_scene.h"
#include "trace/integrator.h"
#include <memory>

namespace penumbra {

class LookupCache;
class TextureLookup;
struct GatherScratch;

// What the render plan decided for a frame (plan/render_plan.h: choicesOf), read by
// the tracer beside the scene's settings, which stay as the user gave them.
struct FrameChoices {
  bool gate = true;         // ask the shadow photon map before casting a shadow ray
  bool shadows = true;      // false: lights reach every surface facing them
  bool reflection = true;   // mirror and glass-reflected recursion
  bool refraction = true;   // glass-transmitted recursion
  int lightSamples = 16;    // per area light and shading point
  int volumeSamples = 1;    // single scattering: per light and medium stretch
  bool packets = true;      // camera rays and their shadow rays as Embree packets
  const Integrator* integrator = nullptr;  // the transport model's shading
};

template <class Photon>
using ConstMapPtr = const PhotonMapFor<Photon>*;

// Read-only inputs shared by all render threads.
struct ShadingContext {
  ShadingContext(const Scene& s, const TraceScene& t, const FrameChoices& c) : scene(s), tracer(t), choices(c) {}
  const Scene& scene;
  const TraceScene& tracer;
  FrameChoices choices;
  // The maps the frame reads, null where none is stored: no shadow map, every shadow
  // test is a ray; no indirect map, the ambient term is used.
  MapSlots<ConstMapPtr> maps{};
  // Each map's gather in this pass (the transport model's): the k nearest (a progressive
  // pass's k shrinks) within the radius (0: any distance), or with k = 0 every photon within it.
  PerMap<PhotonGather> gathers;
  const TextureLookup* textures = nullptr;
  // photons.lookup = precomputed: the indirect (classic) or global (physical,
  // Lambertian part) estimate read from `lookup`, the gate verdicts from `gateLookup`
  // (the same cache, or one of finer cells); one query of each per shading point.
  const LookupCache* lookup = nullptr;
  const LookupCache* gateLookup = nullptr;
  uint32_t pass = 0;  // progressive pass: sample streams continue after earlier passes'
  uint32_t passes = 1;  // of the frame: more than one draws camera samples from a sequence over all
  float classicScale = 1.0f;  // turns stored photon flux back into photon colour
  float pixelSpread = 0.0f;   // radians per pixel, for texture filter widths
  bool hasGlass = false;      // some material is transparent (GlassShadows says what it does)
};

// Rays one camera sample may spawn (itself included). Every glass hit spawns two
// rays, so nested glass at a deep max_depth would otherwise grow the tree
// exponentially; a normal scene at depth 6 needs at most 127.
constexpr int kMaxRaysPerSample = 1024;

// Per-thread mutable state: counters, reusable gather buffers, optional recorder.
struct ThreadState {
  ThreadState();
  ~ThreadState();
  ThreadState(ThreadState&&) noexcept;
  RayCounts counts;
  std::unique_ptr<GatherScratch> scratch;
  RayTree* recorder = nullptr;  // --trace-pixel: every ray appended here
  int currentRecord = -1;       // the recorded ray being shaded: parent of its shadow rays
  int raysLeft = kMaxRaysPerSample;  // reset for every camera sample
  // Light samples draw from (camera sample key, shading point along its ray tree,
  // light): the same numbers for any thread count.
  uint64_t sampleKey = 0;
  uint32_t shadingPoint = 0;
  // Shadow rays of this sample's camera hit (shading point 1) already traced in a
  // packet (tracePrimaryShadows, light_visibility.h): bit li of `knownShadows` says light li's
  // answer is in bit li of `blockedShadows`. Zero outside the packet path.
  uint32_t knownShadows = 0, blockedShadows = 0;
  // Scenes with media: the medium around the shading point whose shadow rays are being
  // cast (the side its ray arrived from, the only side a light sample faces), and how
  // many medium streams this sample has drawn (each seeds one from sampleKey).
  int medium = kNoMedium;
  uint32_t mediumDraws = 0;
  // The photon estimates' smoothing bias this sample's ray tree gathered, weighted as
  // the estimates are (when the context's gathers probe it; 0 otherwise).
  Color smoothing{0.0f};
};

// A camera sample starts: its key seeds every light sample of its ray tree.
inline void beginSample(ThreadState& ts, uint64_t key) {
  ts.sampleKey = key ^ 0x6c69676874736d70ull;  // "lightsmp": a stream apart from the pixel's
  ts.shadingPoint = 0;
  ts.knownShadows = ts.blockedShadows = 0;
  ts.mediumDraws = 0;
  ts.smoothing = Color(0.0f);
}

enum class RayKind { Camera, Reflection, Refraction };

// Radiance arriving along `ray`. `weight` is the path throughput so far (used
// only to stop recursion when it becomes negligible); `cone` is the ray's
// footprint width at its origin, for texture filtering.
Color traceRay(const ShadingContext& ctx, const Ray& ray, int depth, const Color& weight,
               float cone, RayKind kind, int parentRecord, ThreadState& ts);
// The same for a ray already traced (a camera ray of a packet): `hit` is its first
// hit, null on a miss.
Color traceRayHit(const ShadingContext& ctx, const Ray& ray, const Hit* hit, int depth,
                  const Color& weight, float cone, RayKind kind, int parentRecord, ThreadState& ts);

bool sceneHasGlass(const Scene& scene);

// Shared by both integrators (ray_tree.cpp): ray counters, --trace-pixel records,
// and the mirror direction that never points into the surface.
void countRay(RayKind kind, RayCounts& counts);
int beginRecord(ThreadState& ts, RayKind kind, const Ray& ray, int depth, const Color& weight,
                int parent);
void endRecord(ThreadState& ts, int index, const Hit& hit, const SurfaceRecord& s,
               const Material& m, const Color& contribution, const std::string& note);
// The shaded surface into record `index`: `s` after any normal map, `interpolated` the
// shading normal before it, the material as evaluated at the hit.
struct EvaluatedMaterial {
  Color base;
  float metallic, roughness;
};
void recordSurface(ThreadState& ts, int index, const SurfaceRecord& s, const Vec3& interpolated, const Material& m,
                   const EvaluatedMaterial& evaluated);
Vec3 mirrorDirection(const Vec3& dir, const SurfaceRecord& s);

// Whether shading this material reads the hit's uv (some texture of it).
inline bool readsUv(const Material& m) {
  return m.texture >= 0 || m.metalRoughTexture >= 0 || m.normalTexture >= 0 || m.emissionTexture >= 0;
}

// What an emitting surface sends back along a ray: its emission (times its emissive
// texture) on its emitting side. A light's glow belongs to the direct term, which a
// ray whose lights are sampled leaves out (`lightsSampled`); a decorative emitter,
// which no light sampling covers, glows for every ray.
Color emitterGlow(const ShadingContext& ctx, const Material& m, const SurfaceRecord& s, float footprint,
                  bool lightsSampled);


}  // namespace penumbra
