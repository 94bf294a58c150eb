// The physical model against closed-form radiometry, light that needs no photons
// or one bounce of them: a point light over a Lambert plane (L = rho/pi I cos / d^2,
// E cos for a directional light), the furnace (a closed Lambert sphere with a point
// light at its centre: uniform irradiance E0 / (1 - rho)), and the estimator on a
// regular photon grid. Every tolerance is stated next to its assertion.
#include "support/physical_fixtures.h"
#include "support/emit_fixtures.h"

namespace penumbra {
namespace {

// ---------------------------------------------------------------------------
// a. Direct light on a plane.

TEST(PhysicalDirect, PointLightOverLambertPlaneIsRhoOverPiTimesICosOverD2) {
  // A 100 x 100 plane (rho 0.5) at y = 0, a point light of radiant intensity
  // I = colour x intensity at height 1.5. Camera rays from an oblique eye hit it
  // off-axis; L = rho/pi I cos(theta) / d^2 with no photon maps. Tolerance 1e-4
  // relative (tighter than the 0.5% asked): nothing is sampled, only float rounding.
  Scene scene = physicalScene();
  scene.materials.push_back(lambert("plane", Color(0.5f)));
  scene.meshes.push_back(makeQuad(Vec3(-50, 0, -50), Vec3(0, 0, 100), Vec3(100, 0, 0), 0));
  const Vec3 lightPos(0.0f, 1.5f, 0.0f);
  const Color colour(1.0f, 0.8f, 0.6f);
  const float intensity = 2.0f;
  scene.lights.push_back(point(lightPos, colour, intensity));
  Rig rig(scene);
  const Vec3 eye(-2.0f, 3.0f, 1.0f);
  for (Vec3 p : {Vec3(0.7f, 0.0f, -0.4f), Vec3(2.5f, 0.0f, 1.0f), Vec3(-1.0f, 0.0f, -3.0f),
                 Vec3(0.0f, 0.0f, 0.0f), Vec3(6.0f, 0.0f, 4.0f)}) {
    Color got = trace(rig, makeRay(eye, p - eye), kTermAll);
    const double d = glm::length(glm::dvec3(lightPos - p)), cosT = 1.5 / d;
    for (int c = 0; c < 3; ++c) {
      const double want = 0.5 / kPiD * colour[c] * intensity * cosT / (d * d);
      EXPECT_LT(rel(got[c], want), 1e-4) << "at (" << p.x << "," << p.z << ") ch " << c << ": " << got[c]
                                         << " vs " << want;
    }
  }
  // The direct view alone is the same number; the photon views are zero.
  Ray r = makeRay(eye, Vec3(0.7f, 0.0f, -0.4f) - eye);
  EXPECT_EQ(trace(rig, r, kTermDirect), trace(rig, r, kTermAll));
  EXPECT_EQ(trace(rig, r, kTermCaustic | kTermGlobal), Color(0.0f));
}

TEST(PhysicalDirect, DirectionalLightIsRhoOverPiTimesECos) {
  // Directional irradiance E (normal to the beam) on the plane: L = rho/pi E cos.
  // Tolerance 1e-4 relative (float rounding only).
  Scene scene = physicalScene();
  scene.materials.push_back(lambert("plane", Color(0.3f, 0.5f, 0.7f)));
  scene.meshes.push_back(makeQuad(Vec3(-50, 0, -50), Vec3(0, 0, 100), Vec3(100, 0, 0), 0));
  const Vec3 travel = glm::normalize(Vec3(0.4f, -1.0f, 0.3f));
  scene.lights.push_back(directional(travel, Color(1.0f), 3.0f));
  Rig rig(scene);
  const Vec3 eye(0.0f, 2.0f, 3.0f);
  Color got = trace(rig, makeRay(eye, Vec3(0.5f, 0.0f, -0.5f) - eye), kTermAll);
  const double cosT = -travel.y;
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(rel(got[c], scene.materials[0].diffuse[c] / kPiD * 3.0 * cosT), 1e-4) << c;
  }
}

// ---------------------------------------------------------------------------
// b. The furnace: a closed Lambert sphere around a point light.

class Furnace : public ::testing::TestWithParam<float> {};

TEST_P(Furnace, GlobalMapGivesTheInterreflectionOfAClosedSphere) {
  // Sphere of radius R = 1.5 (analytic; hit from inside, its normal faces the ray),
  // Lambert rho, a point light of radiant intensity I at the centre. Direct
  // irradiance E0 = I / R^2 everywhere. Interreflection in a sphere is uniform
  // (every point sees every other with the same form factor dA / (4 pi R^2)), so
  // the power stored after >= 1 diffuse bounce is Phi rho / (1 - rho), Phi = 4 pi I,
  // and the global radiance is rho/pi E0 rho / (1 - rho). The chord-distance disc on
  // a sphere has area exactly pi r^2 (Archimedes), so the kNN estimate has no
  // curvature bias.
  const float rho = GetParam();
  const float R = 1.5f;
  const Vec3 centre(0.2f, -0.1f, 0.3f);
  const Color colour(1.0f, 0.7f, 0.4f);
  const float intensity = 2.0f;
  Scene scene = physicalScene();
  scene.materials.push_back(lambert("wall", Color(rho)));
  scene.spheres.push_back(Sphere{centre, R, 0});
  scene.lights.push_back(point(centre, colour, intensity));
  scene.photons.globalPhotons = 500000;
  scene.photons.maxBounces = 64;  // rho^64 < 2e-9: the cap loses nothing measurable
  Rig rig(scene);

  EmittedPhotons photons = emitPhysicalPhotons(scene, rig.tracer, 0, sceneEmit(scene));
  const glm::dvec3 phi = 4.0 * kPiD * glm::dvec3(colour) * double(intensity);
  const double gain = rho / (1.0 - rho);
  EXPECT_EQ(photons.emitted[MapKind::Global], 500000u);
  EXPECT_TRUE(photons.batches.get<MapKind::Caustic>().empty());  // nothing specular to aim at
  const PhotonTally& t = photons.tally[MapKind::Global];
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(t.emitted[c], phi[c], 1e-4 * phi[c]);  // float shares summed in double
    EXPECT_EQ(t.escaped[c], 0.0);                      // closed: nothing leaves
    // Stored power per emitted photon is geometric: mean rho/(1-rho), variance
    // rho/(1-rho)^2, so the relative standard error is 1/sqrt(rho N) <= 0.2%;
    // tolerance 1% (>= 5 sigma).
    EXPECT_LT(rel(t.stored[MapKind::Global][c], phi[c] * gain), 0.01) << "channel " << c;
    // Bookkeeping: every watt emitted is absorbed or capped (exact up to double rounding).
    EXPECT_NEAR(t.absorbed[c] + t.capped[c] + t.escaped[c], t.emitted[c], 1e-9 * t.emitted[c]);
  }

