// The closed box the photon-pass tests emit into: diffuse walls of a chosen
// reflectance around a point light, and a check that a count lies within a number of
// standard deviations of its mean.
#pragma once
#include "core/scene.h"
#include "io/shapes.h"
#include "support/scene_fixtures.h"
#include <gtest/gtest.h>
#include <cmath>
#include <string>

namespace penumbra::testing {

inline Material wallMaterial(float pR, Color diffuse = Color(0.8f)) {
  Material m;
  m.name = "wall";
  m.diffuse = diffuse;
  m.pR = pR;
  m.pT = 0.0f;
  return m;
}

inline Light pointLight(Vec3 p, float intensity = 1.0f, Color color = Color(1.0f)) {
  return point(p, color, intensity);
}

// A closed box [-h, h]^3 around a point light; no indirect photons by default.
inline Scene boxScene(float h, Vec3 light, uint64_t shadow, uint64_t indirect = 0, float pR = 0.0f) {
  Scene scene;
  scene.materials.push_back(wallMaterial(pR));
  scene.meshes.push_back(makeBox(Vec3(-h), Vec3(h), 0));
  scene.lights.push_back(pointLight(light));
  scene.photons.shadowPhotons = shadow;
  scene.photons.indirectPhotons = indirect;
  scene.render.seed = 12345;
  return scene;
}

// |k - mean| within `sigmas` standard deviations.
inline void expectWithinSigmas(double k, double mean, double sd, double sigmas, const std::string& what) {
  EXPECT_LT(std::abs(k - mean), sigmas * sd) << what << ": got " << k << ", expected " << mean
                                             << " +- " << sd;
}
}  // namespace penumbra::testing
