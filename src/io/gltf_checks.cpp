// glTF model checks after tinygltf has parsed the file and before the loader reads
// any accessor: bounds in checked arithmetic, the node forest, transforms, lights,
// material extensions, cameras, primitive modes, and the memory the meshes need.
#include "io/gltf_checks.h"
#include "core/byte_size.h"

#include "io/model_import.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <cstdio>

namespace penumbra {

namespace {

std::string at(const char* array, size_t i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

// a + b and a * b, false on overflow: every size and offset from the file goes
// through these, so no sum can wrap around and pass a bounds check.
bool add(uint64_t a, uint64_t b, uint64_t& out) { return !__builtin_add_overflow(a, b, &out); }
bool mul(uint64_t a, uint64_t b, uint64_t& out) { return !__builtin_mul_overflow(a, b, &out); }

bool finite(const std::vector<double>& v) {
  for (double x : v) if (!std::isfinite(x)) return false;
  return true;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// What a JSON value is, for a message: "\"0\"", "0.5", "an array".
std::string shown(const tinygltf::Value& v) {
  if (v.IsString()) return "\"" + v.Get<std::string>() + "\"";
  if (v.IsNumber() || v.IsInt()) return num(v.GetNumberAsDouble());
  return v.IsArray() ? "an array" : v.IsObject() ? "an object" : v.IsBool() ? "a boolean" : "null";
}

// The camera and light a node names exist, checked with the nodes, before any mesh
// is read: a wrong index is refused before the heavy work, not after it.
void checkNodeRefs(const tinygltf::Model& m, const tinygltf::Node& n, const std::string& where, const std::string& path) {
  if (n.camera >= 0 && static_cast<size_t>(n.camera) >= m.cameras.size()) {
    gltfFail(path, where + ".camera", "camera " + std::to_string(n.camera) + " does not exist");
  }
  auto ext = n.extensions.find("KHR_lights_punctual");
  if (ext == n.extensions.end()) return;
  const std::string key = where + ".extensions.KHR_lights_punctual";
  if (!ext->second.IsObject() || !ext->second.Has("light")) gltfFail(path, key, "must be an object with a \"light\" index");
  // tinygltf would read a string or a fraction as some integer: "0" was light 0.
  const tinygltf::Value& v = ext->second.Get("light");
  const double index = v.IsInt() || v.IsNumber() ? v.GetNumberAsDouble() : NAN;
  if (!(index == std::floor(index))) gltfFail(path, key + ".light", "must be the integer index of a light, got " + shown(v));
  if (index < 0.0 || index >= static_cast<double>(m.lights.size())) {
    gltfFail(path, key + ".light", "light " + num(index) + " does not exist (the file has " +
                                       std::to_string(m.lights.size()) + " in extensions.KHR_lights_punctual.lights)");
  }
}

void checkNode(const tinygltf::Model& m, size_t i, const std::string& path) {
  const tinygltf::Node& n = m.nodes[i];
  const std::string where = at("nodes", i);
  if (!n.matrix.empty() && n.matrix.size() != 16) {
    gltfFail(path, where + ".matrix", "must have 16 numbers, got " + std::to_string(n.matrix.size()));
  }
  if (!n.translation.empty() && n.translation.size() != 3) gltfFail(path, where + ".translation", "must have 3 numbers");
  if (!n.rotation.empty() && n.rotation.size() != 4) gltfFail(path, where + ".rotation", "must have 4 numbers");
  if (!n.scale.empty() && n.scale.size() != 3) gltfFail(path, where + ".scale", "must have 3 numbers");
  if (!finite(n.matrix) || !finite(n.translation) || !finite(n.rotation) || !finite(n.scale)) {
    gltfFail(path, where, "its transform holds a number that is not finite");
  }
  if (n.rotation.size() == 4) {
    const double len = std::sqrt(n.rotation[0] * n.rotation[0] + n.rotation[1] * n.rotation[1] +
                                 n.rotation[2] * n.rotation[2] + n.rotation[3] * n.rotation[3]);
    // The spec asks for a unit quaternion; rounding is forgiven, zero has no rotation.
    if (!(len > 1e-6)) gltfFail(path, where + ".rotation", "is a zero quaternion (no rotation is defined)");
  }
  // A singular transform flattens what it holds: normals by its inverse transpose
  // come out infinite. Columns nearly parallel count too (relative determinant).
  const glm::dmat3 linear(nodeMatrix(n));
  const double scale = glm::length(linear[0]) * glm::length(linear[1]) * glm::length(linear[2]);
  const double det = glm::determinant(linear);
  const std::string key = where + (n.matrix.empty() ? std::string() : ".matrix");
  if (!std::isfinite(det) || !std::isfinite(scale)) gltfFail(path, key, "the node's transform scales beyond double range");
  if (!(std::fabs(det) > 1e-9 * scale) || !(scale > 1e-300)) {
    gltfFail(path, key, "the node's transform is singular (a zero scale, or axes that coincide)");
  }
  checkNodeRefs(m, n, where, path);
}

// Each node at most one parent, no cycles, the scene's nodes roots: then every node
// is reached once and instancing cannot grow with the depth of the tree.
std::vector<int> forestRoots(const tinygltf::Model& m, const std::string& path) {
  const size_t n = m.nodes.size();
  std::vector<int> parent(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const std::vector<int>& children = m.nodes[i].children;
    for (size_t k = 0; k < children.size(); ++k) {
      const int c = children[k];
      const std::string where = at("nodes", i) + ".children[" + std::to_string(k) + "]";
      if (c < 0 || static_cast<size_t>(c) >= n) gltfFail(path, where, "node " + std::to_string(c) + " does not exist");
      if (static_cast<size_t>(c) == i) gltfFail(path, where, "a node cannot be its own child");
      if (parent[c] >= 0) {
        gltfFail(path, where, "node " + std::to_string(c) + " is already a child of node " + std::to_string(parent[c]) +
                                  " (glTF nodes form trees: one parent each)");
      }
      parent[c] = static_cast<int>(i);
    }
  }
  // With one parent each, a cycle is a parent chain that comes back to itself.
  std::vector<int> seen(n, -1);  // the walk that first reached a node
  for (size_t start = 0; start < n; ++start) {
    size_t v = start;
    while (seen[v] < 0) {
      seen[v] = static_cast<int>(start);
      if (parent[v] < 0) break;
      v = static_cast<size_t>(parent[v]);
      if (seen[v] == static_cast<int>(start)) {
        gltfFail(path, at("nodes", v) + ".children", "the node graph has a cycle through node " + std::to_string(v));
      }
    }
  }
  std::vector<int> roots;
  if (m.scenes.empty()) {
    for (size_t i = 0; i < n; ++i) if (parent[i] < 0) roots.push_back(static_cast<int>(i));
    return roots;
  }
  const bool given = m.defaultScene >= 0 && static_cast<size_t>(m.defaultScene) < m.scenes.size();
  if (m.defaultScene >= 0 && !given) gltfFail(path, "scene", "scene " + std::to_string(m.defaultScene) + " does not exist");
  const size_t s = given ? static_cast<size_t>(m.defaultScene) : 0;
  std::vector<bool> listed(n, false);
  for (size_t k = 0; k < m.scenes[s].nodes.size(); ++k) {
    const int r = m.scenes[s].nodes[k];
    const std::string where = at("scenes", s) + ".nodes[" + std::to_string(k) + "]";
    if (r < 0 || static_cast<size_t>(r) >= n) gltfFail(path, where, "node " + std::to_string(r) + " does not exist");
    if (parent[r] >= 0) gltfFail(path, where, "node " + std::to_string(r) + " is a child of node " + std::to_string(parent[r]) + ", not a root");
    if (listed[r]) gltfFail(path, where, "node " + std::to_string(r) + " is listed twice");
    listed[r] = true;
    roots.push_back(r);
  }
  return roots;
}

void checkPrimitive(const tinygltf::Model& m, const tinygltf::Primitive& p, const std::string& where,
                    const std::string& path, std::vector<std::string>& warnings) {
  const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) {
    warnings.push_back(where + ".mode: points and lines are not rendered; skipped");
    return;
  }
  if (mode > TINYGLTF_MODE_TRIANGLE_FAN) gltfFail(path, where + ".mode", "must be 0..6, got " + std::to_string(mode));
  if (p.material >= static_cast<int>(m.materials.size())) {
    gltfFail(path, where + ".material", "material " + std::to_string(p.material) + " does not exist");
  }
  auto pos = p.attributes.find("POSITION");
  if (pos == p.attributes.end()) gltfFail(path, where + ".attributes", "has no POSITION");
  const AccessorSpan positions = accessorSpan(m, pos->second, where + ".attributes.POSITION", path);
  if (positions.components != 3 || positions.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    gltfFail(path, at("accessors", pos->second), "POSITION must be a VEC3 of FLOAT");
  }
  // Without a buffer view every position is zero: nothing but degenerate
  // triangles, at any cost in memory the count asks for.
  if (positions.data == nullptr) gltfFail(path, at("accessors", pos->second), "POSITION has no bufferView (all zeros)");
  for (const auto& [name, index] : p.attributes) {
    if (name != "NORMAL" && name != "TEXCOORD_0" && name != "COLOR_0") continue;
    const AccessorSpan a = accessorSpan(m, index, where + ".attributes." + name, path);
    const bool normal = name == "NORMAL";
    if (name == "COLOR_0") {
      // The spec's colour accessors: floats, or unsigned integers read as 0..1.
      const bool unorm = a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                          a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
      if ((a.components != 3 && a.components != 4) || (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !unorm)) {
        gltfFail(path, at("accessors", index),
                 "COLOR_0 must be a VEC3 or VEC4 of FLOAT, or of normalized UNSIGNED_BYTE or UNSIGNED_SHORT");
      }
    } else if (a.components != (normal ? 3 : 2)) {
      gltfFail(path, at("accessors", index), name + " must be a " + (normal ? "VEC3" : "VEC2"));
    }
    if (normal && a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) gltfFail(path, at("accessors", index), "NORMAL must be FLOAT");
    if (a.count != positions.count) {
      gltfFail(path, where + ".attributes." + name, "has " + std::to_string(a.count) + " elements but POSITION has " +
                                                        std::to_string(positions.count) + " (the spec wants equal counts)");
    }
  }
  if (p.indices >= 0) {
    const AccessorSpan idx = accessorSpan(m, p.indices, where + ".indices", path);
    const bool unsignedInt = idx.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                             idx.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                             idx.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    if (idx.components != 1 || !unsignedInt || idx.normalized || idx.data == nullptr) {
      gltfFail(path, at("accessors", p.indices),
               "indices must be a SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT, not normalized, in a buffer view");
    }
  }
}

void checkCameraValues(const tinygltf::Camera& c, const std::string& where, const std::string& path,
                       std::vector<std::string>& warnings) {
  if (c.type == "orthographic") {  // half width and height; their pixel step: addCamera, once placed
    const double x = c.orthographic.xmag, y = c.orthographic.ymag;
    if (!(x > 0.0 && y > 0.0 && x / y >= 0.01 && x / y <= 100.0)) {
      gltfFail(path, where + ".orthographic", "xmag and ymag must be positive, their ratio 0.01..100");
    }
    return;
  }
  if (c.type != "perspective") {
    warnings.push_back(where + ": only perspective and orthographic cameras are used; \"" + c.type + "\" skipped");
    return;
  }
  const double yfov = c.perspective.yfov;
  if (!(yfov > 1e-6 && yfov < 3.14159)) {
    gltfFail(path, where + ".perspective.yfov", "must be between 0 and pi radians (both excluded), got " + num(yfov));
  }
  const double aspect = c.perspective.aspectRatio;
  // Beyond 1:100 one side of the image would be a few pixels wide.
  if (aspect != 0.0 && !(aspect >= 0.01 && aspect <= 100.0)) {
    gltfFail(path, where + ".perspective.aspectRatio", "must be 0.01..100 (width / height), got " + num(aspect));
  }
}

}  // namespace

void gltfFail(const std::string& path, const std::string& where, const std::string& problem) {
  throw ModelError("glTF file " + path + ": " + where + ": " + problem);
}

AccessorSpan accessorSpan(const tinygltf::Model& m, int index, const std::string& ref, const std::string& path) {
  if (index < 0 || static_cast<size_t>(index) >= m.accessors.size()) {
    gltfFail(path, ref, "accessor " + std::to_string(index) + " does not exist");
  }
  const tinygltf::Accessor& a = m.accessors[index];
  const std::string where = at("accessors", index);
  if (a.sparse.isSparse) gltfFail(path, where + ".sparse", "sparse accessors are not supported");
  AccessorSpan s;
  s.components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(a.type));
  s.componentSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
  s.componentType = a.componentType;
  s.normalized = a.normalized;
  s.count = a.count;
  if (s.components <= 0) gltfFail(path, where + ".type", "unknown element type");
  if (s.componentSize <= 0 || a.componentType == TINYGLTF_COMPONENT_TYPE_INT || a.componentType == TINYGLTF_COMPONENT_TYPE_DOUBLE) {
    gltfFail(path, where + ".componentType", "is not one of glTF's component types");
  }
  if (s.count == 0) gltfFail(path, where + ".count", "must be at least 1");
  const uint64_t element = static_cast<uint64_t>(s.components) * static_cast<uint64_t>(s.componentSize);
  s.stride = element;
  if (a.bufferView < 0) return s;  // all zeros, as the spec says
  if (static_cast<size_t>(a.bufferView) >= m.bufferViews.size()) {
    gltfFail(path, where + ".bufferView", "buffer view " + std::to_string(a.bufferView) + " does not exist");
  }
  const tinygltf::BufferView& view = m.bufferViews[a.bufferView];
  const std::string viewWhere = at("bufferViews", a.bufferView);
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= m.buffers.size()) {
    gltfFail(path, viewWhere + ".buffer", "buffer " + std::to_string(view.buffer) + " does not exist");
  }
  const std::vector<unsigned char>& data = m.buffers[view.buffer].data;
  uint64_t viewEnd = 0;
  if (!add(view.byteOffset, view.byteLength, viewEnd) || viewEnd > data.size()) {
    gltfFail(path, viewWhere, "byteOffset + byteLength reaches past the end of its buffer (" + std::to_string(data.size()) + " bytes)");
  }
  if (view.byteStride != 0) {
    if (view.byteStride < element || view.byteStride > 252) {
      gltfFail(path, viewWhere + ".byteStride", "must be " + std::to_string(element) + "..252 for " + where + "'s " +
                                                    std::to_string(element) + "-byte elements, got " + std::to_string(view.byteStride));
    }
    s.stride = view.byteStride;
  }
  // The last element ends at byteOffset + stride * (count - 1) + element.
  uint64_t span = 0, end = 0;
  if (!mul(s.stride, s.count - 1, span) || !add(span, element, end) || !add(end, a.byteOffset, end) || end > view.byteLength) {
    gltfFail(path, where + ".count", std::to_string(s.count) + " elements of " + std::to_string(element) + " bytes, " +
                                         std::to_string(s.stride) + " apart from byte " + std::to_string(a.byteOffset) +
                                         ", reaches past the end of its buffer view (" + std::to_string(view.byteLength) + " bytes)");
  }
  s.data = data.data() + view.byteOffset + a.byteOffset;
  return s;
}

