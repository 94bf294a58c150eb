// The physical model's integrator: exact direct light by shadow rays, caustic and
// global photon-map estimates at smooth surfaces, delta lobes followed by rays.
#pragma once
#include "trace/shading.h"

namespace penumbra {

// Which terms a physical render adds up: everything for beauty, one for an AOV.
enum PhysicalTerms : uint8_t {
  kTermDirect = 1 << 0,   // lights by shadow rays (or the gate)
  kTermCaustic = 1 << 1,  // the caustic map: L S+ D
  kTermGlobal = 1 << 2,   // the global map: light after >= 1 diffuse bounce
  kTermMissed = 1 << 3,   // the background seen by rays that leave the scene
  kTermEmitters = 1 << 4,  // area lights seen by the ray (not by a narrow lobe's: sampled as direct)
  kTermAll = kTermDirect | kTermCaustic | kTermGlobal | kTermMissed | kTermEmitters,
};

// Radiance along `ray` in W/(sr m^2). `throughput` is the product of the delta
// lobes' weights so far; recursion stops at max_depth or below min_weight. `medium`:
// the medium the ray starts in (a camera ray: Scene::cameraMedium).
Color tracePhysical(const ShadingContext& ctx, const Ray& ray, int depth, const Color& throughput,
                    RayKind kind, uint8_t terms, int parentRecord, ThreadState& ts, int medium = kNoMedium);
// The same for a ray already traced (a camera ray of a packet): `hit` is its first
// hit, null on a miss.
Color tracePhysicalHit(const ShadingContext& ctx, const Ray& ray, const Hit* hit, int depth,
                       const Color& throughput, RayKind kind, uint8_t terms, int parentRecord,
                       ThreadState& ts, int medium = kNoMedium);

}  // namespace penumbra
