// A small glTF scene for loader tests, written with tinygltf's writer: four quads
// (paint, chrome, glass, an emissive lamp) under transformed nodes, a camera, a
// point light and a sun.
#pragma once
#include "core/math.h"
#include "support/gltf_writer.h"
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace penumbra {

// One quad primitive (two triangles in z = 0, facing +z) per material, under nodes.
inline tinygltf::Model makeGltf() {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.buffers.resize(1);
  const float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float nrm[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const uint16_t idx[] = {0, 1, 2, 0, 2, 3};
  addAccessor(m, pos, sizeof pos, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 4);
  addAccessor(m, nrm, sizeof nrm, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 4);
  addAccessor(m, idx, sizeof idx, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 6);
  auto material = [&](const std::string& name, std::vector<double> base, double metallic, double roughness) {
    tinygltf::Material mat;
    mat.name = name;
    mat.pbrMetallicRoughness.baseColorFactor = base;
    mat.pbrMetallicRoughness.metallicFactor = metallic;
    mat.pbrMetallicRoughness.roughnessFactor = roughness;
    m.materials.push_back(mat);
    tinygltf::Primitive prim;
    prim.attributes = {{"POSITION", 0}, {"NORMAL", 1}};
    prim.indices = 2;
    prim.material = static_cast<int>(m.materials.size()) - 1;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(prim);
    m.meshes.push_back(mesh);
    return static_cast<int>(m.meshes.size()) - 1;
  };
  const int paint = material("paint", {0.2, 0.4, 0.6, 1}, 0.0, 1.0);
  const int chrome = material("chrome", {1, 1, 1, 1}, 1.0, 0.0);
  const int glass = material("glass", {0.9, 0.95, 1, 1}, 0.0, 0.0);
  m.materials[glass].extensions["KHR_materials_transmission"] =
      tinygltf::Value(tinygltf::Value::Object{{"transmissionFactor", tinygltf::Value(1.0)}});
  m.materials[glass].extensions["KHR_materials_ior"] =
      tinygltf::Value(tinygltf::Value::Object{{"ior", tinygltf::Value(1.33)}});
  const int lamp = material("lamp", {1, 1, 1, 1}, 0.0, 1.0);
  m.materials[lamp].emissiveFactor = {1.0, 0.5, 0.25};
  m.materials[lamp].extensions["KHR_materials_emissive_strength"] =
      tinygltf::Value(tinygltf::Value::Object{{"emissiveStrength", tinygltf::Value(4.0)}});
  m.extensionsUsed = {"KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength",
                      "KHR_lights_punctual"};

  auto node = [&](int mesh, std::vector<double> t, std::vector<double> r, std::vector<double> s) {
    tinygltf::Node n;
    n.mesh = mesh;
    n.translation = t;
    n.rotation = r;
    n.scale = s;
    m.nodes.push_back(n);
    return static_cast<int>(m.nodes.size()) - 1;
  };
  const double h = std::sqrt(0.5);
  // A parent scaled by 2 and moved by x + 10; the paint quad under it rotated 90 degrees
  // about x (so it lies in y = 0 facing -y... +y after the rotation's sign: checked below).
  const int parent = node(-1, {10, 0, 0}, {}, {2, 2, 2});
  const int floor = node(paint, {}, {-h, 0, 0, h}, {});
  m.nodes[parent].children = {floor};
  const int mirror = node(chrome, {0, 0, -5}, {}, {});
  const int pane = node(glass, {0, 0, -3}, {}, {});
  const int light = node(lamp, {0, 4, 0}, {h, 0, 0, h}, {});  // rotated to face -y
  // Camera at (0, 1, 8) looking down -z; lights: a point at (1, 5, 1), a sun along -y.
  tinygltf::Camera cam;
  cam.type = "perspective";
  cam.perspective.yfov = 0.5;
  cam.perspective.aspectRatio = 2.0;
  cam.perspective.znear = 0.1;
  m.cameras.push_back(cam);
  const int camera = node(-1, {0, 1, 8}, {}, {});
  m.nodes[camera].camera = 0;
  tinygltf::Light point;
  point.type = "point";
  point.color = {1, 0.5, 0.5};
  point.intensity = 30;
  tinygltf::Light sun;
  sun.type = "directional";
  sun.intensity = 2;
  m.lights = {point, sun};
  const int pointNode = node(-1, {1, 5, 1}, {}, {});
  const int sunNode = node(-1, {}, {-h, 0, 0, h}, {});  // -z turned to -y
  m.nodes[pointNode].extensions["KHR_lights_punctual"] =
      tinygltf::Value(tinygltf::Value::Object{{"light", tinygltf::Value(0)}});
  m.nodes[sunNode].extensions["KHR_lights_punctual"] =
      tinygltf::Value(tinygltf::Value::Object{{"light", tinygltf::Value(1)}});
  tinygltf::Scene scene;
  scene.nodes = {parent, mirror, pane, light, camera, pointNode, sunNode};
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  return m;
}

inline void writeGltf(const tinygltf::Model& m, const std::filesystem::path& file, bool binary) {
  tinygltf::TinyGLTF writer;
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&m, file.string(), true, true, false, binary));
}

inline void expectNear(const Vec3& a, const Vec3& b, float tol, const char* what) {
  EXPECT_NEAR(glm::length(a - b), 0.0f, tol) << what << ": (" << a.x << ", " << a.y << ", " << a.z << ")";
}

}  // namespace penumbra
