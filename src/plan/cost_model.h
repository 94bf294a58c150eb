// Every cost the plan reasons with, in one place: per-operation times and bytes
// measured on the project's machine (docs/PERFORMANCE.md, "Resource estimate").
// Constants, not timings taken at render time, so decisions and images are the
// same on every run; the gate decision, the resource estimate and batch's shard
// balance all read them from here.
#pragma once
#include <cmath>

namespace penumbra::cost {

// Nanoseconds on one core.
constexpr double kShadowRayNs = 50.0;       // rtcOccluded1 to a light (bench_lookup)
constexpr double kRayNs = 100.0;            // a camera, shadow or specular ray with its shading
constexpr double kPhotonSegmentNs = 140.0;  // one photon ray + surface + store (bench_photons)
constexpr double kBuildNsPerPhoton = 200.0; // KD build per stored photon
// An environment's photon start beyond its segment, and per level of its map's
// search (a glTF box and environment_sky, 1 thread: CPU with and without the photons).
constexpr double kEnvironmentPhotonNs = 120.0;
constexpr double kEnvironmentMapLevelNs = 13.0;
// Exact gathers, per neighbour found, from a map that fits a core's caches
// (kGatherCacheBytes); each doubling of the map past them adds kGatherSlowdown, as
// the search waits on memory (gatherNsPerNeighbour). Classic: fig14_cornell's
// indirect map from 20k to 5M photons, 1 thread, against the render without it.
// Physical, with its shading: cornell_physical's global and caustic maps at 12
// passes of 200k photons and at 3 of 5k, 1 thread, over the neighbours --stats counts.
// Each model names its own (IndirectLookup::nsPerNeighbour) for the lookup decision.
constexpr double kGatherNsPerNeighbour = 19.0;
constexpr double kPhysicalGatherNsPerNeighbour = 42.0;
constexpr double kGatherCacheBytes = 64.0 * 1024;
constexpr double kGatherSlowdown = 0.05;
constexpr double kLookupNs = 80.0;          // one precomputed query per shading point, all lights
constexpr double kExactVoteNs = 3000.0;     // one exact k-nearest gate vote per light
constexpr double kShadowPhotonNs = 520.0;   // emit + build + cache, per emitted shadow photon
constexpr double kStartupSeconds = 0.2;     // load, BVH, set-up of a small scene (large BVHs: below)
// Loading the image module (OpenImageIO), once per process that reads an image: a
// texture, an environment map, an alpha mask (fig15_globe at 8x8 against fig01_depth,
// 1 thread: the dlopen of its libraries and the texture's first tiles).
constexpr double kImageModuleSeconds = 0.25;
// One filtered texture lookup at a shading point, per texture its material reads
// (fig15_globe at 640x480 and 16 spp, 1 thread, with and without --disable textures).
constexpr double kTextureLookupNs = 600.0;
constexpr double kBvhBuildNsPerPrimitive = 1200.0;  // Embree's build, per triangle or sphere
constexpr double kMeshLightSampleNs = 40.0;   // one sample of a mesh light: a point on a triangle
constexpr double kMeshLightLevelNs = 12.0;    // ... plus per level of its search by area
// Shading one light sample (the BSDF, the light's answer, the gate's verdict), charged
// where a camera pilot counted the shading points: the analytic depth factor's extra
// points stand in for it elsewhere (soft_shadows, 32 samples a point, 1 thread).
constexpr double kLightSampleShadeNs = 30.0;

// Participating media (plan/media_estimate.h): a photon's flight through a medium
// (free-flight sample, albedo roulette, phase sample, and the unstored ray a surface
// map's photon starts after a scatter: the fog room's and an infinite fog's photon
// phases set it between them), one light sample on a camera
// ray's segment (equiangular or distance, with the phase function; its transmittance
// ray is a kRayNs), a tracking step in a density grid, and the beam gather of the
// volume map per grid cell its walk visits and per photon found (bench_volume's box,
// 36 cells a beam, and bench_media's fog room, 73, measure them).
constexpr double kMediumEventNs = 200.0;
constexpr double kMediumSampleNs = 40.0;
constexpr double kTrackingStepNs = 15.0;
constexpr double kVolumeGatherNsPerCell = 100.0;
constexpr double kVolumeBuildNsPerPhoton = 450.0;  // the volume map's build, per stored photon
constexpr double kVolumeGatherNsPerNeighbour = 40.0;
// Medium segments a camera sample traces per level of the specular depth factor past
// the first (the fog room: 1.18 segments a sample, its depth factor 2).
constexpr double kMediumSegmentsPerSpecularLevel = 0.2;

// Shares.
constexpr double kAvoidable = 0.85;  // shadow tests a gate answers without a ray (soft_shadows)
// The same where precomputed cells keep a verdict per stratum of an area light, and a
// split line where a stratum's photons disagree: only samples near a stratum's own
// shadow edge cast rays (soft_shadows_dense, the lowest of the soft-shadow scenes).
constexpr double kAvoidableStratified = 0.95;
constexpr double kSpillSlowdown = 0.3;  // extra time per doubling of photon data past the caches

// Bytes.
constexpr double kIndexBytes = 8.25;               // KD index per photon: a 64-bit slot plus its part's nodes
constexpr double kBvhBytesPerPrimitive = 70.0;     // Embree's default BVH, triangles or spheres
constexpr double kBvhBuildBytesPerPrimitive = 32.0;  // Embree's build references, at the peak
constexpr double kCompactBvhBytesPerPrimitive = 36.0;  // the compact layout (trace_scene.h), its build's peak too
constexpr double kFrameBytesPerTriangle = 20.0;    // the tracer's geometric normal and error bounds
// Lookup-cache records: a cell holds this share of the photons photonsPerCacheCell puts
// in it where they lie on a plane (buckets by facing and surface edges split cells;
// measured: the showcase's indirect cells 0.47, soft_shadows' gate cells 0.60), and a
// gate record this many split lines per area light of several strata (measured 0.58
// soft_shadows, 0.90 soft_shadows_dense).
constexpr double kCacheCellFill = 0.47;
constexpr double kGateCellFill = 0.6;
constexpr double kSplitsPerStratifiedLight = 0.75;
constexpr double kBaseBytes = 140.0 * 1024 * 1024; // the process before any scene data
constexpr double kTextureCacheBytes = 1024.0 * 1024 * 1024;  // OIIO's cache cap (texture_lookup.cpp)
constexpr double kCacheFriendlyBytes = 256.0 * 1024 * 1024;  // photon data that still runs at full speed

// An exact gather's time per neighbour from a map of `mapBytes` (records and index).
inline double gatherNsPerNeighbour(double perNeighbourNs, double mapBytes) {
  const double doublings = mapBytes > kGatherCacheBytes ? std::log2(mapBytes / kGatherCacheBytes) : 0.0;
  return perNeighbourNs * (1.0 + kGatherSlowdown * doublings);
}

}  // namespace penumbra::cost
