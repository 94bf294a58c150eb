// glTF models built in memory with tinygltf and written by its own writer, for the
// tests of glTF scenes and the load benchmark: triangle meshes, boxes, spheres, cameras and
// nodes of scene 0, over support/gltf_writer.h's accessors.
#pragma once
#include "gltf_writer.h"  // beside this file: found from tests and bench alike
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra::testing {

// A glTF 2.0 model with one empty buffer and an empty default scene.
inline tinygltf::Model emptyGltf() {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.buffers.resize(1);
  m.scenes.resize(1);
  m.defaultScene = 0;
  return m;
}

// Appends `values` to buffer 0 as one view and one accessor of `count` elements
// (support/gltf_writer.h); returns the accessor. Positions get the min / max glTF asks for.
template <typename T>
int appendAccessor(tinygltf::Model& m, const std::vector<T>& values, int componentType, int type, size_t count) {
  const int index = addAccessor(m, values.data(), values.size() * sizeof(T), componentType, type, count);
  tinygltf::Accessor& a = m.accessors[index];
  if (type == TINYGLTF_TYPE_VEC3 && componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && count > 0) {
    a.minValues = a.maxValues = {double(values[0]), double(values[1]), double(values[2])};
    for (size_t i = 0; i < count; ++i) {
      for (int k = 0; k < 3; ++k) {
        a.minValues[k] = std::min(a.minValues[k], double(values[3 * i + k]));
        a.maxValues[k] = std::max(a.maxValues[k], double(values[3 * i + k]));
      }
    }
  }
  return index;
}

// A mesh of one triangle primitive: float xyz positions, optional normals and uvs,
// 32-bit indices; `material` -1 = none. Returns the mesh.
inline int addTriangleMesh(tinygltf::Model& m, const std::vector<float>& positions, const std::vector<float>& normals,
                           const std::vector<float>& uvs, const std::vector<uint32_t>& indices, int material = -1) {
  const size_t vertices = positions.size() / 3;
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] =
      appendAccessor(m, positions, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, vertices);
  if (!normals.empty()) {
    prim.attributes["NORMAL"] = appendAccessor(m, normals, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, vertices);
  }
  if (!uvs.empty()) {
    prim.attributes["TEXCOORD_0"] = appendAccessor(m, uvs, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, vertices);
  }
  prim.indices = appendAccessor(m, indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, indices.size());
  prim.material = material;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  return static_cast<int>(m.meshes.size()) - 1;
}

// The box [lo, hi] as 12 triangles facing out (8 shared corners, flat-shaded).
inline int addBoxMesh(tinygltf::Model& m, const float lo[3], const float hi[3], int material = -1) {
  std::vector<float> p;
  for (int k = 0; k < 8; ++k) {
    p.insert(p.end(), {(k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2]});
  }
  const std::vector<uint32_t> idx = {0, 2, 1, 1, 2, 3,  4, 5, 6, 5, 7, 6,  0, 1, 4, 1, 5, 4,
                                     2, 6, 3, 3, 6, 7,  0, 4, 2, 2, 4, 6,  1, 3, 5, 3, 7, 5};
  return addTriangleMesh(m, p, {}, {}, idx, material);
}

// A UV sphere about `centre`: `rings` bands of `segments` quads, vertices on the
// sphere of `radius`, triangles facing out.
inline int addSphereMesh(tinygltf::Model& m, const float centre[3], float radius, int segments = 64, int rings = 32) {
  std::vector<float> p;
  for (int i = 0; i <= rings; ++i) {
    const double theta = 3.14159265358979323846 * i / rings;
    for (int j = 0; j <= segments; ++j) {
      const double phi = 2.0 * 3.14159265358979323846 * j / segments;
      p.insert(p.end(), {float(centre[0] + radius * std::sin(theta) * std::cos(phi)),
                         float(centre[1] + radius * std::cos(theta)),
                         float(centre[2] - radius * std::sin(theta) * std::sin(phi))});
    }
  }
  std::vector<uint32_t> idx;
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const uint32_t a = i * (segments + 1) + j, b = a + segments + 1;
      idx.insert(idx.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  }
  return addTriangleMesh(m, p, {}, {}, idx);
}

// A node in scene 0 holding `mesh` (-1: none) at `translation`; returns the node.
inline int addSceneNode(tinygltf::Model& m, int mesh, const std::vector<double>& translation = {}) {
  tinygltf::Node n;
  n.mesh = mesh;
  n.translation = translation;
  m.nodes.push_back(n);
  const int index = static_cast<int>(m.nodes.size()) - 1;
  m.scenes[0].nodes.push_back(index);
  return index;
}

// A perspective camera of `yfov` radians on a new node of scene 0 at `translation`;
// returns the node (to rotate it).
inline int addCameraNode(tinygltf::Model& m, double yfov, const std::vector<double>& translation) {
  tinygltf::Camera cam;
  cam.type = "perspective";
  cam.perspective.yfov = yfov;
  cam.perspective.znear = 0.1;
  m.cameras.push_back(cam);
  const int node = addSceneNode(m, -1, translation);
  m.nodes[node].camera = static_cast<int>(m.cameras.size()) - 1;
  return node;
}

// Writes `m` with its buffers embedded: a .glb when `binary`, else a .gltf.
inline bool writeGltfFile(const tinygltf::Model& m, const std::string& file, bool binary) {
  tinygltf::TinyGLTF writer;
  return writer.WriteGltfSceneToFile(&m, file, true, true, false, binary);
}

// A box [0, 2] x [0, 1] x [0, 1] without camera, light or material, as a .glb.
inline bool writeBoxGlb(const std::string& file) {
  tinygltf::Model m = emptyGltf();
  const float lo[3] = {0, 0, 0}, hi[3] = {2, 1, 1};
  addSceneNode(m, addBoxMesh(m, lo, hi));
  return writeGltfFile(m, file, true);
}

}  // namespace penumbra::testing
