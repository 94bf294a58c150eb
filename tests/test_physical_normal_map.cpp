// Tangent-space normal maps: a flat quad whose constant map encodes a tilt shades
// like the quad tilted by that angle, in both shading models and with a glossy
// BSDF; tangents computed from uvs point along +u with the bitangent up the image.
#include "io/mesh_tangents.h"
#include "support/physical_fixtures.h"
#include "support/scratch_dir.h"
#include "trace/texture_lookup.h"
#include <OpenImageIO/imageio.h>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

constexpr float kTilt = 20.0f * kPi / 180.0f;

// A constant 4x4 normal map in 32-bit float EXR: an 8-bit map would round the
// encoded normal by up to 1/255, far above the 1e-3 the comparison asks.
std::string writeNormalMap(const fs::path& file, const Vec3& tangentSpaceNormal) {
  const Vec3 texel = 0.5f * (tangentSpaceNormal + Vec3(1.0f));
  std::vector<float> pixels;
  for (int i = 0; i < 16; ++i) pixels.insert(pixels.end(), {texel.x, texel.y, texel.z});
  auto out = OIIO::ImageOutput::create(file.string());
  EXPECT_TRUE(out);
  OIIO::ImageSpec spec(4, 4, 3, OIIO::TypeDesc::FLOAT);
  EXPECT_TRUE(out->open(file.string(), spec));
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
  out->close();
  return file.string();
}

// A 4 x 4 quad through the origin: in z = 0 facing +z when flat, else turned about x
// by `tilt` so its normal is (0, sin tilt, cos tilt). Its uvs run u along +x and v
// along the second edge, so the image's up (-v) is -y on the flat quad.
TriangleMesh quad(float tilt, int material) {
  const Vec3 e1(4.0f, 0.0f, 0.0f), e2 = 4.0f * Vec3(0.0f, std::cos(tilt), -std::sin(tilt));
  return makeQuad(-0.5f * (e1 + e2), e1, e2, material);
}

struct Pair {
  Color flatMapped, tilted;
};

// The same rays at the origin of the normal-mapped flat quad and of the tilted one.
std::vector<Pair> shadeBoth(Material m, ShadingModel model, const std::string& map) {
  std::vector<Pair> out;
  const TextureLookup textures({map}, {true});
  Scene scenes[2];
  for (int k = 0; k < 2; ++k) {
    Scene& scene = scenes[k];
    scene = physicalScene();
    scene.render.model = model;
    scene.textures = {Texture{map, true, std::nullopt}};
    Material mk = m;
    mk.normalTexture = k == 0 ? 0 : -1;
    scene.materials.push_back(mk);
    scene.meshes.push_back(quad(k == 0 ? 0.0f : kTilt, 0));
    if (k == 0) computeTangents(scene.meshes[0]);
    scene.lights.push_back(directional(Vec3(-0.3f, -0.8f, -1.0f), Color(1.0f, 0.9f, 0.8f), 2.0f));
  }
  Rig flat(scenes[0]), tilted(scenes[1]);
  flat.ctx.textures = tilted.ctx.textures = &textures;
  for (const Vec3& eye : {Vec3(0.3f, -0.4f, 5.0f), Vec3(-2.0f, 1.0f, 4.0f), Vec3(1.5f, 2.5f, 3.0f)}) {
    const Ray ray = makeRay(eye, -eye);
    Pair p;
    if (model == ShadingModel::Physical) {
      p.flatMapped = trace(flat, ray, kTermAll);
      p.tilted = trace(tilted, ray, kTermAll);
    } else {
      p.flatMapped = flat.shade(ray);
      p.tilted = tilted.shade(ray);
    }
    out.push_back(p);
  }
  return out;
}

// Within 1e-3 relative per channel; the largest difference is recorded (measured 0:
// the mapped and the geometric normal come out as the same floats here).
void expectSame(const std::vector<Pair>& pairs, const char* what) {
  double worst = 0.0;
  for (size_t i = 0; i < pairs.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_GT(pairs[i].tilted[c], 1e-3f) << what << ": the light reaches the tilted quad";
      worst = std::max(worst, rel(pairs[i].flatMapped[c], pairs[i].tilted[c]));
      EXPECT_LT(rel(pairs[i].flatMapped[c], pairs[i].tilted[c]), 1e-3)
          << what << " ray " << i << " ch " << c << ": " << pairs[i].flatMapped[c] << " vs " << pairs[i].tilted[c];
    }
  }
  char worstText[32];
  std::snprintf(worstText, sizeof worstText, "%.3g", worst);
  ::testing::Test::RecordProperty(std::string(what) + "_worst_relative", worstText);
}