glm::dmat4 nodeMatrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    glm::dmat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[4 * c + r];  // column-major, as glm
    return m;
  }
  glm::dmat4 m(1.0);
  if (n.translation.size() == 3) m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4) {
    const glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    const double len = glm::length(q);
    if (len > 0.0) m *= glm::mat4_cast(q / len);
  }
  if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

std::vector<int> checkGltfModel(const tinygltf::Model& m, const std::string& path, std::vector<std::string>& warnings) {
  for (size_t i = 0; i < m.nodes.size(); ++i) checkNode(m, i, path);
  std::vector<int> roots = forestRoots(m, path);
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    for (size_t j = 0; j < m.meshes[i].primitives.size(); ++j) {
      checkPrimitive(m, m.meshes[i].primitives[j], at("meshes", i) + ".primitives[" + std::to_string(j) + "]", path, warnings);
    }
  }
  for (size_t i = 0; i < m.lights.size(); ++i) {
    const std::string& type = m.lights[i].type;
    if (type != "directional" && type != "point" && type != "spot") {
      gltfFail(path, "extensions.KHR_lights_punctual." + at("lights", i) + ".type",
               "must be \"directional\", \"point\" or \"spot\", got \"" + type + "\"");
    }
  }
  for (size_t i = 0; i < m.materials.size(); ++i) checkGltfMaterial(m.materials[i], at("materials", i), path);
  for (size_t i = 0; i < m.cameras.size(); ++i) checkCameraValues(m.cameras[i], at("cameras", i), path, warnings);
  return roots;
}

