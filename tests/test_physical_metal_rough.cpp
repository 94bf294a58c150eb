// glTF's metallic-roughness material through the physical integrator, against
// closed forms written here in double: direct light from a point light (GGX
// D G2 F / (4 cos cos) plus the Fresnel-weighted base), the mirror limit
// (Schlick's Fresnel times what the reflection sees), a narrow lobe traced by
// sampled rays under a uniform sky (its directional albedo), the white furnace in
// a constant environment, and the JSON keys.
#include "core/bsdf.h"
#include "core/lights/environment_map.h"
#include "core/error.h"
#include "io/scene_loader.h"
#include "support/bsdf_sampling.h"
#include "support/physical_fixtures.h"

namespace penumbra {
namespace {

// The material as glTF gives it; `roughness` perceptual (alpha = roughness^2).
Material metalRoughMaterial(const Color& base, float metallic, float roughness) {
  Material m = lambert("metal_rough", base);
  m.metalRough = true;
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

double schlick(double f0, double c) { return f0 + (1.0 - f0) * std::pow(1.0 - c, 5.0); }

// f cos for normal n = +y, written out from the GGX formulas (Walter 2007; Heitz 2014).
double expectedFCos(double base, double metallic, double alpha, const glm::dvec3& wo, const glm::dvec3& wi) {
  const double cosO = wo.y, cosI = wi.y;
  const glm::dvec3 h = glm::normalize(wo + wi);
  const double a2 = alpha * alpha, ch = h.y;
  const double d = a2 / (kPiD * std::pow(ch * ch * (a2 - 1.0) + 1.0, 2.0));
  auto lambda = [&](double c) { return 0.5 * (std::sqrt(1.0 + a2 * (1.0 - c * c) / (c * c)) - 1.0); };
  const double g2 = 1.0 / (1.0 + lambda(cosO) + lambda(cosI));
  const double voh = glm::dot(wo, h);
  const double fresnel = metallic * schlick(base, voh) + (1.0 - metallic) * schlick(0.04, voh);
  const double specular = fresnel * d * g2 / (4.0 * cosO * cosI);
  const double diffuse = (1.0 - metallic) * (1.0 - schlick(0.04, cosO)) * base / kPiD;
  return (specular + diffuse) * cosI;
}

Scene planeScene(const Material& m) {
  Scene scene = physicalScene();
  scene.materials.push_back(m);
  scene.meshes.push_back(makeQuad(Vec3(-50, 0, -50), Vec3(0, 0, 100), Vec3(100, 0, 0), 0));
  return scene;
}

TEST(PhysicalMetalRough, PointLightOverAPlaneIsTheGgxBsdfTimesIOverD2) {
  // Half metal, alpha 0.36 (a gathered lobe, not narrow), no photons: the pixel is
  // f cos I / d^2. Tolerance 2e-4 relative: float GGX against the double formula.
  const Color base(0.9f, 0.6f, 0.3f);
  Scene scene = planeScene(metalRoughMaterial(base, 0.5f, 0.6f));
  const Vec3 lightPos(0.5f, 2.0f, -0.5f);
  scene.lights.push_back(point(lightPos, Color(1.0f), 3.0f));
  Rig rig(scene);
  const Vec3 eye(-2.0f, 3.0f, 1.0f);
  for (Vec3 p : {Vec3(0.7f, 0.0f, -0.4f), Vec3(1.5f, 0.0f, -1.5f), Vec3(-1.0f, 0.0f, -3.0f), Vec3(0.2f, 0.0f, 0.3f)}) {
    const Color got = trace(rig, makeRay(eye, p - eye), kTermAll);
    const glm::dvec3 wo = glm::normalize(glm::dvec3(eye - p)), toLight = glm::dvec3(lightPos - p);
    const double d2 = glm::dot(toLight, toLight);
    for (int c = 0; c < 3; ++c) {
      const double want = expectedFCos(base[c], 0.5, 0.36, wo, glm::normalize(toLight)) * 3.0 / d2;
      EXPECT_LT(rel(got[c], want), 2e-4) << "at (" << p.x << "," << p.z << ") ch " << c << ": " << got[c] << " vs " << want;
    }
  }
}

TEST(PhysicalMetalRough, RoughnessZeroIsAMirrorWeightedBySchlicksFresnel) {
  // No light: a smooth metal shows the background times F(base, cos); a smooth
  // dielectric F(0.04, cos), its base receiving nothing. Tolerance 1e-5 absolute.
  const Color sky(0.5f, 0.7f, 1.0f);
  const Vec3 eye(0.0f, 1.0f, 2.0f), p(0.0f, 0.0f, 0.0f);
  const double cosO = glm::normalize(glm::dvec3(eye - p)).y;
  for (float metallic : {1.0f, 0.0f}) {
    const Color base(0.9f, 0.6f, 0.3f);
    Scene scene = planeScene(metalRoughMaterial(base, metallic, 0.0f));
    scene.render.background = sky;
    Rig rig(scene);
    const Color got = trace(rig, makeRay(eye, p - eye), kTermAll);
    for (int c = 0; c < 3; ++c) {
      const double f = metallic > 0.0f ? schlick(base[c], cosO) : schlick(0.04, cosO);
      EXPECT_NEAR(got[c], f * sky[c], 1e-5) << "metallic " << metallic << " ch " << c;
    }
  }
}

TEST(PhysicalMetalRough, ANarrowLobeUnderAUniformSkyReturnsItsDirectionalAlbedo) {
  // A white conductor at alpha 0.04 is traced by one sampled ray per hit. Under a
  // sky of radiance 1 the mean over camera samples is the lobe's albedo, here the
  // integral of f cos over the hemisphere (stratified, independent of the sampler),
  // never above 1 (a furnace). Tolerance: 4 standard errors of the mean plus 1e-3
  // for the reference quadrature.
  Scene scene = planeScene(metalRoughMaterial(Color(1.0f), 1.0f, 0.2f));
  scene.render.background = Color(1.0f);
  Rig rig(scene);
  const Vec3 eye(0.0f, 1.0f, 1.5f), p(0.0f);
  const Ray ray = makeRay(eye, p - eye);
  const int n = 20000;
  double sum = 0.0, sum2 = 0.0;
  ThreadState ts;
  for (int i = 0; i < n; ++i) {
    beginSample(ts, static_cast<uint64_t>(i));
    ts.raysLeft = kMaxRaysPerSample;
    const double v = tracePhysical(rig.ctx, ray, 0, Color(1.0f), RayKind::Camera, kTermAll, -1, ts).g;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n, err = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
  const Bsdf b = makeBsdf(scene.materials[0], BsdfFamily::Radiometric, HemisphereSampling::Cosine);
  const Vec3 wo = glm::normalize(eye - p);
  const double albedo = hemisphereIntegral(b, frameOf(Vec3(0, 1, 0)), wo, 800, 7).y;
  EXPECT_NEAR(mean, albedo, 4.0 * err + 1e-3) << "standard error " << err;
  EXPECT_LE(mean, 1.0 + 4.0 * err);
  EXPECT_GT(albedo, 0.9);  // a nearly smooth conductor loses little at this angle
}

TEST(PhysicalMetalRough, AWhiteFurnaceReturnsAtMostWhatArrivesAndARoughMetalLosesWhatGgxLoses) {
  // A unit sphere of base colour 1 in a constant sky of radiance 1, no photons: a
  // camera sample at a point returns the directional albedo there (a convex sphere
  // sees only sky), by light and BSDF samples weighted by the power heuristic (and
  // for a narrow lobe, light samples alone). At every metallic and roughness the mean
  // stays at most 1 (4 standard errors); for a rough conductor with F0 = 1 it matches
  // the single-scattering albedo 1 - loss, integrated here from the BSDF by
  // quadrature, within 2%.
  const Vec3 eye(0.0f, 0.6f, 3.0f);
  const Vec3 p = glm::normalize(Vec3(0.5f, 0.4f, 0.7f));
  const Ray ray = makeRay(eye, p - eye);
  const Vec3 wo = glm::normalize(eye - p);
  for (float metallic : {0.0f, 0.5f, 1.0f}) {
    for (float roughness : {0.0f, 0.1f, 0.25f, 0.5f, 1.0f}) {
      Scene scene = physicalScene();
      scene.render.lightSamples = 4;
      scene.materials.push_back(metalRoughMaterial(Color(1.0f), metallic, roughness));
      scene.spheres.push_back({Vec3(0.0f), 1.0f, 0});
      scene.lights.push_back(makeEnvironmentLight(Color(1.0f), 1.0f, nullptr));
      Rig rig(scene);
      const int n = 4000;
      double sum = 0.0, sum2 = 0.0;
      ThreadState ts;
      for (int i = 0; i < n; ++i) {
        beginSample(ts, hashKey(11, static_cast<uint64_t>(i)));
        ts.raysLeft = kMaxRaysPerSample;
        const double v = tracePhysical(rig.ctx, ray, 0, Color(1.0f), RayKind::Camera, kTermAll, -1, ts).g;
        sum += v;
        sum2 += v * v;
      }
      const double mean = sum / n, err = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
      const std::string what = "metallic " + std::to_string(metallic) + " roughness " + std::to_string(roughness);
      EXPECT_LE(mean, 1.0 + 4.0 * err) << what;
      if (metallic == 1.0f && roughness >= 0.5f) {
        const Bsdf b = makeBsdf(scene.materials[0], BsdfFamily::Radiometric, HemisphereSampling::Cosine);
        const double albedo = hemisphereIntegral(b, frameOf(p), wo, 1000, 3).y;
        std::printf("%s: furnace %.4f, single-scattering albedo %.4f (loss %.1f%%)\n", what.c_str(), mean, albedo,
                    100.0 * (1.0 - albedo));
        EXPECT_LT(rel(mean, albedo), 0.02) << what << ": " << mean << " vs " << albedo;
      }
    }
  }
}

TEST(PhysicalMetalRough, JsonKeysSelectTheMaterialAndRefuseAPhongTermBeside) {
  const Scene s = parseScene(R"({"render": {"model": "physical"}, "materials": {
      "gold": {"diffuse": [1, 0.78, 0.34], "metallic": 1, "roughness": 0.3},
      "plastic": {"diffuse": [0.2, 0.4, 0.8], "roughness": 0.5}}})",
                             "x.json");
  std::map<std::string, Material> m;
  for (const Material& mat : s.materials) m[mat.name] = mat;
  EXPECT_TRUE(m["gold"].metalRough);
  EXPECT_EQ(m["gold"].metallic, 1.0f);
  EXPECT_FLOAT_EQ(m["gold"].roughness, 0.3f);
  EXPECT_EQ(m["plastic"].metallic, 0.0f);  // glTF's default is 1; a JSON material's 0
  const Bsdf gold = makeBsdf(m["gold"], BsdfFamily::Radiometric, HemisphereSampling::Cosine);
  EXPECT_EQ(gold.type, BsdfType::MetalRough);
  EXPECT_FLOAT_EQ(gold.roughness, 0.09f);
  // The classic model: no mirror for a rough metal, the metal's colour as highlight.
  const Bsdf classic = makeBsdf(m["gold"], BsdfFamily::Phong, HemisphereSampling::Uniform);
  EXPECT_LT(classic.kr, 0.25f);
  EXPECT_FLOAT_EQ(classic.specular.g, 0.78f);
  EXPECT_EQ(classic.diffuse, Color(0.0f));
  try {
    parseScene(R"({"materials": {"m": {"metallic": 1, "reflective": {"kr": 1}}}})", "x.json");
    FAIL() << "a mirror weight beside metallic must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("materials.m.reflective"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace penumbra
