// glTF and MTL materials, lights and cameras beyond the basics: the metallic-
// roughness map read as data, texture transforms and volume tint, MTL's PBR keys,
// spot cones and orthographic cameras, loaded from files tinygltf's writer made.
#include "core/error.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "support/gltf_scene_model.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

TEST(Gltf, MetallicRoughnessTextureIsReadAsDataBesideTheBaseColour) {
  // The chrome quad gets one PNG as base colour and as metallic-roughness map: two
  // textures, the second marked as data (test_trace_texture reads it undecoded).
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  Image mr(2, 2);
  mr.pixels.assign(4, Color(0.0f, 128.0f / 255.0f, 1.0f));
  writeImage((dir / "mr.png").string(), mr);
  tinygltf::Model m = makeGltf();
  addTexture(m, "mr.png");
  m.materials[1].pbrMetallicRoughness.baseColorTexture.index = 0;
  m.materials[1].pbrMetallicRoughness.metallicRoughnessTexture.index = 0;
  m.materials[1].pbrMetallicRoughness.roughnessFactor = 0.8;
  writeGltf(m, dir / "model.gltf", false);
  const Scene s = loadScene((dir / "model.gltf").string());
  const Material& chrome = s.materials[s.meshes[1].material];
  ASSERT_GE(chrome.texture, 0);
  ASSERT_GE(chrome.metalRoughTexture, 0);
  EXPECT_NE(chrome.texture, chrome.metalRoughTexture);
  EXPECT_FALSE(s.textures[chrome.texture].data);
  EXPECT_TRUE(s.textures[chrome.metalRoughTexture].data);
}

TEST(Gltf, TextureTransformAndVolumeAttenuationReachTheMaterial) {
  // KHR_texture_transform on the base colour places every map of the material;
  // KHR_materials_volume tints glass by attenuationColor^(thickness / distance).
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  Image img(2, 2);
  img.pixels.assign(4, Color(0.5f));
  writeImage((dir / "base.png").string(), img);
  tinygltf::Model m = makeGltf();
  addTexture(m, "base.png");
  tinygltf::TextureInfo& info = m.materials[1].pbrMetallicRoughness.baseColorTexture;
  info.index = 0;
  info.extensions["KHR_texture_transform"] = tinygltf::Value(tinygltf::Value::Object{
      {"offset", tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(0.25), tinygltf::Value(0.5)})},
      {"rotation", tinygltf::Value(0.3)},
      {"scale", tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(2.0), tinygltf::Value(-1.0)})}});
  m.materials[2].extensions["KHR_materials_volume"] = tinygltf::Value(tinygltf::Value::Object{
      {"thicknessFactor", tinygltf::Value(0.5)},
      {"attenuationDistance", tinygltf::Value(2.0)},
      {"attenuationColor",
       tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(0.5), tinygltf::Value(1.0), tinygltf::Value(0.0625)})}});
  m.extensionsUsed.push_back("KHR_texture_transform");
  m.extensionsUsed.push_back("KHR_materials_volume");
  writeGltf(m, dir / "model.gltf", false);
  const Scene s = loadScene((dir / "model.gltf").string());
  const Material& chrome = s.materials[s.meshes[1].material];
  EXPECT_EQ(chrome.uvScale, Vec2(2.0f, -1.0f));
  EXPECT_EQ(chrome.uvOffset, Vec2(0.25f, 0.5f));
  EXPECT_FLOAT_EQ(chrome.uvRotation, 0.3f);
  const Material& glass = s.materials[s.meshes[2].material];
  // base (0.9, 0.95, 1) x (0.5, 1, 0.0625)^(1/4) = (0.9 x 0.8409, 0.95, 0.5). Tolerance 1e-5.
  EXPECT_NEAR(glass.tint.r, 0.9f * std::pow(0.5f, 0.25f), 1e-5f);
  EXPECT_NEAR(glass.tint.g, 0.95f, 1e-5f);
  EXPECT_NEAR(glass.tint.b, 0.5f, 1e-5f);
}

