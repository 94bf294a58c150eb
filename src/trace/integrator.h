// A transport model's shading as the tile loop sees it: one camera sample of a view,
// one pixel's ray tree, and how its shadow rays meet glass. Whitted (classic) and
// physical each provide one; the plan picks it once per frame (FrameChoices).
#pragma once
#include "core/scene.h"
#include "core/view.h"
#include "geometry/trace_scene.h"

namespace penumbra {

struct ShadingContext;
struct ThreadState;

// Classic glass tints a shadow ray (a walk through every surface); physical glass
// blocks it like anything else, since light through glass arrives as caustic photons.
enum class GlassShadows : uint8_t { Tint, Block };

struct Integrator {
  const char* name;
  // One camera sample of a view that reads light (not depth or normal): `hit` is the
  // ray's first hit, already traced (alone or in a packet), null on a miss.
  Color (*sample)(const ShadingContext& ctx, const Ray& ray, const Hit* hit, Aov aov, ThreadState& ts);
  // The full ray tree of one camera ray (--trace-pixel records it into ts.recorder).
  void (*tree)(const ShadingContext& ctx, const Ray& ray, ThreadState& ts);
  // Whether a camera hit on `m` may take direct light by shadow rays, so the packet
  // path traces those rays ahead (light_visibility.h: tracePrimaryShadows).
  bool (*shadesDirect)(const Scene& scene, const Material& m);
  GlassShadows glass;
  // Whether its photon gathers add their smoothing bias to ThreadState::smoothing when
  // the context's gathers ask (PhotonGather::probeSmoothing).
  bool probesSmoothing;
};

const Integrator& whittedIntegrator();   // trace/whitted.cpp
const Integrator& physicalIntegrator();  // trace/physical.cpp

}  // namespace penumbra