TEST(NormalMap, ComputedTangentsFollowUAndTheBitangentPointsUpTheImage) {
  // makeQuad's v grows along its second edge (+y here); the image's up is -v, so the
  // bitangent cross(n, t) w is -y: w = -1. Exact to 1e-6.
  TriangleMesh mesh = quad(0.0f, 0);
  computeTangents(mesh);
  ASSERT_EQ(mesh.tangents.size(), mesh.positions.size());
  for (const glm::vec4& t : mesh.tangents) {
    EXPECT_NEAR(glm::length(Vec3(t) - Vec3(1, 0, 0)), 0.0f, 1e-6f);
    EXPECT_EQ(t.w, -1.0f);
    const Vec3 b = glm::cross(Vec3(0, 0, 1), Vec3(t)) * t.w;
    EXPECT_NEAR(glm::length(b - Vec3(0, -1, 0)), 0.0f, 1e-6f);
  }
}

// The map's normal (0, -sin, cos) in (T, B, N) with B = -y is (0, sin, cos) in the
// world: the tilted quad's normal. Tolerance 1e-3 relative, per channel.
TEST(NormalMap, FlatQuadWithATiltMapShadesLikeTheTiltedQuadPhysical) {
  const testing::ScratchDir scratch;
  const std::string map = writeNormalMap(scratch.path() / "tilt.exr", Vec3(0.0f, -std::sin(kTilt), std::cos(kTilt)));
  const std::vector<Pair> lambertPairs = shadeBoth(lambert("lambert", Color(0.7f, 0.5f, 0.3f)), ShadingModel::Physical, map);
  expectSame(lambertPairs, "lambert");
  // The map matters: the plain flat quad is more than 5% away from the tilted one.
  const Vec3 toLight = -glm::normalize(Vec3(-0.3f, -0.8f, -1.0f));
  const float cosFlat = toLight.z, cosTilted = glm::dot(toLight, Vec3(0.0f, std::sin(kTilt), std::cos(kTilt)));
  EXPECT_GT(std::abs(cosTilted / cosFlat - 1.0f), 0.05f);
  EXPECT_NEAR(lambertPairs[0].tilted.r, 0.7f / kPi * 2.0f * cosTilted, 1e-5f);  // rho / pi E cos
  Material glossy = lambert("glossy", Color(0.8f, 0.6f, 0.4f));
  glossy.metalRough = true;
  glossy.metallic = 0.4f;
  glossy.roughness = 0.6f;
  expectSame(shadeBoth(glossy, ShadingModel::Physical, map), "metal-rough");
}

TEST(NormalMap, FlatQuadWithATiltMapShadesLikeTheTiltedQuadClassic) {
  const testing::ScratchDir scratch;
  const std::string map = writeNormalMap(scratch.path() / "tilt.exr", Vec3(0.0f, -std::sin(kTilt), std::cos(kTilt)));
  Material phong = makeMaterial("phong", Color(0.05f), Color(0.6f, 0.5f, 0.4f));
  phong.specular = Color(0.3f);
  phong.shininess = 20.0f;
  expectSame(shadeBoth(phong, ShadingModel::Classic, map), "phong");
}

TEST(NormalMap, ScaleZeroAndAFlatMapLeaveTheShadingAsItWas) {
  // normalScale 0 drops the tilt; a (0, 0, 1) map is the unperturbed normal. Both
  // must equal the flat quad without any map, within 1e-6 relative (float rounding).
  const testing::ScratchDir scratch;
  const std::string tilted = writeNormalMap(scratch.path() / "tilt.exr", Vec3(0.0f, -std::sin(kTilt), std::cos(kTilt)));
  const std::string flat = writeNormalMap(scratch.path() / "flat.exr", Vec3(0.0f, 0.0f, 1.0f));
  Material m = lambert("lambert", Color(0.5f));
  Scene plain = physicalScene();
  plain.materials.push_back(m);
  plain.meshes.push_back(quad(0.0f, 0));
  plain.lights.push_back(directional(Vec3(-0.3f, -0.8f, -1.0f), Color(1.0f), 2.0f));
  const Ray ray = makeRay(Vec3(0.3f, -0.4f, 5.0f), Vec3(-0.3f, 0.4f, -5.0f));
  const Color want = trace(Rig(plain), ray, kTermAll);
  for (const auto& [file, scale] : {std::pair{tilted, 0.0f}, std::pair{flat, 1.0f}}) {
    Scene scene = plain;
    scene.textures = {Texture{file, true, std::nullopt}};
    scene.materials[0].normalTexture = 0;
    scene.materials[0].normalScale = scale;
    computeTangents(scene.meshes[0]);
    const TextureLookup textures({file}, {true});
    Rig rig(scene);
    rig.ctx.textures = &textures;
    EXPECT_LT(rel(trace(rig, ray, kTermAll).g, want.g), 1e-6) << file << " scale " << scale;
  }
}

}  // namespace
}  // namespace penumbra
