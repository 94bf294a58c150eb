// OBJ + MTL and glTF 2.0 files into scenes: each test writes its own small files
// (OBJ/MTL as text, glTF built with tinygltf's own writer) into a scratch folder and
// checks geometry, materials, camera and lights against the values it wrote.
#include "core/bsdf.h"
#include "core/error.h"
#include "core/light_sample.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "support/gltf_scene_model.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

const Material& byName(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials) if (m.name == name) return m;
  ADD_FAILURE() << "no material " << name;
  return s.materials[0];
}

// A floor quad (red, textured), a glass triangle, a downward light quad (Ke) and a
// Cornell-style light marked by Ka 20 without Ke.
void writeObj(const fs::path& dir) {
  Image texture(2, 2);
  texture.pixels = {Color(1, 0, 0), Color(0, 1, 0), Color(0, 0, 1), Color(1, 1, 1)};
  writeImage((dir / "tex.png").string(), texture);
  write(dir / "room.mtl",
        "newmtl red\nKd 0.8 0.1 0.1\nKs 0.5 0.5 0.5\nNs 40\nmap_Kd tex.png\n"
        "newmtl glass\nKd 0 0 0\nNi 1.45\nd 0.1\nTf 0.9 1 0.9\n"
        "newmtl lamp\nKd 0.7 0.7 0.7\nKe 4 3 2\n"
        "newmtl oldlamp\nKa 20 20 20\nKd 1 1 1\n");
  write(dir / "room.obj",
        "mtllib room.mtl\n"
        "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n"            // 1-4 floor
        "v 0 0.5 0\nv 0.5 0.5 0\nv 0 1 0\n"                   // 5-7 glass
        "v -0.5 2 -0.5\nv 0.5 2 -0.5\nv 0.5 2 0.5\nv -0.5 2 0.5\n"  // 8-11 lamp (faces down)
        "v 0 3 0\nv 0 3 0.5\nv 0.5 3 0\n"                     // 12-14 old lamp
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "usemtl red\nf 1/1 4/4 3/3 2/2\n"
        "usemtl glass\nf 5 6 7\n"
        "usemtl lamp\nf 8 9 10 11\n"
        "usemtl oldlamp\nf 12 14 13\n");
}

TEST(ObjMaterials, UsemtlGroupsKeepTheirMtlMaterialsAndKeLightsTheScene) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  writeObj(dir);
  write(dir / "scene.json", R"({"render": {"model": "physical"}, "materials": {"grey": {"diffuse": 0.5}},
    "objects": [{"type": "mesh", "file": "room.obj", "translate": [0, 1, 0]}]})");
  const Scene s = loadScene((dir / "scene.json").string());
  ASSERT_EQ(s.meshes.size(), 4u);  // one per usemtl group
  const Material& red = byName(s, "room.obj:red");
  EXPECT_FLOAT_EQ(red.diffuse.r, 0.8f);
  EXPECT_FLOAT_EQ(red.shininess, 40.0f);
  EXPECT_NEAR(red.specular.r, 0.2f, 1e-6);  // physical: Ks gives way to 1 - Kd
  EXPECT_NEAR(red.specular.g, 0.5f, 1e-6);
  ASSERT_GE(red.texture, 0);
  EXPECT_EQ(fs::path(s.textures[red.texture].path).filename(), "tex.png");
  const Material& glass = byName(s, "room.obj:glass");
  EXPECT_TRUE(glass.transparent);
  EXPECT_FLOAT_EQ(glass.ior, 1.45f);
  EXPECT_FLOAT_EQ(glass.tint.r, 0.9f);
  // The floor kept its uvs and moved with the object's transform.
  EXPECT_EQ(s.meshes[0].uvs.size(), s.meshes[0].positions.size());
  EXPECT_FLOAT_EQ(s.meshes[0].positions[0].y, 1.0f);
  // Ke and Ka 20 made two mesh lights: pi A L each, at the transformed height.
  ASSERT_EQ(s.lights.size(), 2u);
  const Light& lamp = s.lights[0];
  EXPECT_EQ(lamp.type, LightType::Mesh);
  EXPECT_NEAR(lightArea(lamp), 1.0f, 1e-6);
  EXPECT_FLOAT_EQ(lamp.radiance().r, 4.0f);
  EXPECT_FLOAT_EQ(lamp.radiance().b, 2.0f);
  EXPECT_FLOAT_EQ(lamp.triangles[0].y, 3.0f);
  EXPECT_NEAR(lightPower(lamp, SceneSphere{}).g, 3.14159265f * 1.0f * 3.0f, 1e-4);
  EXPECT_EQ(byName(s, "room.obj:lamp").light, 0);
  EXPECT_NEAR(lightArea(s.lights[1]), 0.125f, 1e-6);
  EXPECT_FLOAT_EQ(s.lights[1].radiance().g, 20.0f);
}

