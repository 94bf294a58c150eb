// The render Rig: renders a hand-built Scene through the integrators, without
// photon maps unless a test attaches them.
#pragma once
#include "trace/camera.h"
#include "trace/render.h"
#include "trace/shading.h"
#include "geometry/trace_scene.h"
#include "support/scene_fixtures.h"

namespace penumbra {

// What a frame without a render plan decides: the scene's own settings (a gate unless
// photons.gate is off) and its model's integrator.
inline FrameChoices sceneChoices(const Scene& scene) {
  const Integrator& integrator =
      scene.render.model == ShadingModel::Physical ? physicalIntegrator() : whittedIntegrator();
  FrameChoices c;
  c.gate = scene.photons.gateMode != GateMode::Off;
  c.shadows = scene.render.shadows;
  c.lightSamples = scene.render.lightSamples;
  c.volumeSamples = scene.render.volumeSamples;
  c.packets = scene.render.packets;
  c.integrator = &integrator;
  return c;
}

// Each map's gather in a frame of one pass (both models' maps).
inline PerMap<PhotonGather> sceneGathers(const PhotonSettings& ps) {
  PerMap<PhotonGather> g;
  g[MapKind::Indirect] = {ps.kIndirect, ps.maxRadius};
  g[MapKind::Global] = {ps.kGlobal, 0.0f};
  g[MapKind::Caustic] = {ps.kCaustic, 0.0f};
  return g;
}

// Everything a render needs, built from a Scene owned by the caller.
struct Rig {
  explicit Rig(const Scene& s) : scene(s), tracer(s), ctx(s, tracer, sceneChoices(s)) {
    ctx.gathers = sceneGathers(s.photons);
    ctx.hasGlass = sceneHasGlass(s);
    ctx.pixelSpread = CameraRays(s.camera).pixelSpread();
  }
  Color shade(const Ray& ray, RayTree* tree = nullptr) const {
    ThreadState ts;
    ts.recorder = tree;
    return traceRay(ctx, ray, 0, Color(1.0f), 0.0f, RayKind::Camera, -1, ts);
  }
  Image render(Aov aov = Aov::Beauty) const {
    RenderOptions options;
    options.aov = aov;
    RayCounts counts;
    return renderImage(ctx, options, counts);
  }
  const Scene& scene;
  TraceScene tracer;
  ShadingContext ctx;
};

}  // namespace penumbra