  IndirectPhotonMap map;
  map.build(std::move(photons.batches.get<MapKind::Global>()));
  rig.ctx.maps.get<MapKind::Global>() = &map;
  // Camera rays from the centre in uniformly random directions land on points
  // uniformly spread over the wall; the global view there is rho/pi E0 rho/(1-rho),
  // the direct view rho/pi E0 (normal incidence everywhere).
  const int points = 4000;
  Rng rng(5);
  glm::dvec3 sumGlobal(0.0);
  for (int i = 0; i < points; ++i) {
    Vec3 dir = uniformSphere(rng.uniform(), rng.uniform());
    Ray ray = makeRay(centre + 0.01f * Vec3(1, 1, 1), dir);
    sumGlobal += glm::dvec3(trace(rig, ray, kTermGlobal));
    if (i < 200) {
      Color direct = trace(rig, ray, kTermDirect);
      // The direct term is exact; 1e-3 relative covers the ray origin being 0.017
      // off-centre (cos and d^2 change by < 1e-4) and float rounding.
      Vec3 p = centre + 0.01f * Vec3(1, 1, 1);
      Hit hit;
      ASSERT_TRUE(rig.tracer.intersect(ray, hit));
      Vec3 x = p + hit.t * ray.dir;
      const double d = glm::length(glm::dvec3(x - centre));
      for (int c = 0; c < 3; ++c) {
        const double want = rho / kPiD * colour[c] * intensity / (d * d);
        ASSERT_LT(rel(direct[c], want), 1e-3) << i << " ch " << c;
      }
    }
  }
  glm::dvec3 mean = sumGlobal / double(points);
  for (int c = 0; c < 3; ++c) {
    const double e0 = colour[c] * intensity / double(R * R);
    const double want = rho / kPiD * e0 * gain;
    // The kNN Epanechnikov estimate (k = 100) is unbiased on a uniform density;
    // per point it scatters ~12%, so 4000 points average to ~0.2%, plus the ~0.2%
    // of the photon total. Tolerance 1% as asked (>= 3.5 sigma).
    EXPECT_LT(rel(mean[c], want), 0.01) << "rho " << rho << " channel " << c << ": " << mean[c]
                                        << " vs " << want;
  }
}

