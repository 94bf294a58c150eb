// Shared by the physical-model analytic tests: a photon-free physical scene, Lambert
// materials, and one traced ray with a chosen set of terms.
#pragma once
#include "core/light_sample.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "emit/emit.h"
#include "emit/emit_physical.h"
#include "gather/photon_map.h"
#include "gather/radiance_estimate.h"
#include "trace/physical.h"
#include "io/shapes.h"
#include <gtest/gtest.h>
#include <cmath>
#include <string>
#include <vector>
#include "support/bsdf_sampling.h"
#include "support/render_fixtures.h"

namespace penumbra {


inline Material lambert(const std::string& name, Color rho) {
  Material m = makeMaterial(name, Color(0.0f), rho);
  m.shininess = 0.0f;
  return m;
}

// A physical-model scene with no photons unless a test asks for them.
inline Scene physicalScene() {
  Scene s;
  s.render.model = ShadingModel::Physical;
  s.render.seed = 20261201;
  s.photons.globalPhotons = 0;
  s.photons.causticPhotons = 0;
  s.photons.shadowPhotons = 0;
  s.camera = axisCamera(Vec3(0.0f, 0.0f, 5.0f), Vec3(0.0f));
  return s;
}

inline Color trace(const Rig& rig, const Ray& ray, uint8_t terms) {
  ThreadState ts;
  return tracePhysical(rig.ctx, ray, 0, Color(1.0f), RayKind::Camera, terms, -1, ts);
}

inline double rel(double got, double want) { return std::abs(got - want) / std::abs(want); }

// The red channel of `runs` camera samples along `ray` (sample k keyed by (seed, k)):
// their mean and its standard error.
struct SampleMean {
  double mean = 0.0, standardError = 0.0;
};
inline SampleMean meanOverSamples(const Rig& rig, const Ray& ray, int runs, uint64_t seed, uint8_t terms) {
  double sum = 0.0, sum2 = 0.0;
  for (int k = 0; k < runs; ++k) {
    ThreadState ts;
    beginSample(ts, hashKey(seed, k));
    const double v = tracePhysical(rig.ctx, ray, 0, Color(1.0f), RayKind::Camera, terms, -1, ts).r;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / runs;
  return {mean, std::sqrt(std::max(0.0, sum2 / runs - mean * mean) / runs)};
}

// A one-sided quad light (emitting towards e1 x e2) of uniform radiance colour x radiance.
inline Light quadLight(Vec3 corner, Vec3 e1, Vec3 e2, Color colour, float radiance) {
  Light l;
  l.type = LightType::Quad;
  l.position = corner;
  l.edge1 = e1;
  l.edge2 = e2;
  l.color = colour;
  l.intensity = radiance;
  return l;
}

}  // namespace penumbra
