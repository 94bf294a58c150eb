// Alpha cut-outs through the geometry's Embree filter: a checkerboard-masked quad
// over a floor casts a checkerboard shadow (direct light and photons), camera rays
// see the floor through its holes (single rays and packets alike), a blended quad
// lets through 1 - alpha of the light, the same rays on every run, and a mask cuts
// by its mesh's vertex alpha too.
#include "support/physical_fixtures.h"

namespace penumbra {
namespace {

constexpr int kSquares = 4;       // the mask is 4 x 4 texels, one per square
constexpr float kMaskY = 1.0f;    // the masked quad lies in y = 1, x and z in [-1, 1]
const Vec3 kLight(0.1f, 3.0f, -0.2f);
constexpr float kIntensity = 5.0f;
constexpr float kRho = 0.6f;

// Square (i, j) covers u in [i, i+1]/4 and v in [j, j+1]/4: x = -1 + 2u, z = -1 + 2v.
bool opaque(int i, int j) { return (i + j) % 2 == 0; }
Vec3 squareCentre(int i, int j) {
  return Vec3(-1.0f + 0.5f * (float(i) + 0.5f), kMaskY, -1.0f + 0.5f * (float(j) + 0.5f));
}
// Where the light's ray through point c on the mask meets the floor (y = 0).
Vec3 onFloor(const Vec3& c) { return kLight + (c - kLight) * (kLight.y / (kLight.y - kMaskY)); }

Scene maskedScene(AlphaMode mode, bool checker, float alpha = 1.0f) {
  Scene scene = physicalScene();
  scene.materials.push_back(lambert("floor", Color(kRho)));
  Material cut = lambert("cut", Color(0.0f));
  cut.alphaMode = mode;
  cut.alpha = alpha;
  if (checker) {
    AlphaMask mask;
    mask.source = "checker";
    mask.width = mask.height = kSquares;
    for (int j = 0; j < kSquares; ++j) {
      for (int i = 0; i < kSquares; ++i) mask.alpha.push_back(opaque(i, j) ? 255 : 0);
    }
    scene.alphaMasks.push_back(mask);
    cut.alphaMask = 0;
  }
  scene.materials.push_back(cut);
  scene.meshes.push_back(makeQuad(Vec3(-20, 0, -20), Vec3(0, 0, 40), Vec3(40, 0, 0), 0));
  scene.meshes.push_back(makeQuad(Vec3(-1, kMaskY, -1), Vec3(2, 0, 0), Vec3(0, 0, 2), 1));
  scene.lights.push_back(point(kLight, Color(1.0f), kIntensity));
  return scene;
}

// I cos / d^2 x rho / pi at floor point p.
double closedForm(const Vec3& p) {
  const glm::dvec3 d = glm::dvec3(kLight - p);
  const double d2 = glm::dot(d, d);
  return kIntensity * (d.y / std::sqrt(d2)) / d2 * kRho / kPiD;
}

// A camera ray at floor point p from the side, below the mask (it never crosses y = 1).
Ray sideRay(const Vec3& p) { return makeRay(Vec3(p.x + 0.5f, 0.6f, p.z + 3.0f), p - Vec3(p.x + 0.5f, 0.6f, p.z + 3.0f)); }

TEST(AlphaMask, CheckerboardShadowOnTheFloorIsExact) {
  // Under a cut-out square the floor gets the closed form (1e-4 relative, float
  // against double); under an opaque one nothing (exactly 0).
  const Scene scene = maskedScene(AlphaMode::Mask, true);
  Rig rig(scene);
  for (int j = 0; j < kSquares; ++j) {
    for (int i = 0; i < kSquares; ++i) {
      const Vec3 p = onFloor(squareCentre(i, j));
      const double got = trace(rig, sideRay(p), kTermDirect).g;
      if (opaque(i, j)) {
        EXPECT_EQ(got, 0.0) << "square " << i << "," << j;
      } else {
        EXPECT_LT(rel(got, closedForm(p)), 1e-4) << "square " << i << "," << j << ": " << got;
      }
    }
  }
}

TEST(AlphaMask, CameraRaysSeeTheFloorThroughTheHolesInPacketsToo) {
  // Straight down through each square centre: the mask's hit (t = 4) on an opaque
  // square, the floor's (t = 5) on a cut-out one; packets give the same hits.
  const Scene scene = maskedScene(AlphaMode::Mask, true);
  TraceScene tracer(scene);
  std::vector<Ray> rays;
  for (int j = 0; j < kSquares; ++j) {
    for (int i = 0; i < kSquares; ++i) {
      const Vec3 c = squareCentre(i, j);
      rays.push_back(makeRay(Vec3(c.x, 5.0f, c.z), Vec3(0, -1, 0)));
    }
  }
  std::vector<Hit> packet(rays.size());
  tracer.intersectPacket(rays.data(), static_cast<int>(rays.size()), packet.data());
  // Occlusion up to between the mask and the floor: only the opaque squares block.
  std::vector<Ray> shortRays = rays;
  for (Ray& r : shortRays) r.tMax = 4.5f;
  std::vector<uint8_t> blocked(rays.size());
  tracer.occludedPacket(shortRays.data(), static_cast<int>(rays.size()), blocked.data());
  for (size_t k = 0; k < rays.size(); ++k) {
    const int i = int(k) % kSquares, j = int(k) / kSquares;
    Hit hit;
    ASSERT_TRUE(tracer.intersect(rays[k], hit));
    EXPECT_EQ(tracer.materialOf(hit), opaque(i, j) ? 1 : 0) << "square " << i << "," << j;
    EXPECT_NEAR(hit.t, opaque(i, j) ? 4.0f : 5.0f, 1e-5f);
    EXPECT_EQ(packet[k].t, hit.t);
    EXPECT_EQ(packet[k].primId, hit.primId);
    EXPECT_EQ(tracer.occluded(shortRays[k]), opaque(i, j));
    EXPECT_EQ(blocked[k] != 0, opaque(i, j));
  }
}

// The solid angle of the rectangle [x1, x2] x [z1, z2] at height h below a point.
double rectangleSolidAngle(double x1, double x2, double z1, double z2, double h) {
  auto f = [h](double x, double z) { return std::atan(x * z / (h * std::sqrt(x * x + z * z + h * h))); };
  return f(x2, z2) - f(x1, z2) - f(x2, z1) + f(x1, z1);
}

TEST(AlphaMask, ShadowPhotonsReachTheFloorOnlyThroughTheHoles) {
  // The classic shadow pass's direct photons on the floor, counted in the inner 80%
  // of each square's shadow: none under an opaque square (its photons are stored as
  // shadow photons there), and under a hole the light's share of photons through
  // that solid angle, within 4 binomial standard deviations.
  Scene scene = maskedScene(AlphaMode::Mask, true);
  scene.render.model = ShadingModel::Classic;
  const uint64_t n = 400000;
  scene.photons.shadowPhotons = n;
  scene.photons.gateMode = GateMode::On;
  TraceScene tracer(scene);
  EmitOptions options;
  options.budgets[MapKind::Shadow] = n;
  const EmittedPhotons maps = emitPhotons(scene, tracer, options);
  const double shrink = 0.1 * 0.5;  // 10% of a square's side off each edge
  for (int j = 0; j < kSquares; ++j) {
    for (int i = 0; i < kSquares; ++i) {
      const Vec3 c = squareCentre(i, j);
      const double x1 = c.x - 0.25 + shrink, x2 = c.x + 0.25 - shrink, z1 = c.z - 0.25 + shrink, z2 = c.z + 0.25 - shrink;
      const Vec3 lo = onFloor(Vec3(x1, kMaskY, z1)), hi = onFloor(Vec3(x2, kMaskY, z2));
      uint64_t direct = 0, shadow = 0;
      for (const ShadowPhoton& p : maps.batches.get<MapKind::Shadow>()) {
        if (p.position.y > 1e-4f || p.position.x < lo.x || p.position.x > hi.x || p.position.z < lo.z || p.position.z > hi.z) continue;
        (p.shadow == kDirect ? direct : shadow) += 1;
      }
      if (opaque(i, j)) {
        EXPECT_EQ(direct, 0u) << "square " << i << "," << j;
        EXPECT_GT(shadow, 0u) << "square " << i << "," << j;
      } else {
        const double h = kLight.y - kMaskY;
        const double f = rectangleSolidAngle(x1 - kLight.x, x2 - kLight.x, z1 - kLight.z, z2 - kLight.z, h) / (4.0 * kPiD);
        const double mean = double(n) * f, sd = std::sqrt(double(n) * f * (1.0 - f));
        EXPECT_LT(std::abs(double(direct) - mean), 4.0 * sd) << "square " << i << "," << j << ": " << direct << " vs " << mean;
        EXPECT_EQ(shadow, 0u);
      }
    }
  }
}

TEST(AlphaMask, BlendLetsThroughOneMinusAlphaTheSameRaysEveryTime) {
  // A uniform quad of alpha 0.3 in blend mode: over 4000 floor points under it, the
  // direct light averages 0.7 of the closed form within 4 binomial standard
  // deviations, and tracing the same rays again gives the same answers bit for bit.
  const Scene scene = maskedScene(AlphaMode::Blend, false, 0.3f);
  Rig rig(scene);
  Rng rng(7);
  const int count = 4000;
  double sum = 0.0;
  std::vector<float> first;
  for (int k = 0; k < count; ++k) {
    const Vec3 c(-0.9f + 1.8f * rng.uniform(), kMaskY, -0.9f + 1.8f * rng.uniform());
    const Vec3 p = onFloor(c);
    const float got = trace(rig, sideRay(p), kTermDirect).g;
    first.push_back(got);
    sum += got / closedForm(p);
  }
  const double sd = std::sqrt(0.7 * 0.3 / count);
  EXPECT_NEAR(sum / count, 0.7, 4.0 * sd);
  Rng again(7);
  for (int k = 0; k < count; ++k) {
    const Vec3 c(-0.9f + 1.8f * again.uniform(), kMaskY, -0.9f + 1.8f * again.uniform());
    ASSERT_EQ(trace(rig, sideRay(onFloor(c)), kTermDirect).g, first[k]) << k;
  }
}

TEST(AlphaMask, MaskWithoutTextureCutsByTheFactorAlone) {
  // alpha 0.4 under cutoff 0.5: the whole quad is cut out; 0.6: the whole quad stays.
  for (float alpha : {0.4f, 0.6f}) {
    const Scene scene = maskedScene(AlphaMode::Mask, false, alpha);
    TraceScene tracer(scene);
    Hit hit;
    ASSERT_TRUE(tracer.intersect(makeRay(Vec3(0.3f, 5.0f, 0.2f), Vec3(0, -1, 0)), hit));
    EXPECT_EQ(tracer.materialOf(hit), alpha < 0.5f ? 0 : 1) << alpha;
  }
}

// The untextured mask quad with vertex alpha `alphaAt(x)` at its corners (white RGB).
template <class Alpha>
Scene vertexAlphaScene(Alpha alphaAt) {
  Scene scene = maskedScene(AlphaMode::Mask, false);
  TriangleMesh& quad = scene.meshes[1];
  for (const Vec3& p : quad.positions) quad.colors.emplace_back(1.0f, 1.0f, 1.0f, alphaAt(p.x));
  return scene;
}

TEST(AlphaMask, VertexAlphaZeroLetsCameraAndShadowRaysThrough) {
  // Alpha 0 at every corner: a ray straight down meets the floor (t = 5), and the
  // light reaches the floor under the quad in full (1e-4 relative).
  const Scene scene = vertexAlphaScene([](float) { return 0.0f; });
  Rig rig(scene);
  Hit hit;
  ASSERT_TRUE(rig.tracer.intersect(makeRay(Vec3(0.2f, 5.0f, 0.3f), Vec3(0, -1, 0)), hit));
  EXPECT_EQ(rig.tracer.materialOf(hit), 0);
  EXPECT_NEAR(hit.t, 5.0f, 1e-5f);
  const Vec3 p = onFloor(Vec3(0.2f, kMaskY, 0.3f));
  EXPECT_LT(rel(trace(rig, sideRay(p), kTermDirect).g, closedForm(p)), 1e-4);
}

TEST(AlphaMask, VertexAlphaRampCutsWhereItFallsBelowTheCutoff) {
  // Alpha (x + 1) / 2 across the quad: cut out for x < 0, kept for x > 0. Straight-
  // down rays (single and in a packet) meet the floor or the quad on either side,
  // occlusion agrees, and the floor is lit under the cut half only (exactly 0 under
  // the kept one; the closed form within 1e-4 relative under the cut one).
  const Scene scene = vertexAlphaScene([](float x) { return 0.5f * (x + 1.0f); });
  Rig rig(scene);
  std::vector<Ray> rays, shortRays;
  for (float x : {-0.8f, -0.3f, -0.05f, 0.05f, 0.3f, 0.8f}) {
    for (float z : {-0.7f, 0.1f, 0.6f}) {
      rays.push_back(makeRay(Vec3(x, 5.0f, z), Vec3(0, -1, 0)));
      shortRays.push_back(rays.back());
      shortRays.back().tMax = 4.5f;
    }
  }
  std::vector<Hit> packet(rays.size());
  rig.tracer.intersectPacket(rays.data(), int(rays.size()), packet.data());
  std::vector<uint8_t> blocked(rays.size());
  rig.tracer.occludedPacket(shortRays.data(), int(rays.size()), blocked.data());
  for (size_t k = 0; k < rays.size(); ++k) {
    const bool kept = rays[k].origin.x > 0.0f;
    Hit hit;
    ASSERT_TRUE(rig.tracer.intersect(rays[k], hit));
    EXPECT_NEAR(hit.t, kept ? 4.0f : 5.0f, 1e-5f) << k;
    EXPECT_EQ(packet[k].t, hit.t) << k;
    EXPECT_EQ(rig.tracer.occluded(shortRays[k]), kept) << k;
    EXPECT_EQ(blocked[k] != 0, kept) << k;
    const Vec3 p = onFloor(Vec3(rays[k].origin.x, kMaskY, rays[k].origin.z));
    const double got = trace(rig, sideRay(p), kTermDirect).g;
    if (kept) {
      EXPECT_EQ(got, 0.0) << k;
    } else {
      EXPECT_LT(rel(got, closedForm(p)), 1e-4) << k;
    }
  }
}

}  // namespace
}  // namespace penumbra