TEST(ObjMaterials, TheScenesMaterialOverridesTheMtl) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  writeObj(dir);
  write(dir / "scene.json", R"({"materials": {"grey": {"diffuse": 0.5}},
    "objects": [{"type": "mesh", "file": "room.obj", "material": "grey"}]})");
  const Scene s = loadScene((dir / "scene.json").string());
  EXPECT_EQ(s.materials.size(), 1u);
  EXPECT_TRUE(s.lights.empty());
  for (const TriangleMesh& m : s.meshes) EXPECT_EQ(m.material, 0);
}

TEST(ObjMaterials, AnObjWithoutMaterialsStillNeedsOne) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  write(dir / "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write(dir / "scene.json", R"({"materials": {"grey": {}}, "objects": [{"type": "mesh", "file": "t.obj"}]})");
  try {
    loadScene((dir / "scene.json").string());
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("objects[0]: missing required key \"material\" (t.obj has no materials"),
              std::string::npos) << e.what();
  }
}

// ---- glTF, built with tinygltf's writer.

TEST(Gltf, AWholeGlbSceneBringsMeshesMaterialsCameraAndLights) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  writeGltf(makeGltf(), dir / "model.glb", true);
  write(dir / "model.json", R"({"render": {"model": "physical"}, "camera": {"width": 320}})");
  const Scene s = loadScene((dir / "model.glb").string());
  EXPECT_EQ(s.name, "model");
  ASSERT_EQ(s.meshes.size(), 4u);
  // Paint quad: rotated -90 degrees about x, scaled 2, moved to x = 10: corner (1, 1, 0)
  // goes to (2, 0, -2) + (10, 0, 0); its +z normal turns to +y.
  const TriangleMesh& floor = s.meshes[0];
  expectNear(floor.positions[2], Vec3(12, 0, -2), 1e-5f, "floor corner");
  expectNear(floor.normals[0], Vec3(0, 1, 0), 1e-5f, "floor normal");
  const Material& paint = s.materials[floor.material];
  EXPECT_EQ(paint.name, "model.glb:paint");
  // glTF's metallic-roughness as given: a rough dielectric paint and a smooth metal,
  // whose physical BSDF is the delta mirror reflecting its white base colour whole.
  EXPECT_FLOAT_EQ(paint.diffuse.g, 0.4f);
  EXPECT_TRUE(paint.metalRough);
  EXPECT_EQ(paint.metallic, 0.0f);
  EXPECT_EQ(paint.roughness, 1.0f);
  const Material& chrome = s.materials[s.meshes[1].material];
  EXPECT_TRUE(chrome.metalRough);
  EXPECT_EQ(chrome.metallic, 1.0f);
  EXPECT_EQ(chrome.roughness, 0.0f);
  const Bsdf mirror = makeBsdf(chrome, BsdfFamily::Radiometric, HemisphereSampling::Cosine);
  EXPECT_EQ(bsdfFlags(mirror), kBsdfSpecular);
  const BsdfFrame up{Vec3(0, 0, 1), Vec3(0, 0, 1), true};
  expectNear(mirrorReflectance(mirror, up, glm::normalize(Vec3(1, 0, 1))), Color(1.0f), 1e-6f, "chrome");
  const Material& glass = s.materials[s.meshes[2].material];
  EXPECT_TRUE(glass.transparent);
  EXPECT_FLOAT_EQ(glass.ior, 1.33f);
  EXPECT_FLOAT_EQ(glass.tint.g, 0.95f);
  // Camera: the node's position, -z forward, yfov in degrees, the sidecar's width and
  // the file's aspect ratio for the height.
  expectNear(s.camera.position, Vec3(0, 1, 8), 1e-6f, "camera");
  expectNear(glm::normalize(s.camera.lookAt - s.camera.position), Vec3(0, 0, -1), 1e-6f, "view");
  EXPECT_NEAR(s.camera.fovY, 0.5 * 180.0 / 3.14159265358979, 1e-4);
  EXPECT_EQ(s.camera.width, 320);
  EXPECT_EQ(s.camera.height, 160);  // the sidecar set only the width: the file's aspect ratio 2 stays
  // Lights: point, directional, then the emissive quad as a mesh light (facing -y at y = 4).
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lights[0].type, LightType::Point);
  expectNear(s.lights[0].position, Vec3(1, 5, 1), 1e-6f, "point light");
  EXPECT_FLOAT_EQ(s.lights[0].radiance().g, 15.0f);
  EXPECT_EQ(s.lights[1].type, LightType::Directional);
  expectNear(s.lights[1].direction, Vec3(0, -1, 0), 1e-6f, "sun");
  const Light& lamp = s.lights[2];
  EXPECT_EQ(lamp.type, LightType::Mesh);
  EXPECT_NEAR(lightArea(lamp), 1.0f, 1e-6);
  EXPECT_FLOAT_EQ(lamp.radiance().g, 2.0f);  // 0.5 x strength 4
  const Vec3 n = glm::cross(lamp.triangles[1] - lamp.triangles[0], lamp.triangles[2] - lamp.triangles[0]);
  expectNear(glm::normalize(n), Vec3(0, -1, 0), 1e-5f, "lamp faces down");
  EXPECT_EQ(s.render.model, ShadingModel::Physical);
}

