// Vertex colours read into TriangleMesh::colors: glTF's COLOR_0 from files tinygltf's
// writer made (FLOAT VEC3, normalized UNSIGNED_BYTE VEC4 and UNSIGNED_SHORT VEC3,
// decoded to linear 0..1), all-white colours dropped, accessors the spec does not
// allow for colours refused naming them, and OBJ's `v x y z r g b` lines.
#include "io/scene_loader.h"
#include "support/gltf_build.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// The quad (0,0,0) (1,0,0) (1,1,0) (0,1,0) with COLOR_0 = `colours` (4 elements of
// `type`), written as quad.gltf in `dir`; returns its path.
template <typename T>
fs::path writeQuad(const fs::path& dir, const std::vector<T>& colours, int componentType, int type, bool normalized,
                   size_t count = 4) {
  tinygltf::Model m = testing::emptyGltf();
  const int mesh = testing::addTriangleMesh(m, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {}, {}, {0, 1, 2, 0, 2, 3});
  const int accessor = testing::appendAccessor(m, colours, componentType, type, count);
  m.accessors[accessor].normalized = normalized;
  m.meshes[mesh].primitives[0].attributes["COLOR_0"] = accessor;
  testing::addSceneNode(m, mesh);
  const fs::path file = dir / "quad.gltf";
  EXPECT_TRUE(testing::writeGltfFile(m, file.string(), false));
  return file;
}

std::string loadError(const fs::path& file) {
  try {
    loadScene(file.string());
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

void expectColours(const std::vector<glm::vec4>& got, const std::vector<glm::vec4>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    for (int c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(got[i][c], want[i][c]) << "vertex " << i << " channel " << c;
  }
}

TEST(VertexColors, GltfFloatRedQuadIsRedWithAlphaOne) {
  const testing::ScratchDir scratch;
  const std::vector<float> red = {1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0};
  const Scene s =
      loadScene(writeQuad(scratch.path(), red, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, false).string());
  ASSERT_EQ(s.meshes.size(), 1u);
  expectColours(s.meshes[0].colors, std::vector<glm::vec4>(4, glm::vec4(1, 0, 0, 1)));
}

TEST(VertexColors, GltfNormalizedBytesAndShortsAreDividedBy255And65535) {
  // A gradient of UNSIGNED_BYTE RGBA: each channel b / 255 (alpha too); then
  // UNSIGNED_SHORT RGB: h / 65535 with alpha 1.
  const testing::ScratchDir scratch;
  const std::vector<uint8_t> bytes = {0, 0, 0, 255, 85, 128, 255, 0, 170, 64, 32, 128, 255, 255, 255, 255};
  Scene s = loadScene(
      writeQuad(scratch.path(), bytes, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, true).string());
  std::vector<glm::vec4> want;
  for (size_t v = 0; v < 4; ++v) {
    want.emplace_back(bytes[4 * v] / 255.0f, bytes[4 * v + 1] / 255.0f, bytes[4 * v + 2] / 255.0f,
                      bytes[4 * v + 3] / 255.0f);
  }
  expectColours(s.meshes[0].colors, want);

  const std::vector<uint16_t> shorts = {0, 32768, 65535, 1, 2, 3, 65535, 0, 4096, 12000, 24000, 48000};
  s = loadScene(
      writeQuad(scratch.path(), shorts, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC3, true).string());
  want.clear();
  for (size_t v = 0; v < 4; ++v) {
    want.emplace_back(shorts[3 * v] / 65535.0f, shorts[3 * v + 1] / 65535.0f, shorts[3 * v + 2] / 65535.0f, 1.0f);
  }
  expectColours(s.meshes[0].colors, want);
}

TEST(VertexColors, FloatsOutsideZeroToOneAreClampedAndAllWhiteIsNoColours) {
  const testing::ScratchDir scratch;
  const std::vector<float> wild = {1.5f, -0.25f, 0.5f, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  Scene s =
      loadScene(writeQuad(scratch.path(), wild, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, false).string());
  expectColours(s.meshes[0].colors, {glm::vec4(1, 0, 0.5f, 1), glm::vec4(1), glm::vec4(1), glm::vec4(1)});
  // Opaque white everywhere multiplies by 1: the mesh keeps no colours.
  const std::vector<float> white(16, 1.0f);
  s = loadScene(writeQuad(scratch.path(), white, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, false).string());
  EXPECT_TRUE(s.meshes[0].colors.empty());
  EXPECT_EQ(s.meshes[0].colors.capacity(), 0u);
}

TEST(VertexColors, GltfColourAccessorsTheSpecDoesNotAllowAreRefused) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  const std::vector<uint8_t> bytes(16, 200);
  std::string e = loadError(writeQuad(dir, bytes, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, false));
  EXPECT_NE(e.find("accessors[2]: COLOR_0 must be a VEC3 or VEC4 of FLOAT, or of normalized UNSIGNED_BYTE"),
            std::string::npos) << e;
  const std::vector<float> pairs(8, 0.5f);
  e = loadError(writeQuad(dir, pairs, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, false));
  EXPECT_NE(e.find("COLOR_0 must be a VEC3 or VEC4"), std::string::npos) << e;
  const std::vector<float> three(9, 0.5f);
  e = loadError(writeQuad(dir, three, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, false, 3));
  EXPECT_NE(e.find("attributes.COLOR_0: has 3 elements but POSITION has 4"), std::string::npos) << e;
}

TEST(VertexColors, ObjVertexColoursFollowTheirVerticesIntoEachMaterialsMesh) {
  // Two usemtl groups: each mesh keeps the colours of its own vertices. A file where
  // one `v` lacks a colour has none (tinyobjloader keeps them only for all).
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  std::ofstream(dir / "m.mtl") << "newmtl a\nKd 0.5 0.5 0.5\nnewmtl b\nKd 0.5 0.5 0.5\n";
  std::ofstream(dir / "m.obj") << "mtllib m.mtl\n"
                                  "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nv 1 1 0 0.25 0.5 0.75\n"
                                  "usemtl a\nf 1 2 3\nusemtl b\nf 2 4 3\n";
  std::ofstream(dir / "scene.json") << R"({"objects": [{"type": "mesh", "file": "m.obj"}]})";
  Scene s = loadScene((dir / "scene.json").string());
  ASSERT_EQ(s.meshes.size(), 2u);
  expectColours(s.meshes[0].colors, {glm::vec4(1, 0, 0, 1), glm::vec4(0, 1, 0, 1), glm::vec4(0, 0, 1, 1)});
  expectColours(s.meshes[1].colors, {glm::vec4(0, 1, 0, 1), glm::vec4(0.25f, 0.5f, 0.75f, 1), glm::vec4(0, 0, 1, 1)});

  std::ofstream(dir / "m.obj") << "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
  s = loadScene((dir / "scene.json").string());
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_TRUE(s.meshes[0].colors.empty());
}

}  // namespace
}  // namespace penumbra
