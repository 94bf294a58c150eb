// Hard cases, class "glTF" (values): what the spec forbids or penumbra cannot show
// is refused naming the JSON path (versions, required extensions, light types,
// material extensions, matrices, quaternions, cameras, uvs); points and lines are
// skipped with a warning and normals that cannot be normalised flat-shade.
#include "hard/hard_gltf_support.h"

#include "io/camera_checks.h"

#include <cmath>

using namespace penumbra;
using namespace penumbra::hard_gltf;

namespace {

uint32_t le(uint32_t v) { return v; }  // the machines penumbra builds on are little-endian

std::string word(uint32_t v) {
  v = le(v);
  return std::string(reinterpret_cast<const char*>(&v), 4);
}

// A GLB of `doc` (its buffer 0 becomes the BIN chunk) with header version `version`.
std::string glb(json doc, uint32_t version) {
  const std::string bin = kVertexData + std::string("\0\1\2\0", 4);
  doc["buffers"][0].erase("uri");
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  const std::string body = word(uint32_t(text.size())) + "JSON" + text + word(uint32_t(bin.size())) + std::string("BIN\0", 4) + bin;
  return "glTF" + word(version) + word(uint32_t(12 + body.size())) + body;
}

json withLight(const std::string& type) {
  json j = triangle();
  j["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", type}, {"intensity", 1}}};
  if (type == "spot") j["extensions"]["KHR_lights_punctual"]["lights"][0]["spot"] = json::object();
  j["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"translation", {0, 1, 1}}});
  j["scenes"][0]["nodes"].push_back(1);
  return j;
}

json withMaterialExtension(const std::string& name, const json& value) {
  json j = triangle();
  j["materials"] = {{{"extensions", {{name, value}}}}};
  j["meshes"][0]["primitives"][0]["material"] = 0;
  return j;
}

json withCamera(const json& perspective, const json& translation = {0, 0, 3}) {
  json j = triangle();
  j["cameras"] = {{{"type", "perspective"}, {"perspective", perspective}}};
  j["nodes"].push_back({{"camera", 0}, {"translation", translation}});
  j["scenes"][0]["nodes"].push_back(1);
  return j;
}

}  // namespace

TEST(HardGltfValues, VersionsAndRequiredExtensionsAreChecked) {
  const ScratchDir dir;
  json j = triangle();
  j["asset"]["version"] = "3.0";
  expectRefused(dir, j, {"asset.version", "\"3.0\""});
  for (const char* ext : {"KHR_draco_mesh_compression", "VENDOR_unknown_extension", "EXT_meshopt_compression"}) {
    j = triangle();
    j["extensionsUsed"] = {ext};
    j["extensionsRequired"] = {ext};
    expectRefused(dir, j, {"extensionsRequired[0]", std::string("requires ") + ext, "which penumbra does not support"});
  }
  const fs::path ok = dir.write("model.glb", glb(triangle(), 2));
  EXPECT_EQ(refusal(ok), "");
  const fs::path v1 = dir.write("model.glb", glb(triangle(), 1));
  const std::string what = refusal(v1);
  EXPECT_NE(what.find("GLB header: version 1"), std::string::npos) << what;
}

TEST(HardGltfValues, PrimitiveModes) {
  const ScratchDir dir;
  json j = triangle();
  j["meshes"][0]["primitives"].push_back(j["meshes"][0]["primitives"][0]);
  j["meshes"][0]["primitives"][1]["mode"] = 1;  // lines: skipped, said so
  const fs::path file = dir.write("model.gltf", j.dump());
  const LoadedModel m = loadModel(file.string());
  EXPECT_EQ(m.meshes.size(), 1u);
  EXPECT_NE(m.warning.find("meshes[0].primitives[1].mode"), std::string::npos) << m.warning;
  j["meshes"][0]["primitives"][1]["mode"] = 7;
  expectRefused(dir, j, {"meshes[0].primitives[1].mode", "must be 0..6"});
  j["meshes"][0]["primitives"][1]["mode"] = 6;  // a fan of three is one triangle
  EXPECT_EQ(loadModel(dir.write("model.gltf", j.dump()).string()).meshes.size(), 2u);
}

