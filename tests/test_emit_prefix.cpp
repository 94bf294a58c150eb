// Prefix reuse against fresh emissions: a smaller budget cut out of a larger
// emission holds exactly the photons a fresh emission of that budget stores (same
// positions, directions, normals, lights, in the same order), with powers within
// the packing's rounding, for several lights of different power, in both models.
#include "emit/emit.h"
#include "support/emit_fixtures.h"
#include "emit/emit_physical.h"
#include "emit/photon_prefix.h"
#include "io/shapes.h"
#include "support/scene_fixtures.h"
#include <gtest/gtest.h>

namespace penumbra {
namespace {

// An open box with a mirror sphere: photons bounce (pR) and some are caustic.
Scene prefixScene() {
  Scene scene;
  Material wall = makeMaterial("wall", Color(0.1f), Color(0.7f, 0.5f, 0.3f));
  wall.pR = 0.6f;
  Material mirror = makeMaterial("mirror", Color(0.0f), Color(0.0f));
  mirror.kr = 1.0f;
  scene.materials = {wall, mirror};
  scene.meshes.push_back(makeBox(Vec3(-1.0f), Vec3(1.0f), 0));
  scene.spheres.push_back({Vec3(0.3f, -0.6f, 0.2f), 0.3f, 1});
  scene.lights.push_back(point(Vec3(0.2f, 0.7f, 0.1f), Color(1.0f), 3.0f));
  scene.lights.push_back(point(Vec3(-0.5f, 0.5f, -0.3f), Color(1.0f, 0.5f, 0.2f), 1.3f));
  Light quad;
  quad.type = LightType::Quad;
  quad.position = Vec3(-0.2f, 0.99f, -0.2f);
  quad.edge1 = Vec3(0.0f, 0.0f, 0.4f);
  quad.edge2 = Vec3(0.4f, 0.0f, 0.0f);
  quad.intensity = 2.0f;
  scene.lights.push_back(quad);
  scene.render.seed = 7;
  scene.photons.maxBounces = 8;
  return scene;
}

void expectSameShadow(const PhotonArray<ShadowPhoton>& a, const PhotonArray<ShadowPhoton>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].position, b[i].position) << i;
    ASSERT_EQ(a[i].light, b[i].light) << i;
    ASSERT_EQ(a[i].shadow, b[i].shadow) << i;
  }
}

void expectSameIndirect(const PhotonArray<IndirectPhoton>& a, const PhotonArray<IndirectPhoton>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].position, b[i].position) << i;
    ASSERT_EQ(a[i].direction, b[i].direction) << i;
    ASSERT_EQ(a[i].normal, b[i].normal) << i;
    const Color pa = a[i].power.color(), pb = b[i].power.color();
    // Within 2^-8 each: the fresh packing, the full one, and the rescaled one's repacking.
    const float tol = 3.0f * std::ldexp(maxComponent(pb), -8);
    ASSERT_NEAR(pa.r, pb.r, tol) << i;
    ASSERT_NEAR(pa.g, pb.g, tol) << i;
    ASSERT_NEAR(pa.b, pb.b, tol) << i;
  }
}

TEST(EmitPrefix, ClassicCutsEqualFreshEmissions) {
  Scene full = prefixScene();
  full.photons.shadowPhotons = 50000;
  full.photons.indirectPhotons = 40000;
  TraceScene tracer(full);
  EmitOptions options;
  options.batchSize = 1000;
  // 12345 ends inside batches; 3000 on batch bounds for light 0; 40000 is the full one.
  options.prefixBudgets = {12345, 3000, 40000};
  EmittedPhotons big = emitPhotons(full, tracer, sceneEmit(full, options));
  const PerMap<PrefixCuts>& cuts = big.cuts;
  for (uint64_t budget : {uint64_t(3000), uint64_t(12345)}) {
    Scene small = full;
    small.photons.shadowPhotons = budget;
    small.photons.indirectPhotons = budget;
    EmitOptions fresh;
    fresh.batchSize = 1000;
    EmittedPhotons expected = emitPhotons(small, tracer, sceneEmit(small, fresh));
    const PrefixCut* s = cuts[MapKind::Shadow].find(budget);
    const PrefixCut* in = cuts[MapKind::Indirect].find(budget);
    ASSERT_NE(s, nullptr);
    ASSERT_NE(in, nullptr);
    expectSameShadow(takePrefix(big.batches.get<MapKind::Shadow>(), *s), expected.batches.get<MapKind::Shadow>().flatten());
    expectSameIndirect(takePrefix(big.batches.get<MapKind::Indirect>(), *in), expected.batches.get<MapKind::Indirect>().flatten());
    EXPECT_GT(expected.batches.get<MapKind::Indirect>().size(), budget / 2) << "the test needs bouncing photons";
  }
  EXPECT_EQ(cuts[MapKind::Indirect].find(40000), nullptr) << "the full budget is not a cut";
}

TEST(EmitPrefix, PhysicalCutsEqualFreshEmissions) {
  Scene full = prefixScene();
  full.render.model = ShadingModel::Physical;
  full.photons.globalPhotons = 30000;
  full.photons.causticPhotons = 20000;
  TraceScene tracer(full);
  EmitOptions options;
  options.batchSize = 1000;
  options.prefixBudgets = {7777};
  EmittedPhotons big = emitPhysicalPhotons(full, tracer, 0, sceneEmit(full, options));
  Scene small = full;
  small.photons.globalPhotons = 7777;
  small.photons.causticPhotons = 7777;
  EmitOptions fresh;
  fresh.batchSize = 1000;
  EmittedPhotons expected = emitPhysicalPhotons(small, tracer, 0, sceneEmit(small, fresh));
  ASSERT_NE(big.cuts[MapKind::Global].find(7777), nullptr);
  ASSERT_NE(big.cuts[MapKind::Caustic].find(7777), nullptr);
  expectSameIndirect(takePrefix(big.batches.get<MapKind::Global>(), *big.cuts[MapKind::Global].find(7777)), expected.batches.get<MapKind::Global>().flatten());
  expectSameIndirect(takePrefix(big.batches.get<MapKind::Caustic>(), *big.cuts[MapKind::Caustic].find(7777)), expected.batches.get<MapKind::Caustic>().flatten());
  EXPECT_GT(expected.batches.get<MapKind::Caustic>().size(), 100u) << "the test needs caustic photons";
}

// A budget whose light split is not inside the full one's is refused, not cut wrongly.
TEST(EmitPrefix, BudgetsThatAreNotPrefixesHaveNoCut) {
  const std::vector<double> weights = {1.0, 1.0, 1.0};
  const std::vector<uint64_t> counts = splitByWeight(weights, 4);  // 2, 1, 1
  const std::vector<PhotonBatch> batches = makeBatches(counts, 8);
  PrefixCuts cuts(weights, counts, {2, 3}, batches);
  // 2 -> (1, 1, 0) and 3 -> (1, 1, 1): both inside (2, 1, 1).
  ASSERT_EQ(cuts.cuts().size(), 2u);
  const std::vector<uint64_t> skewed = {1, 2, 1};  // a full split that 3 -> (1,1,1) fits, 2 -> (1,1,0) too
  PrefixCuts other(weights, skewed, {2}, makeBatches(skewed, 8));
  EXPECT_EQ(other.cuts().size(), 1u);
  const std::vector<uint64_t> tiny = {0, 1, 1};  // 2 -> (1, 1, 0) asks light 0 for 1 > 0
  PrefixCuts none(weights, tiny, {2}, makeBatches(tiny, 8));
  EXPECT_TRUE(none.cuts().empty());
}

}  // namespace
}  // namespace penumbra