TEST(Gltf, AsAMeshObjectInAJsonScene) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  writeGltf(makeGltf(), dir / "parts.gltf", false);
  write(dir / "scene.json", R"({"lights": [{"type": "point", "position": [0, 9, 0]}],
    "objects": [{"type": "mesh", "file": "parts.gltf", "translate": [0, 0, 100]}]})");
  const Scene s = loadScene((dir / "scene.json").string());
  ASSERT_EQ(s.meshes.size(), 4u);
  expectNear(s.meshes[0].positions[2], Vec3(12, 0, 98), 1e-5f, "floor corner");
  // Its own materials (after "default"); only the JSON's light and the mesh light.
  EXPECT_EQ(s.materials[s.meshes[1].material].name, "parts.gltf:chrome");
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[1].type, LightType::Mesh);
  EXPECT_EQ(s.camera.position, Camera{}.position);  // a mesh object brings no camera
  // Every mesh leaves its vertices padded for Embree's 16-byte loads, so the tracer
  // reads them in place: the file's primitives placed by a mesh object, or as the scene.
  for (const TriangleMesh& m : s.meshes) EXPECT_TRUE(hasVertexPadding(m.positions)) << m.name;
  const Scene whole = loadScene((dir / "parts.gltf").string());
  for (const TriangleMesh& m : whole.meshes) EXPECT_TRUE(hasVertexPadding(m.positions)) << m.name;
}

TEST(Gltf, BrokenFilesFailWithOneLine) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  write(dir / "junk.glb", "glTF but not really");
  try {
    loadScene((dir / "junk.glb").string());
    FAIL() << "loaded";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("junk.glb"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  tinygltf::Model m = makeGltf();
  m.accessors[2].count = 600;  // indices past the end of their buffer view
  writeGltf(m, dir / "short.gltf", false);
  write(dir / "scene.json", R"({"objects": [{"type": "mesh", "file": "short.gltf"}]})");
  try {
    loadScene((dir / "scene.json").string());
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("objects[0].file: glTF file"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("reaches past the end of its buffer"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace penumbra