TEST(HardGltfValues, LightsAndMaterialExtensionsAreInRange) {
  const ScratchDir dir;
  EXPECT_EQ(refusal(dir.write("model.gltf", withLight("spot").dump())), "");
  expectRefused(dir, withLight("area"), {"KHR_lights_punctual.lights[0].type", "\"area\""});
  for (const json& ior : {json(0), json(-1.5), json("glass"), json(0.5)}) {
    expectRefused(dir, withMaterialExtension("KHR_materials_ior", {{"ior", ior}}),
                  {"materials[0].extensions.KHR_materials_ior.ior"});
  }
  EXPECT_EQ(refusal(dir.write("model.gltf", withMaterialExtension("KHR_materials_ior", {{"ior", 1.33}}).dump())), "");
  expectRefused(dir, withMaterialExtension("KHR_materials_emissive_strength", {{"emissiveStrength", -5}}),
                {"materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength"});
}

TEST(HardGltfValues, NodeTransformsAreWellFormedAndInvertible) {
  const ScratchDir dir;
  json j = triangle();
  j["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0};  // 15 numbers
  expectRefused(dir, j, {"nodes[0].matrix", "must have 16 numbers"});
  j["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};  // flattens z: singular
  expectRefused(dir, j, {"nodes[0].matrix", "singular"});
  j["nodes"][0].erase("matrix");
  j["nodes"][0]["rotation"] = {0, 0, 0, 0};
  expectRefused(dir, j, {"nodes[0].rotation", "zero quaternion"});
  j["nodes"][0]["rotation"] = {0, 0, 0, 2};  // not unit: normalised, as rounding would need
  EXPECT_EQ(refusal(dir.write("model.gltf", j.dump())), "");
  j["nodes"][0]["scale"] = {1, 1, 0};
  expectRefused(dir, j, {"nodes[0]", "singular"});
}

// glTF cameras skipped the checks JSON cameras get (one function now checks both).
TEST(HardGltfValues, CamerasMeetTheJsonCameraChecks) {
  const ScratchDir dir;
  EXPECT_EQ(refusal(dir.write("model.gltf", withCamera({{"yfov", 0.8}, {"znear", 0.1}, {"aspectRatio", 1.5}}).dump())), "");
  for (double yfov : {0.0, -0.5, 3.1416, 1e300}) {
    expectRefused(dir, withCamera({{"yfov", yfov}, {"znear", 0.1}}), {"cameras[0].perspective.yfov"});
  }
  for (double aspect : {1e300, 1e-300, 1000.0}) {
    expectRefused(dir, withCamera({{"yfov", 0.8}, {"znear", 0.1}, {"aspectRatio", aspect}}), {"cameras[0].perspective.aspectRatio"});
  }
  expectRefused(dir, withCamera({{"yfov", 0.8}, {"znear", 0.1}}, {0, 0, 1e16}), {"cameras[0]", "position", "1e+15"});
  // The shared check itself, as batch orbits will call it.
  Camera far;
  far.position = Vec3(0.0f, 0.0f, 1e16f);
  EXPECT_THROW(checkCamera(far, "orbit view 2"), InputError);
  EXPECT_NO_THROW(checkCamera(Camera{}, "default"));
}

// Zero or NaN normals flat-shade their primitive (the geometric normal) instead of
// a made-up (0, 0, 1); texture coordinates are bounded like positions.
TEST(HardGltfValues, BadNormalsFlatShadeAndUvsAreBounded) {
  const ScratchDir dir;
  for (float bad : {0.0f, NAN}) {
    json j = triangle();
    j["buffers"][0]["uri"] = dataUri(bytesOf<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}) + bytesOf<float>({0, 0, 1, 0, 0, bad, 0, 0, 1}) +
                                     bytesOf<float>({0, 0, 1, 0, 0, 1}) + std::string("\0\1\2\0", 4));
    const LoadedModel m = loadModel(dir.write("model.gltf", j.dump()).string());
    ASSERT_EQ(m.meshes.size(), 1u);
    EXPECT_TRUE(m.meshes[0].normals.empty()) << bad;
    EXPECT_NE(m.warning.find("NORMAL"), std::string::npos) << m.warning;
  }
  json j = triangle();
  j["buffers"][0]["uri"] = dataUri(kVertexData.substr(0, 72) + bytesOf<float>({0, 0, 1e10f, 0, 0, 1}) + std::string("\0\1\2\0", 4));
  expectRefused(dir, j, {"accessors[2]", "texture coordinate 1 is beyond +-1e6"});
}
