// Primary shadow packets: the same shadow rays shadowTransmittance builds (shadowRayTo
// from the same surface record and light sample), only traced 16 at a time.
#include "integrator/primary_shadows.h"
#include "core/bsdf.h"
#include "core/light_sample.h"
#include "gather/photon_map.h"
#include "integrator/light_visibility.h"

namespace penumbra {

uint32_t packetShadowLights(const ShadingContext& ctx, bool direct) {
  const Scene& scene = ctx.scene;
  const bool tinted = ctx.hasGlass && scene.render.model == ShadingModel::Classic;
  if (!direct || !scene.render.shadows || tinted) return 0;
  uint32_t mask = 0;
  for (uint32_t li = 0; li < scene.lights.size() && li < 32; ++li) {
    const Light& light = scene.lights[li];
    if (!isDeltaLight(light) || maxComponent(light.radiance()) <= 0.0f) continue;
    // As gateVerdict: with a gate for this light the verdict, not the ray, comes first.
    const bool gated = scene.photons.gate && ctx.shadowMap && ctx.shadowMap->hasPhotons(li);
    if (!gated) mask |= 1u << li;
  }
  return mask;
}

void tracePrimaryShadows(const ShadingContext& ctx, uint32_t lights, const Ray* rays,
                         const Hit* hits, int n, uint32_t* known, uint32_t* blocked,
                         PrimaryShadowScratch& scratch) {
  for (int i = 0; i < n; ++i) known[i] = blocked[i] = 0;
  if (lights == 0) return;
  const Scene& scene = ctx.scene;
  scratch.rays.resize(static_cast<size_t>(n));
  scratch.owner.resize(static_cast<size_t>(n));
  scratch.blocked.resize(static_cast<size_t>(n));
  for (uint32_t li = 0; li < scene.lights.size() && li < 32; ++li) {
    if (!((lights >> li) & 1u)) continue;
    const Light& light = scene.lights[li];
    int count = 0;
    for (int i = 0; i < n; ++i) {
      if (!hits[i].valid()) continue;
      const Material& m = scene.materials[ctx.tracer.materialOf(hits[i])];
      if (maxComponent(m.emission) > 0.0f) continue;  // an emitter only glows
      if (scene.render.model == ShadingModel::Physical &&
          !hasSmoothLobe(makeBsdf(m, ShadingModel::Physical, scene.photons.sampling)) && m.texture < 0)
        continue;  // a mirror or glass: no direct term (a texture may add a lobe: keep it)
      // The record the integrators build (position, normals and error bounds do not
      // depend on the uv fields).
      const SurfaceRecord s = ctx.tracer.surface(rays[i], hits[i], kSurfaceShadingNormal);
      // A delta light's one sample, as directFromLight draws it.
      const LightIncidence in = sampleLight(prepareLight(light, s.position), 0.5f, 0.5f);
      if (!in.valid || glm::dot(s.ng, in.wi) <= 0.0f || glm::dot(s.ns, in.wi) <= 0.0f) continue;
      known[i] |= 1u << li;
      if (!shadowRayTo(s, in, scratch.rays[static_cast<size_t>(count)])) continue;  // at the light: clear
      scratch.owner[static_cast<size_t>(count++)] = i;
    }
    ctx.tracer.occludedPacket(scratch.rays.data(), count, scratch.blocked.data());
    for (int j = 0; j < count; ++j) {
      if (scratch.blocked[static_cast<size_t>(j)]) blocked[scratch.owner[static_cast<size_t>(j)]] |= 1u << li;
    }
  }
}

}  // namespace penumbra