// Named rho_0_50 and rho_0_73: ctest lists the generated name (NO_PRETTY_VALUES).
INSTANTIATE_TEST_SUITE_P(Albedo, Furnace, ::testing::Values(0.5f, 0.73f),
                         [](const ::testing::TestParamInfo<float>& tp) {
                           return "rho_0_" + std::to_string(int(std::lround(tp.param * 100.0f)));
                         });

// ---------------------------------------------------------------------------
// The estimator itself on a synthetic map.

TEST(PhotonEstimate, UniformPhotonsOnAPlaneGiveFTimesTheIrradiance) {
  // Photons of power Phi on a regular grid of spacing h in the plane z = 0, all
  // arriving from one direction wi: irradiance E = Phi / h^2, and the estimate must be
  // f(wo, wi) E, for a Lambert BSDF (the one-multiply fast path) and for Lambert +
  // normalised Phong (the per-photon BSDF path), with a fixed radius and with kNN.
  // Tolerance 1%: the Epanechnikov kernel summed over a grid 20+ spacings wide
  // differs from its integral by < 0.1%; kNN (k = 400) by < 1% (the k-th ring).
  const float h = 0.01f, phi = 0.003f;
  const Vec3 n(0.0f, 0.0f, 1.0f);
  const Vec3 wi = glm::normalize(Vec3(0.3f, -0.2f, 0.9f));  // towards where light came from
  PhotonArray<IndirectPhoton> photons;
  for (int i = -100; i <= 100; ++i) {
    for (int j = -100; j <= 100; ++j) {
      photons.push_back({Vec3(i * h, j * h, 0.0f), Color(phi, 2 * phi, 3 * phi), encodeOctahedral(-wi),
                         encodeOctahedral(n)});
    }
  }
  IndirectPhotonMap map;
  map.build(photons);
  GatherScratch scratch;
  const BsdfFrame frame{n, n, true};
  const Vec3 wo = glm::normalize(Vec3(-0.4f, 0.1f, 0.8f));
  const Vec3 q(0.0013f, -0.0021f, 0.0f);
  for (bool glossy : {false, true}) {
    Material m = lambert("m", Color(0.5f, 0.4f, 0.3f));
    if (glossy) {
      m.specular = Color(0.3f);
      m.shininess = 10.0f;
    }
    Bsdf b = makeBsdf(m, BsdfFamily::Radiometric, HemisphereSampling::Cosine);
    const Color f = evaluateBsdf(b, frame, wo, wi) / glm::dot(n, wi);
    for (PhotonGather gather : {PhotonGather{0, 0.2f}, PhotonGather{400, 0.0f}}) {
      const float radius = gather.maxRadius;
      RadianceEstimate e = photonRadiance(map, b, frame, q, wo, gather, scratch);
      for (int c = 0; c < 3; ++c) {
        const double want = f[c] * (c + 1) * phi / (h * h);
        EXPECT_LT(rel(e.value[c], want), 0.01) << (glossy ? "glossy" : "lambert") << " r=" << radius
                                               << " ch " << c << ": " << e.value[c] << " vs " << want;
      }
    }
  }
  // Photons whose stored normal faces away (the back of a thin wall) do not count.
  PhotonArray<IndirectPhoton> back = photons;
  for (IndirectPhoton& p : back) p.normal = encodeOctahedral(-n);
  IndirectPhotonMap backMap;
  backMap.build(back);
  Bsdf b = makeBsdf(lambert("m", Color(0.5f)), BsdfFamily::Radiometric, HemisphereSampling::Cosine);
  EXPECT_EQ(photonRadiance(backMap, b, frame, q, wo, PhotonGather{0, 0.2f}, scratch).value, Color(0.0f));
}

}  // namespace
}  // namespace penumbra
