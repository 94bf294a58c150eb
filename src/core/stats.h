// Render statistics as plain counters. Parallel phases keep one RayCounts per
// thread (tbb::enumerable_thread_specific) and add them up afterwards.
#pragma once
#include "core/cpu_time.h"
#include "core/shading_model.h"
#include "core/error_estimate.h"
#include "core/map_kind.h"
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

struct RayCounts {
  uint64_t camera = 0, shadow = 0, reflection = 0, refraction = 0;
  // Ambiguity gate (one query per shading point and light).
  uint64_t gateQueries = 0, gateLit = 0, gateShadowed = 0, gateMixed = 0;
  uint64_t shadowRaysAvoided = 0;
  // Indirect gather.
  uint64_t gatherQueries = 0, gatherNeighbours = 0;
  // Precomputed lookups: cache queries, and estimates that fell back to an exact gather.
  uint64_t cacheLookups = 0, cacheFallbacks = 0;
  // Samples whose radiance came out NaN or infinite: dropped from their pixel.
  uint64_t nonfiniteSamples = 0;
  // Participating media (scenes with a medium): camera and specular ray stretches inside
  // a medium, the scattering points sampled on them (equiangular and distance, per light;
  // a grid's emission sample), volume-map gathers and the photons they found, shadow
  // rays that spent any length in a medium (from surfaces and from scattering points).
  uint64_t mediumSegments = 0, mediumSamples = 0, volumeGathers = 0, volumeNeighbours = 0, transmittanceRays = 0;

  RayCounts& operator+=(const RayCounts& o) {
    camera += o.camera; shadow += o.shadow; reflection += o.reflection; refraction += o.refraction;
    gateQueries += o.gateQueries; gateLit += o.gateLit; gateShadowed += o.gateShadowed;
    gateMixed += o.gateMixed; shadowRaysAvoided += o.shadowRaysAvoided;
    gatherQueries += o.gatherQueries; gatherNeighbours += o.gatherNeighbours;
    cacheLookups += o.cacheLookups; cacheFallbacks += o.cacheFallbacks;
    nonfiniteSamples += o.nonfiniteSamples;
    mediumSegments += o.mediumSegments; mediumSamples += o.mediumSamples; volumeGathers += o.volumeGathers;
    volumeNeighbours += o.volumeNeighbours; transmittanceRays += o.transmittanceRays;
    return *this;
  }
};

struct Timings {
  double load = 0, buildBvh = 0, emit = 0, buildMaps = 0, precompute = 0, render = 0, write = 0,
         total = 0;
};

// The stages by their --stats names (time_s.*), in the order a render runs them.
struct TimingField {
  const char* name;
  double Timings::*field;
};
constexpr TimingField kTimingFields[] = {
    {"load", &Timings::load},       {"build_bvh", &Timings::buildBvh},     {"emit", &Timings::emit},
    {"build_maps", &Timings::buildMaps}, {"precompute", &Timings::precompute}, {"render", &Timings::render},
    {"write", &Timings::write},     {"total", &Timings::total}};

struct RenderStats {
  std::string scene;
  int width = 0, height = 0, spp = 1, threads = 1;
  uint64_t seed = 0;
  Timings time;
  RayCounts rays;
  std::string model = shadingModelName(kDefaultShadingModel);
  int passes = 1;
  ErrorEstimate error;     // the image's noise (and bias change) without a reference
  std::string budget;      // --time-limit / --target-error as given; empty: none
  std::string budgetStop;  // ... and why the passes stopped
  MapCounts emitted, stored;  // photons per map, over every pass
  PerMap<float> gatherRadius;  // passes > 1: the last pass's typical (median k-nearest) radius per map
  uint64_t photonMapBytes = 0;
  std::string lookup = "exact";      // photons.lookup
  std::string gateMode = "auto";     // photons.gate as given
  bool gate = false;                 // ... and as decided
  std::string gateReason;            // why (auto: the cost model's estimate)
  std::string plan;                  // the render plan as JSON (plan/render_plan.h)
  uint64_t cacheRecords = 0;         // precomputed: cells (last pass)
  uint64_t cacheSplits = 0;          // precomputed: strata answered by a split line (last pass)
  uint64_t cacheLazyCells = 0;       // precomputed: cells the cache has computed on first use so far
  float cacheCell = 0.0f;            // precomputed: cell size (last pass)
  uint64_t cacheBytes = 0;
  uint64_t peakRssBytes = 0;
  CpuTiming cpu;  // the process's CPU time over the span of time.total
  std::vector<std::string> ignoredExtensions;  // a glTF scene's optional extensions left unread
  std::vector<std::string> defaultsAdded;      // what loading added to a glTF scene: "camera", "sky"
};

// Wall-clock stopwatch in seconds.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Peak resident set size of this process (VmHWM), 0 if unknown.
uint64_t peakRssBytes();

}  // namespace penumbra
