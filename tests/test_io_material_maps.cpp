// Normal maps and alpha cut-outs as the loaders read them: glTF files written with
// tinygltf's writer (normalTexture and its scale, TANGENT given or computed, mirrored
// nodes, alphaMode MASK / BLEND / OPAQUE with the cutoff and the base colour's alpha
// decoded into a mask), MTL norm / map_Bump, and the JSON material keys.
#include "core/error.h"
#include "io/scene_loader.h"
#include "support/gltf_writer.h"
#include "support/scratch_dir.h"
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <filesystem>
#include <fstream>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// A 2 x 2 PNG of 8-bit channels, row 0 at the top.
void writePng(const fs::path& file, int channels, const std::vector<uint8_t>& bytes) {
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(2, 2, channels, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, bytes.data()));
  out->close();
}

// Per material one unit quad in z = 0 facing +z, with glTF uvs (v down: the image's
// up is +y), under its own node; material 0 also carries TANGENT (0, 1, 0, -1).
tinygltf::Model quads(const std::vector<tinygltf::Material>& materials, const std::vector<double>& firstScale = {}) {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.buffers.resize(1);
  const float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float nrm[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const float uv[] = {0, 1, 1, 1, 1, 0, 0, 0};
  const float tan[] = {0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1};
  const uint16_t idx[] = {0, 1, 2, 0, 2, 3};
  const int p = addAccessor(m, pos, sizeof pos, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 4);
  const int n = addAccessor(m, nrm, sizeof nrm, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 4);
  const int t = addAccessor(m, uv, sizeof uv, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, 4);
  const int g = addAccessor(m, tan, sizeof tan, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, 4);
  const int i = addAccessor(m, idx, sizeof idx, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 6);
  tinygltf::Scene scene;
  for (size_t k = 0; k < materials.size(); ++k) {
    m.materials.push_back(materials[k]);
    tinygltf::Primitive prim;
    prim.attributes = {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", t}};
    if (k == 0) prim.attributes["TANGENT"] = g;
    prim.indices = i;
    prim.material = static_cast<int>(k);
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh mesh;
    mesh.primitives.push_back(prim);
    m.meshes.push_back(mesh);
    tinygltf::Node node;
    node.mesh = static_cast<int>(k);
    node.translation = {0, 0, -2.0 * double(k)};
    if (k == 0) node.scale = firstScale;
    m.nodes.push_back(node);
    scene.nodes.push_back(static_cast<int>(k));
  }
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  return m;
}

Scene loadWritten(tinygltf::Model& m, const fs::path& file) {
  tinygltf::TinyGLTF writer;
  EXPECT_TRUE(writer.WriteGltfSceneToFile(&m, file.string(), true, true, false, false));
  return loadScene(file.string());
}

tinygltf::Material named(const std::string& name) {
  tinygltf::Material mat;
  mat.name = name;
  return mat;
}

TEST(GltfMaps, NormalTextureWithScaleAndTangentsGivenOrComputed) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  writePng(dir / "normal.png", 3, std::vector<uint8_t>(12, 128));
  std::vector<tinygltf::Material> mats = {named("given"), named("computed"), named("plain")};
  tinygltf::Model m = quads(mats);
  const int tex = addTexture(m, "normal.png");
  for (int k : {0, 1}) m.materials[k].normalTexture.index = tex;
  m.materials[0].normalTexture.scale = 0.5;
  const Scene s = loadWritten(m, dir / "maps.gltf");
  ASSERT_EQ(s.meshes.size(), 3u);
  const Material& given = s.materials[s.meshes[0].material];
  ASSERT_GE(given.normalTexture, 0);
  EXPECT_TRUE(s.textures[given.normalTexture].data);  // a normal map is data, never sRGB-decoded
  EXPECT_FLOAT_EQ(given.normalScale, 0.5f);
  EXPECT_FLOAT_EQ(s.materials[s.meshes[1].material].normalScale, 1.0f);  // glTF's default
  EXPECT_EQ(s.materials[s.meshes[2].material].normalTexture, -1);
  // The file's tangents as written; computed ones along +u (+x) with the bitangent
  // up the image (+y here, v runs down): w = +1. Exact to 1e-6.
  ASSERT_EQ(s.meshes[0].tangents.size(), 4u);
  for (const glm::vec4& t : s.meshes[0].tangents) EXPECT_NEAR(glm::length(t - glm::vec4(0, 1, 0, -1)), 0.0f, 1e-6f);
  ASSERT_EQ(s.meshes[1].tangents.size(), 4u);
  for (const glm::vec4& t : s.meshes[1].tangents) EXPECT_NEAR(glm::length(t - glm::vec4(1, 0, 0, 1)), 0.0f, 1e-6f);
  EXPECT_TRUE(s.meshes[2].tangents.empty());  // no normal map: no memory for tangents
}

TEST(GltfMaps, AMirroringNodeTurnsTheTangentAndItsHandedness) {
  // scale (-1, 1, 1): the tangent (0, 1, 0) stays, the bitangent's sign turns.
  const testing::ScratchDir scratch;
  writePng(scratch.path() / "normal.png", 3, std::vector<uint8_t>(12, 128));
  tinygltf::Model m = quads({named("given")}, {-1, 1, 1});
  m.materials[0].normalTexture.index = addTexture(m, "normal.png");
  const Scene s = loadWritten(m, scratch.path() / "mirror.gltf");
  for (const glm::vec4& t : s.meshes[0].tangents) EXPECT_NEAR(glm::length(t - glm::vec4(0, 1, 0, 1)), 0.0f, 1e-6f);
}

TEST(GltfMaps, AlphaModesCutoffAndTheBaseColoursAlphaAsAMask) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  // RGBA, alpha 255, 0 / 128, 64 (row 0 at the top).
  writePng(dir / "leaf.png", 4, {10, 20, 30, 255, 10, 20, 30, 0, 10, 20, 30, 128, 10, 20, 30, 64});
  std::vector<tinygltf::Material> mats = {named("mask"), named("blend"), named("opaque"), named("default_cutoff")};
  mats[0].alphaMode = "MASK";
  mats[0].alphaCutoff = 0.3;
  mats[1].alphaMode = "BLEND";
  mats[1].pbrMetallicRoughness.baseColorFactor = {1, 1, 1, 0.25};
  mats[2].alphaMode = "OPAQUE";
  mats[2].alphaCutoff = 0.9;
  mats[3].alphaMode = "MASK";
  tinygltf::Model m = quads(mats);
  const int tex = addTexture(m, "leaf.png");
  for (int k : {0, 2}) m.materials[k].pbrMetallicRoughness.baseColorTexture.index = tex;
  const Scene s = loadWritten(m, dir / "alpha.gltf");
  const Material& mask = s.materials[s.meshes[0].material];
  EXPECT_EQ(mask.alphaMode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(mask.alphaCutoff, 0.3f);
  ASSERT_EQ(s.alphaMasks.size(), 1u);  // only the textured MASK material decodes one
  ASSERT_EQ(mask.alphaMask, 0);
  const AlphaMask& a = s.alphaMasks[0];
  EXPECT_EQ(a.width, 2);
  EXPECT_EQ(a.height, 2);
  EXPECT_EQ(a.alpha, (std::vector<uint8_t>{255, 0, 128, 64}));
  EXPECT_FLOAT_EQ(a.at(Vec2(0.25f, 0.25f)), 1.0f);  // texel centres read exactly
  EXPECT_FLOAT_EQ(a.at(Vec2(0.75f, 0.75f)), 64.0f / 255.0f);
  const Material& blend = s.materials[s.meshes[1].material];
  EXPECT_EQ(blend.alphaMode, AlphaMode::Blend);
  EXPECT_FLOAT_EQ(blend.alpha, 0.25f);
  EXPECT_EQ(blend.alphaMask, -1);  // no base texture: the factor alone
  const Material& opaque = s.materials[s.meshes[2].material];
  EXPECT_EQ(opaque.alphaMode, AlphaMode::Opaque);
  EXPECT_EQ(opaque.alphaMask, -1);  // OPAQUE ignores alpha (and its cutoff)
  EXPECT_FLOAT_EQ(s.materials[s.meshes[3].material].alphaCutoff, 0.5f);  // glTF's default
}

TEST(ObjMaps, NormAndMapBumpAreTangentSpaceNormalMaps) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  writePng(dir / "n.png", 3, std::vector<uint8_t>(12, 128));
  write(dir / "m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nnorm n.png\nnewmtl b\nKd 0.5 0.5 0.5\nmap_Bump -bm 0.25 n.png\n");
  write(dir / "m.obj",
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 4/4\n");
  write(dir / "s.json", R"({"materials": {}, "objects": [{"type": "mesh", "file": "m.obj"}]})");
  const Scene s = loadScene((dir / "s.json").string());
  ASSERT_EQ(s.meshes.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    const Material& mat = s.materials[s.meshes[k].material];
    ASSERT_GE(mat.normalTexture, 0);
    EXPECT_TRUE(s.textures[mat.normalTexture].data);
    EXPECT_FLOAT_EQ(mat.normalScale, k == 0 ? 1.0f : 0.25f);
    // OBJ's v runs up the image and is flipped at load: the tangent is +x, w = +1.
    ASSERT_EQ(s.meshes[k].tangents.size(), s.meshes[k].positions.size());
    for (const glm::vec4& t : s.meshes[k].tangents) EXPECT_NEAR(glm::length(t - glm::vec4(1, 0, 0, 1)), 0.0f, 1e-6f);
  }
}

TEST(JsonMaps, NormalAndAlphaKeys) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  writePng(dir / "n.png", 3, std::vector<uint8_t>(12, 128));
  writePng(dir / "grey.png", 3, {0, 0, 0, 255, 255, 255, 255, 255, 255, 0, 0, 0});
  write(dir / "s.json", R"({"materials": {
      "bumpy": {"diffuse": [0.5, 0.5, 0.5], "normal_texture": "n.png", "normal_scale": 2},
      "leaf": {"diffuse": [0.5, 0.5, 0.5], "alpha_texture": "grey.png", "alpha_cutoff": 0.25},
      "screen": {"diffuse": [0.5, 0.5, 0.5], "alpha": 0.4, "alpha_mode": "blend"}},
    "objects": [{"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "material": "bumpy"},
                {"type": "quad", "corner": [0, 0, 1], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "material": "leaf"}]})");
  const Scene s = loadScene((dir / "s.json").string());
  const Material& bumpy = s.materials[0];
  EXPECT_GE(bumpy.normalTexture, 0);
  EXPECT_FLOAT_EQ(bumpy.normalScale, 2.0f);
  EXPECT_EQ(s.meshes[0].tangents.size(), 4u);
  EXPECT_TRUE(s.meshes[1].tangents.empty());
  const Material& leaf = s.materials[1];
  EXPECT_EQ(leaf.alphaMode, AlphaMode::Mask);  // the default with alpha_texture
  EXPECT_FLOAT_EQ(leaf.alphaCutoff, 0.25f);
  ASSERT_EQ(leaf.alphaMask, 0);
  EXPECT_EQ(s.alphaMasks[0].alpha, (std::vector<uint8_t>{0, 255, 255, 0}));  // grey without alpha
  EXPECT_EQ(s.materials[2].alphaMode, AlphaMode::Blend);
  EXPECT_FLOAT_EQ(s.materials[2].alpha, 0.4f);
  // A bad mode names its JSON path.
  write(dir / "bad.json", R"({"materials": {"m": {"alpha_mode": "cutout"}}})");
  try {
    loadScene((dir / "bad.json").string());
    ADD_FAILURE() << "an unknown alpha_mode must fail";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("materials.m.alpha_mode"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace penumbra