void checkGltfBudget(const tinygltf::Model& m, const std::vector<int>& roots, const std::string& path,
                     const LoadLimits& limits) {
  if (limits.maxBytes == 0) return;
  double bytes = 0.0;
  for (const tinygltf::Buffer& b : m.buffers) bytes += static_cast<double>(b.data.size());
  for (const tinygltf::Image& im : m.images) bytes += static_cast<double>(im.image.size());
  // Per vertex: position, normal and uv read as doubles, then kept as floats, and
  // an RGBA colour where the primitive has COLOR_0; per index: read as a double,
  // kept as uint32, and a third of a triangle.
  std::vector<int> stack(roots.begin(), roots.end());
  while (!stack.empty()) {  // the forest is checked: each node once
    const tinygltf::Node& n = m.nodes[stack.back()];
    stack.pop_back();
    stack.insert(stack.end(), n.children.begin(), n.children.end());
    if (n.mesh < 0 || static_cast<size_t>(n.mesh) >= m.meshes.size()) continue;
    for (const tinygltf::Primitive& p : m.meshes[n.mesh].primitives) {
      auto pos = p.attributes.find("POSITION");
      if (pos == p.attributes.end() || pos->second < 0 || static_cast<size_t>(pos->second) >= m.accessors.size()) continue;
      const double vertices = static_cast<double>(m.accessors[pos->second].count);
      const double indices = p.indices >= 0 && static_cast<size_t>(p.indices) < m.accessors.size()
                                 ? static_cast<double>(m.accessors[p.indices].count) : vertices;
      const double colour = p.attributes.count("COLOR_0") ? 16.0 : 0.0;
      bytes += vertices * (64.0 + 32.0 + colour) + indices * 16.0;
    }
  }
  if (bytes > static_cast<double>(limits.maxBytes)) {
    throw ModelError("glTF file " + path + ": needs ~" + formatBytes(bytes) + " for its meshes but " + limits.budgetName +
                     " is " + formatBytes(static_cast<double>(limits.maxBytes)));
  }
}

}  // namespace penumbra