TEST(ObjMaterials, PbrExtensionPmAndPrMakeTheMetallicRoughnessMaterial) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  write(dir / "m.mtl", "newmtl gold\nKd 1 0.78 0.34\nPm 1\nPr 0.25\n");
  write(dir / "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl gold\nf 1 2 3\n");
  write(dir / "scene.json", R"({"render": {"model": "physical"}, "objects": [{"type": "mesh", "file": "m.obj"}]})");
  const Scene s = loadScene((dir / "scene.json").string());
  const Material& gold = s.materials[s.meshes[0].material];
  EXPECT_TRUE(gold.metalRough);
  EXPECT_EQ(gold.metallic, 1.0f);
  EXPECT_EQ(gold.roughness, 0.25f);
  EXPECT_FLOAT_EQ(gold.diffuse.g, 0.78f);
}

TEST(Gltf, ASpotKeepsItsConeAndShinesAlongItsNodesMinusZ) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  tinygltf::Model m = makeGltf();
  m.lights[0].type = "spot";
  m.lights[0].spot.innerConeAngle = 0.2;
  m.lights[0].spot.outerConeAngle = 0.5;
  writeGltf(m, dir / "spot.glb", true);
  const Scene s = loadScene((dir / "spot.glb").string());
  const Light* spot = nullptr;
  for (const Light& l : s.lights) if (l.isSpot()) spot = &l;
  ASSERT_NE(spot, nullptr);
  EXPECT_NEAR(spot->spotCosInner, std::cos(0.2), 1e-6);
  EXPECT_NEAR(spot->spotCosOuter, std::cos(0.5), 1e-6);
  expectNear(spot->direction, Vec3(0, 0, -1), 1e-6f, "spot direction");
  m.lights[0].spot.innerConeAngle = 0.6;  // beyond the outer cone
  writeGltf(m, dir / "bad.glb", true);
  try {
    loadScene((dir / "bad.glb").string());
    FAIL() << "an inner cone beyond the outer one must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("innerConeAngle"), std::string::npos) << e.what();
  }
}

TEST(Gltf, AnOrthographicCameraKeepsItsHeightAndAspect) {
  // ymag is half the view's height; xmag / ymag its aspect, which sets the image height.
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  tinygltf::Model m = makeGltf();
  m.cameras[0].type = "orthographic";
  m.cameras[0].orthographic.xmag = 3.0;
  m.cameras[0].orthographic.ymag = 1.5;
  m.cameras[0].orthographic.znear = 0.1;
  m.cameras[0].orthographic.zfar = 100.0;
  writeGltf(m, dir / "ortho.glb", true);
  write(dir / "ortho.json", R"({"camera": {"width": 320}})");
  const Scene s = loadScene((dir / "ortho.glb").string());
  EXPECT_EQ(s.camera.orthoHeight, 3.0f);
  EXPECT_EQ(s.camera.height, 160);
}

TEST(Gltf, EmissiveTextureAndDoubleSidedReachTheLampAndItsLight) {
  // The lamp's emissive texture (a colour: sRGB-decoded) multiplies emissiveFactor x
  // strength; doubleSided makes it emit on both sides; glTF's emitter keeps its BSDF.
  // The lamp quad has no uvs, so its light takes the texture's mean colour.
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  Image glow(2, 1);
  glow.pixels = {Color(1.0f), Color(0.0f)};
  writeImage((dir / "glow.png").string(), glow);
  tinygltf::Model m = makeGltf();
  addTexture(m, "glow.png");
  m.materials[3].emissiveTexture.index = 0;
  m.materials[3].doubleSided = true;
  writeGltf(m, dir / "model.gltf", false);
  const Scene s = loadScene((dir / "model.gltf").string());
  const Material& lamp = s.materials[s.meshes[3].material];
  ASSERT_GE(lamp.emissionTexture, 0);
  EXPECT_FALSE(s.textures[lamp.emissionTexture].data);
  EXPECT_TRUE(lamp.twoSidedEmission);
  EXPECT_TRUE(lamp.emitterShades);
  EXPECT_EQ(lamp.diffuse, Color(1.0f));
  ASSERT_GE(lamp.light, 0);
  const Light& light = s.lights[lamp.light];
  EXPECT_TRUE(light.twoSided);
  EXPECT_FALSE(light.emission);
  expectNear(light.radiance(), Vec3(1.0f, 0.5f, 0.25f) * 4.0f * 0.5f, 1e-3f, "mean texel x factor x strength");
}

}  // namespace
}  // namespace penumbra
