// The resource model: stored photons from emitted counts x stores per path, bytes
// per record, image and BVH sizes, and a per-operation time model (plan/cost_model.h).
#include "plan/resource_estimate.h"
#include "plan/transport_model.h"
#include "plan/cost_model.h"
#include "plan/render_budget.h"
#include "plan/gate_decision.h"
#include "geometry/trace_scene.h"
#include "core/lights/environment_map.h"
#include "core/light_sample.h"
#include "core/light_strata.h"
#include "gather/lookup_cache/lookup_cache.h"
#include "gather/lookup_cache/lookup_cache_cells.h"
#include "core/photon.h"
#include "core/error_estimate.h"
#include "core/image_codec.h"
#include "gather/radiance_estimate.h"
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <cmath>
#include <map>

namespace penumbra {
namespace {

using namespace cost;
constexpr int kBuiltinTextureWidth = 2048;  // texture_gen.cpp's default; "@W" overrides
constexpr int kMaxHitsPerLine = 64;  // EmitOptions::maxHitsPerLine

bool hasSpecular(const Scene& scene) {
  for (const Material& m : scene.materials) {
    if (transportOf(scene).reflects(m, scene.photons)) return true;
  }
  return false;
}

// How often one straight line can cross a mesh: once if it is flat, twice if it
// is convex (checked for meshes small enough to test every vertex against every
// face), otherwise once per triangle up to the emitter's cap.
int maxCrossings(const TriangleMesh& mesh) {
  const size_t t = mesh.triangles.size();
  if (t == 0) return 0;
  if (t > 2048 || mesh.positions.size() > 4096) return kMaxHitsPerLine;
  Vec3 lo(mesh.positions[0]), hi(mesh.positions[0]);
  for (const Vec3& p : mesh.positions) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
  const float eps = 1e-4f * std::max(1e-6f, glm::length(hi - lo));
  bool planar = true, convex = true;
  for (const auto& tri : mesh.triangles) {
    const Vec3 a = mesh.positions[tri[0]];
    Vec3 n = glm::cross(mesh.positions[tri[1]] - a, mesh.positions[tri[2]] - a);
    const float len = glm::length(n);
    if (!(len > 0.0f)) continue;
    n /= len;
    bool above = false, below = false;
    for (const Vec3& p : mesh.positions) {
      const float d = glm::dot(n, p - a);
      above |= d > eps;
      below |= d < -eps;
    }
    planar &= !above && !below;
    convex &= !(above && below);
  }
  if (planar) return 1;
  if (convex) return 2;
  return static_cast<int>(std::min<size_t>(t, kMaxHitsPerLine));
}

// Sum over b = from..to of s^b: the expected stores of a path that survives each
// bounce with probability at most s and meets at most to + 1 surfaces.
double survivalSeries(double s, int from, int to) {
  double sum = 0.0, term = std::pow(s, from);
  for (int b = from; b <= to && term > 1e-12; ++b, term *= s) sum += term;
  return sum;
}

std::string gib(double bytes) { return formatBytes(bytes); }

// Drawing one sample of a light, before any shadow ray: a mesh light picks its
// triangle by binary search over the cumulative areas (a cache miss a level once
// the table outgrows the cache), then a point on it; the rest draw without a search.
double lightSampleNs(const Light& light) {
  const size_t table = lightSampleTable(light);
  if (table == 0) return 0.0;
  return kMeshLightSampleNs + kMeshLightLevelNs * std::log2(1.0 + table);
}

// Starting one photon at the environment, beyond its segment: a direction from its
// map (a search per level of the map's distribution) and a point on the disc facing
// the scene.
double environmentPhotonNs(const Scene& scene) {
  const Light* sky = environmentOf(scene);
  const double texels = sky && sky->environment ? double(sky->environment->width) * sky->environment->height : 0.0;
  return kEnvironmentPhotonNs + (texels > 0.0 ? kEnvironmentMapLevelNs * std::log2(1.0 + texels) : 0.0);
}

// The neighbours one of the physical model's gathers finds, averaged over its passes:
// pass i gathers the passK(k, i) nearest (a fixed photons.radius shrinks by the same
// share, so it holds about as many).
double meanPassNeighbours(int k, int passes, float alpha) {
  if (passes <= 1) return k;
  double sum = 0.0;
  for (int i = 0; i < passes; ++i) sum += passK(k, uint32_t(i), alpha);
  return sum / passes;
}

// From the file's header only (no pixels are read); a builtin texture from its name.
double textureBytes(const Scene& scene) {
  double bytes = 0.0;
  for (const Texture& t : scene.textures) {
    if (t.path.rfind("builtin:", 0) == 0) {
      const size_t at = t.path.find('@');
      const double w = at == std::string::npos ? kBuiltinTextureWidth : std::atof(t.path.c_str() + at + 1);
      bytes += w * (w / 2) * 3.0 * 4.0 / 3.0;
      continue;
    }
    std::string error;
    auto in = imageCodec().open(t.path, error);
    if (!in) continue;  // the texture stage reports unreadable files
    const ImageInfo& spec = in->info();
    bytes += double(spec.width) * spec.height * spec.nchannels * spec.pixelBytes * 4.0 / 3.0;
  }
  return std::min(bytes, kTextureCacheBytes);
}

// `n` stored photons per kind at its record's size (sizeof(PhotonOf<K>)) plus `extra`
// bytes each. Kinds sharing a record size are counted together first, in kAllMaps order.
double photonBytes(const PerMap<double>& n, double extra) {
  std::map<size_t, double> bySize;
  forEachKind([&](auto k) { bySize[sizeof(PhotonOf<decltype(k)::value>)] += n[k]; });
  double bytes = 0.0;
  for (const auto& [size, count] : bySize) bytes += count * (double(size) + extra);
  return bytes;
}

}  // namespace

double mapBytes(MapKind map, double photons) {
  PerMap<double> one;
  one[map] = photons;
  return photonBytes(one, cost::kIndexBytes);
}

StoreRates analyticStoreRates(const Scene& scene) {
  StoreRates r;
  const int bounces = scene.photons.maxBounces;
  int crossings = 2 * static_cast<int>(scene.spheres.size());
  for (const TriangleMesh& m : scene.meshes) crossings = std::min(kMaxHitsPerLine, crossings + maxCrossings(m));
  r.perPhoton[MapKind::Shadow] = std::min(kMaxHitsPerLine, crossings);
  // Classic roulette: a path goes on with p_r + p_t, so the surest material bounds
  // every path (a closed box of it reaches the bound: nothing escapes).
  double s = 0.0;
  for (const Material& m : scene.materials) s = std::max(s, std::min(1.0, double(m.pR) + m.pT));
  const bool firstHit = scene.photons.estimator == IndirectEstimator::Classic;
  r.perPhoton[MapKind::Indirect] = survivalSeries(s, firstHit ? 0 : 1, bounces);
  // Physical: survival is the sampled weight, up to 1 for mirrors and glass, and a
  // photon is stored at most once per surface after the first: bounded by the cap.
  r.perPhoton[MapKind::Global] = bounces;
  r.perPhoton[MapKind::Caustic] = bounces;
  r.perPhoton[MapKind::Volume] = mediaCost(scene, 0.0).storesPerPhoton;
  return r;
}

ResourceEstimate estimateResources(const Scene& scene, const EstimateOptions& options,
                                   const StoreRates& rates) {
  ResourceEstimate e;
  e.rates = rates;
  e.plan = options.photons;
  e.threads = std::max(1, options.threads);
  const PhotonPlan& p = e.plan;
  // The rates are means per path; a run's total strays from n x mean by ~sqrt(n)
  // paths' worth, so 3 sigma (sd per path <= mean for these geometric counts) on top.
  const auto stored = [](uint64_t n, double rate) {
    return n > 0 ? n * rate * (1.0 + 3.0 / std::sqrt(double(n))) : 0.0;
  };
  PerMap<double> n;
  for (MapKind k : kAllMaps) n[k] = stored(p.emitted[k], rates.perPhoton[k]);
  const double shadow = n[MapKind::Shadow];
  for (MapKind k : kAllMaps) e.storedPhotons += n[k];
  e.photonBytes = photonBytes(n, kIndexBytes);
  const PhotonSettings& ps = scene.photons;
  const IndirectLookup lookup = transportOf(scene).indirectLookup(ps);
  const double lookupPhotons = options.precomputed ? n[lookup.map] : 0.0;
  // The emitters' blocks and the sorted arrays each hold a copy while the maps build
  // (one map after another, so this bounds the peak from above); then a lookup cache's
  // build holds an entry per photon it bins, twice while it sorts them.
  const double mapCopy = photonBytes(n, 0.0);
  const double cacheSort = options.precomputed ? 2.0 * sizeof(CacheEntry) * (shadow + lookupPhotons) : 0.0;
  e.photonPeakBytes = e.photonBytes + std::max(mapCopy, cacheSort);
  // The file holds the records as emitted (no index), written from the emission's own
  // blocks and read into the arrays the maps build from: disk, and no memory beyond.
  if (options.mapFile) e.mapFileBytes = mapCopy;
  // A progressive pass emits its photons (all but the gate's) while the previous pass's maps still stand.
  PerMap<double> fresh = n;
  fresh[MapKind::Shadow] = 0.0;
  if (p.photonPasses > 1) e.photonPeakBytes += photonBytes(fresh, kIndexBytes);
  if (options.precomputed) {
    // A record per occupied cell, whose size is a multiple of the typical gather
    // radius: the lookup map's cells and the gate's (finer ones get a cache of their
    // own; summed, an upper bound either way), each with the gate's row of verdicts.
    double records = lookupPhotons / (photonsPerCacheCell(std::max(1, lookup.k), ps.lookupCell) * kCacheCellFill);
    size_t columns = 0, stratified = 0;
    if (shadow > 0.0) {
      records += shadow / (photonsPerCacheCell(ps.kShadow, ps.lookupCell, kMinPhotonsPerGateCell) * kGateCellFill);
      for (const Light& l : scene.lights) {
        columns += 1 + static_cast<size_t>(lightStrata(l));
        stratified += lightStrata(l) > 1;
      }
    }
    e.cacheBytes = LookupCache::estimateBytes(records, columns, kSplitsPerStratifiedLight * double(stratified),
                                              lookupPhotons > 0.0);
  }
  const double pixels = double(scene.camera.width) * scene.camera.height;
  // The frame; with progressive passes a second one to sum them, their spread (even and
  // odd sums) and the bias check's (the first half's even and odd sums, the drift:
  // core/error_estimate.h); else the samples' spread, or at one sample the
  // probes' error view (trace/probe_error.h); the writer's copy, its conversion to half,
  // and the encoded file, which is written from memory (io/image_io.cpp). A model that
  // probes its gathers' smoothing adds the pass's probe, its four sums and the two
  // products the bias figure forms from them (core/error_estimate.h).
  // A budget runs its passes as a progressive frame, whatever photons.passes says.
  const int passes = options.budgeted ? kBudgetMaxPasses : p.passes;
  const bool probes = passes >= kBiasMinPasses && transportOf(scene).integrator().probesSmoothing && !scene.hasMedia();
  const int frames = passes > 1 ? 7 + (probes ? 7 : 0) : 2;
  if (!options.tracePixel) e.imageBytes = pixels * (sizeof(Color) * frames + 12 + 6 + 6);
  double meshBytes = 0.0, tracerBytes = 0.0;
  size_t triangles = 0;
  for (const TriangleMesh& m : scene.meshes) {
    triangles += m.triangles.size();
    meshBytes += m.positions.size() * 12.0 + m.normals.size() * 12.0 + m.uvs.size() * 8.0 +
                 (m.tangents.size() + m.colors.size()) * 16.0 + m.triangles.size() * 12.0;
    // Embree reads the indices in place, and the vertices too where they are padded.
    tracerBytes += (hasVertexPadding(m.positions) ? 0.0 : m.positions.size() * 12.0) +
                   m.triangles.size() * kFrameBytesPerTriangle;
  }
  // Embree's BVH and the references its build holds at the peak, in the layout the
  // tracer picks, a copy of unpadded vertices, and the tracer's per-triangle frames:
  // every mesh object counts in full, instances of one file too (each is a copy).
  const double primitives = double(scene.spheres.size()) + double(triangles);
  e.bvhBytes = primitives * (compactBvh(triangles) ? kCompactBvhBytesPerPrimitive
                                                   : kBvhBytesPerPrimitive + kBvhBuildBytesPerPrimitive) +
               tracerBytes;
  // Alpha masks are decoded bytes the scene holds (one per texel), beside the cache.
  double maskBytes = 0.0;
  for (const AlphaMask& mask : scene.alphaMasks) maskBytes += double(mask.bytes());
  // An environment map's texels and sampling tables, as the loader judged them.
  const Light* sky = environmentOf(scene);
  const double skyBytes = sky && sky->environment
                              ? environmentMapBytes(sky->environment->width, sky->environment->height)
                              : 0.0;
  e.sceneBytes = meshBytes + textureBytes(scene) + maskBytes + skyBytes;
  e.baseBytes = kBaseBytes;

  // Time: each stored photon is one traced segment, plus the one that escapes.
  const double emitted = double(p.emitted.total());
  // The volume map's grid sorts its records by cell and hashes its rows: its own build cost.
  const double volumeStored = n[MapKind::Volume];
  const double photonNs = (e.storedPhotons + emitted) * kPhotonSegmentNs +
                          (e.storedPhotons - volumeStored) * kBuildNsPerPhoton + volumeStored * kVolumeBuildNsPerPhoton +
                          double(p.environmentPhotons) * environmentPhotonNs(scene);
  // Past the caches the emission's stores and the build's gathers wait on memory, so
  // the per-photon costs grow with the log of the data past kCacheFriendlyBytes
  // (the constants are in plan/cost_model.h).
  // Media: each flight through one samples a free path; in a medium filling the scene
  // every map's flights do, elsewhere only the volume map's are priced.
  e.media = mediaCost(scene, n[MapKind::Volume]);
  const double volumeFlights = n[MapKind::Volume] + double(p.emitted[MapKind::Volume]);
  const double flights = scene.sceneMedium != kNoMedium ? e.storedPhotons + emitted : volumeFlights;
  const double mediaPhotonNs = e.media.any ? flights * e.media.photonEventNs : 0.0;
  const double spill = std::max(1.0, e.photonPeakBytes / kCacheFriendlyBytes);
  const auto seconds = [&](double ns) {
    return ns * (1.0 + kSpillSlowdown * std::log2(spill)) * p.photonPasses / e.threads * 1e-9;
  };
  e.photonSeconds = seconds(photonNs + mediaPhotonNs);
  e.mediaPhotonSeconds = seconds(mediaPhotonNs + volumeFlights * kPhotonSegmentNs);
  const double samples = options.tracePixel ? 1.0 : pixels * scene.camera.spp;
  const bool lit = readsLight(options.aov);
  // Mirrors and glass repeat the shading at each level of the recursion, but few
  // paths go many levels deep, so the factor is capped.
  const double depth = lit && hasSpecular(scene) ? 1.0 + 0.25 * std::min(scene.render.maxDepth, 4) : 1.0;
  // A camera pilot counts them in this view instead, and the rays that miss.
  const bool piloted = options.pointsPerSample + options.missesPerSample > 0.0 && !options.tracePixel;
  const double shadings = samples * p.passes * (piloted ? options.pointsPerSample : depth);  // of the whole render
  const double misses = piloted ? samples * p.passes * options.missesPerSample : 0.0;
  double lookupNs = 0.0, samplesPerPoint = 0.0, raysPerPoint = 0.0, sampleNs = 0.0;
  const bool gated = p.emitted[MapKind::Shadow] > 0;
  if (lit && options.shadows) {
    for (const Light& l : scene.lights) {
      const double count = lightSampleCount(l, options.lightSamples);
      samplesPerPoint += count;
      sampleNs += count * lightSampleNs(l);
      // The gate answers most tests without a ray, but not a mesh light's: a large
      // emitter close to what it lights leaves most points mixed, and one without a
      // closed form (over 64 triangles) still draws every sample on a lit verdict.
      // An environment is never gated, and the physical model adds a BSDF sample to
      // each of its light samples (trace/environment_light.h): count both.
      if (lightTraits(l).direct == DirectSampling::EnvironmentMis) raysPerPoint += 2.0 * count;
      else if (gated && lightTraits(l).gateAvoidsRays) raysPerPoint += count * (1.0 - avoidableShare(l, options.precomputed));
      else raysPerPoint += count;
    }
    if (gated) lookupNs += options.precomputed ? kLookupNs : kExactVoteNs * scene.lights.size();
  }
  e.lightSamples = shadings * samplesPerPoint;
  e.shadowRays = shadings * raysPerPoint;
  // An exact gather's time per neighbour grows with its map's bytes (one pass's map).
  const auto perNeighbourNs = [&](MapKind map, double ns) { return gatherNsPerNeighbour(ns, mapBytes(map, n[map])); };
  if (p.emitted[MapKind::Indirect] > 0) {
    lookupNs += options.precomputed ? kLookupNs : ps.kIndirect * perNeighbourNs(MapKind::Indirect, lookup.nsPerNeighbour);
  }
  // The physical model gathers where a camera path meets a diffuse surface, once per
  // sample, pass and map unpiloted (glass's split paths add a tenth in
  // cornell_physical), and a gather costs the neighbours it finds, fewer each pass.
  double physicalNs = 0.0;
  for (const auto& [map, k] : {std::pair{MapKind::Global, ps.kGlobal}, std::pair{MapKind::Caustic, ps.kCaustic}}) {
    if (p.emitted[map] == 0) continue;
    if (options.precomputed) lookupNs += kLookupNs;
    else physicalNs += meanPassNeighbours(k, p.passes, ps.alpha) * perNeighbourNs(map, kPhysicalGatherNsPerNeighbour);
  }
  // Every triangle and sphere of every mesh object, instances of one file included:
  // Embree builds over all of them.
  e.primitives = primitives;
  e.bvhSeconds = primitives * kBvhBuildNsPerPrimitive / e.threads * 1e-9;
  const double gathers = samples * p.passes * (piloted ? options.diffusePerSample : 1.0);
  const double shadeNs = piloted ? samplesPerPoint * kLightSampleShadeNs : 0.0;
  // Every ray segment that crosses a medium (a camera ray, or a mirror's or glass's) does
  // its medium work: the pilot's rays, or each camera sample's and a share per level of
  // the specular depth factor (a shading point is not a ray: glass splits, paths end).
  const double segments = piloted ? shadings + misses
                                  : samples * p.passes * (1.0 + kMediumSegmentsPerSpecularLevel * (depth - 1.0));
  const double mediaNs = e.media.any ? segments * e.media.cameraShare * e.media.rayNs() : 0.0;
  e.mediaCameraSeconds = mediaNs / e.threads * 1e-9;
  // A pilot counts the textures its shading points read; without one, none are priced.
  const double textureNs = piloted ? samples * p.passes * options.texturesPerSample * kTextureLookupNs : 0.0;
  const double ns = shadings * (kRayNs + lookupNs + sampleNs + shadeNs) + (e.shadowRays + misses) * kRayNs +
                    gathers * physicalNs + mediaNs + textureNs;
  e.renderSeconds = kStartupSeconds + e.bvhSeconds + ns / e.threads * 1e-9;
  return e;
}

std::string formatDuration(double s) {
  if (s >= 2 * 3600.0) return fmt::format("{:.0f} h", s / 3600.0);
  if (s >= 120.0) return fmt::format("{:.0f} min", s / 60.0);
  return fmt::format("{:.0f} s", s);
}

std::string describeMemory(const ResourceEstimate& e) {
  const std::string disk = e.mapFileBytes > 0.0 ? fmt::format("; map file {} on disk", gib(e.mapFileBytes)) : "";
  return fmt::format("~{} (photons {} for {:.3g} stored, image {}, bvh {}, cache {}, scene {}, base {}{})",
                     gib(e.totalBytes()), gib(e.photonPeakBytes), e.storedPhotons, gib(e.imageBytes),
                     gib(e.bvhBytes), gib(e.cacheBytes), gib(e.sceneBytes), gib(e.baseBytes), disk);
}

std::string estimateToJson(const ResourceEstimate& e) {
  nlohmann::json j;
  j["bytes"] = {{"total", e.totalBytes()},     {"photon_maps", e.photonBytes},
                {"photon_peak", e.photonPeakBytes}, {"lookup_cache", e.cacheBytes},
                {"image", e.imageBytes},       {"bvh", e.bvhBytes},
                {"scene", e.sceneBytes},       {"base", e.baseBytes}};
  if (e.mapFileBytes > 0.0) j["disk"] = {{"map_file", e.mapFileBytes}};
  j["stored_photons"] = e.storedPhotons;
  j["store_rates"] = {{"measured", e.rates.measured}};
  for (MapKind k : kAllMaps) {
    if (k == MapKind::Volume && e.rates.perPhoton[k] == 0.0) continue;  // no medium: as before media
    j["store_rates"][mapName(k)] = e.rates.perPhoton[k];
  }
  j["seconds"] = {{"total", e.seconds()}, {"photons", e.photonSeconds}, {"render", e.renderSeconds},
                  {"bvh", e.bvhSeconds}, {"threads", e.threads}};
  j["counts"] = {{"light_samples", e.lightSamples}, {"shadow_rays", e.shadowRays},
                 {"primitives", e.primitives}};
  if (e.media.any) j["media"] = mediaCostJson(e.media, e.mediaCameraSeconds, e.mediaPhotonSeconds);
  return j.dump();
}

}  // namespace penumbra
