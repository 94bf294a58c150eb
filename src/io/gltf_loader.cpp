// glTF loading: accessors read with their strides and bounds checked, the node tree
// walked with its transforms, triangle primitives as meshes, the camera and lights.
#include "io/gltf_loader.h"

#include "io/gltf_materials.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace penumbra {

namespace {

using glm::dmat4;

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw ModelError("glTF file " + path + ": " + problem);
}

// Accessor `index` as doubles, `width` components per element (normalised integers
// scaled to [0, 1]); every byte it names must lie inside its buffer.
std::vector<double> readAccessor(const tinygltf::Model& m, int index, int width, const std::string& path) {
  if (index < 0 || static_cast<size_t>(index) >= m.accessors.size()) fail(path, "accessor " + std::to_string(index) + " does not exist");
  const tinygltf::Accessor& a = m.accessors[index];
  const std::string what = "accessor " + std::to_string(index);
  if (a.sparse.isSparse) fail(path, what + " is sparse (not supported)");
  if (tinygltf::GetNumComponentsInType(a.type) != width) fail(path, what + " has the wrong element type");
  const int size = tinygltf::GetComponentSizeInBytes(a.componentType);
  if (size <= 0) fail(path, what + " has an unknown component type");
  std::vector<double> out(a.count * width, 0.0);
  if (a.bufferView < 0) return out;  // all zeros, as the spec says
  if (static_cast<size_t>(a.bufferView) >= m.bufferViews.size()) fail(path, what + ": no such buffer view");
  const tinygltf::BufferView& view = m.bufferViews[a.bufferView];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= m.buffers.size()) fail(path, what + ": no such buffer");
  const std::vector<unsigned char>& data = m.buffers[view.buffer].data;
  const size_t element = static_cast<size_t>(size) * width;
  const size_t stride = view.byteStride > 0 ? view.byteStride : element;
  const size_t start = view.byteOffset + a.byteOffset;
  if (a.count > 0 && (start + stride * (a.count - 1) + element > view.byteOffset + view.byteLength ||
                      view.byteOffset + view.byteLength > data.size())) {
    fail(path, what + " reaches past the end of its buffer");
  }
  for (size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = data.data() + start + i * stride;
    for (int c = 0; c < width; ++c, p += size) {
      double v = 0.0;
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); v = f; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: v = *p / (a.normalized ? 255.0 : 1.0); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t s; std::memcpy(&s, p, 2); v = s / (a.normalized ? 65535.0 : 1.0); break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t u; std::memcpy(&u, p, 4); v = u; break; }
        default: fail(path, what + " has a component type penumbra does not read");
      }
      if (!std::isfinite(v) || std::fabs(v) > 3.4e38) fail(path, what + " holds a value that is not a finite float");
      out[i * width + c] = v;
    }
  }
  return out;
}

dmat4 localMatrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    dmat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[4 * c + r];  // column-major, as glm
    return m;
  }
  dmat4 m(1.0);
  if (n.translation.size() == 3) m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4) m *= glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

void addPrimitive(const tinygltf::Model& m, const tinygltf::Primitive& prim, const dmat4& world,
                  const std::string& name, const std::string& path, LoadedModel& out) {
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) return;
  auto attr = prim.attributes.find("POSITION");
  if (attr == prim.attributes.end()) fail(path, "mesh \"" + name + "\" has a primitive without POSITION");
  const std::vector<double> pos = readAccessor(m, attr->second, 3, path);
  const size_t count = pos.size() / 3;
  TriangleMesh mesh;
  mesh.name = name;
  mesh.material = prim.material;
  const glm::dmat3 linear(world), normalMatrix = glm::transpose(glm::inverse(linear));
  for (size_t i = 0; i < count; ++i) {
    mesh.positions.push_back(Vec3(world * glm::dvec4(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2], 1.0)));
  }
  if ((attr = prim.attributes.find("NORMAL")) != prim.attributes.end()) {
    const std::vector<double> nrm = readAccessor(m, attr->second, 3, path);
    for (size_t i = 0; i < count && 3 * i + 2 < nrm.size(); ++i) {
      const glm::dvec3 n = normalMatrix * glm::dvec3(nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]);
      const double len = glm::length(n);
      mesh.normals.push_back(len > 0.0 ? Vec3(n / len) : Vec3(0.0f, 0.0f, 1.0f));
    }
    if (mesh.normals.size() != count) mesh.normals.clear();
  }
  if ((attr = prim.attributes.find("TEXCOORD_0")) != prim.attributes.end()) {
    const std::vector<double> uv = readAccessor(m, attr->second, 2, path);
    for (size_t i = 0; i < count && 2 * i + 1 < uv.size(); ++i) mesh.uvs.emplace_back(uv[2 * i], uv[2 * i + 1]);
    if (mesh.uvs.size() != count) mesh.uvs.clear();
  }
  std::vector<uint32_t> idx;
  if (prim.indices >= 0) {
    for (double v : readAccessor(m, prim.indices, 1, path)) {
      if (v >= static_cast<double>(count)) fail(path, "mesh \"" + name + "\" indexes a vertex it does not have");
      idx.push_back(static_cast<uint32_t>(v));
    }
  } else {
    for (size_t i = 0; i < count; ++i) idx.push_back(static_cast<uint32_t>(i));
  }
  const bool flip = glm::determinant(linear) < 0.0;  // a mirroring node turns faces inside out
  auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    mesh.triangles.push_back(flip ? std::array<uint32_t, 3>{a, c, b} : std::array<uint32_t, 3>{a, b, c});
  };
  for (size_t i = 0; i + 2 < idx.size();) {
    if (mode == TINYGLTF_MODE_TRIANGLES) { add(idx[i], idx[i + 1], idx[i + 2]); i += 3; continue; }
    if (mode == TINYGLTF_MODE_TRIANGLE_FAN) add(idx[0], idx[i + 1], idx[i + 2]);
    else if (i % 2 == 0) add(idx[i], idx[i + 1], idx[i + 2]);
    else add(idx[i + 1], idx[i], idx[i + 2]);
    ++i;
  }
  if (!mesh.triangles.empty()) out.meshes.push_back(std::move(mesh));
}

void addLight(const tinygltf::Model& m, int index, const dmat4& world, const std::string& path, LoadedModel& out) {
  if (index < 0 || static_cast<size_t>(index) >= m.lights.size()) fail(path, "light " + std::to_string(index) + " does not exist");
  const tinygltf::Light& g = m.lights[index];
  Light light;
  light.color = g.color.size() >= 3 ? Color(float(g.color[0]), float(g.color[1]), float(g.color[2])) : Color(1.0f);
  light.intensity = static_cast<float>(g.intensity);
  if (!(light.intensity >= 0.0f) || !std::isfinite(light.intensity) || !isFinite(light.color) ||
      std::min({light.color.r, light.color.g, light.color.b}) < 0.0f) {
    fail(path, "light " + std::to_string(index) + " has a negative or non-finite colour or intensity");
  }
  if (g.type == "directional") {
    light.type = LightType::Directional;
    const glm::dvec3 d = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    if (!(glm::length(d) > 0.0)) fail(path, "light " + std::to_string(index) + " has no direction");
    light.direction = Vec3(glm::normalize(d));
  } else {
    light.type = LightType::Point;  // point, and spot without its cone
    light.position = Vec3(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  }
  out.lights.push_back(light);
}

void addCamera(const tinygltf::Model& m, int index, const dmat4& world, LoadedModel& out) {
  if (out.camera || index < 0 || static_cast<size_t>(index) >= m.cameras.size()) return;
  const tinygltf::Camera& g = m.cameras[index];
  if (g.type != "perspective") return;  // penumbra's camera is a pinhole
  Camera c;
  c.position = Vec3(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  // One unit ahead, or more far from the origin, so look_at stays apart in float.
  const glm::dvec3 eye(c.position), ahead = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
  const double reach = std::max({1.0, std::fabs(eye.x), std::fabs(eye.y), std::fabs(eye.z)});
  c.lookAt = Vec3(eye + glm::normalize(ahead) * reach);
  c.up = Vec3(glm::normalize(glm::dmat3(world) * glm::dvec3(0.0, 1.0, 0.0)));
  c.fovY = static_cast<float>(g.perspective.yfov * 180.0 / 3.14159265358979323846);
  if (g.perspective.aspectRatio > 0.0) {
    out.aspect = g.perspective.aspectRatio;
    c.height = std::clamp(static_cast<int>(std::lround(c.width / g.perspective.aspectRatio)), 1, 16384);
  }
  out.camera = c;
}

void walk(const tinygltf::Model& m, int node, const dmat4& parent, int depth, const std::string& path, LoadedModel& out) {
  if (node < 0 || static_cast<size_t>(node) >= m.nodes.size()) fail(path, "node " + std::to_string(node) + " does not exist");
  if (depth > 256) fail(path, "the node tree is deeper than 256 levels (a cycle?)");
  const tinygltf::Node& n = m.nodes[node];
  const dmat4 world = parent * localMatrix(n);
  if (n.mesh >= 0) {
    if (static_cast<size_t>(n.mesh) >= m.meshes.size()) fail(path, "mesh " + std::to_string(n.mesh) + " does not exist");
    const tinygltf::Mesh& mesh = m.meshes[n.mesh];
    const std::string name = mesh.name.empty() ? "mesh " + std::to_string(n.mesh) : mesh.name;
    for (const tinygltf::Primitive& prim : mesh.primitives) addPrimitive(m, prim, world, name, path, out);
  }
  if (n.camera >= 0) addCamera(m, n.camera, world, out);
  auto ext = n.extensions.find("KHR_lights_punctual");
  if (ext != n.extensions.end() && ext->second.Has("light")) {
    addLight(m, ext->second.Get("light").GetNumberAsInt(), world, path, out);
  }
  for (int child : n.children) walk(m, child, world, depth + 1, path, out);
}

}  // namespace

LoadedModel loadGltfModel(const std::string& path, const LoadLimits&) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keepEncodedImage, nullptr);
  std::string err, warn;
  const bool binary = path.size() >= 4 && (path.substr(path.size() - 4) == ".glb" || path.substr(path.size() - 4) == ".GLB");
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                         : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) {
    std::string line = err.substr(0, err.find('\n'));
    fail(path, "cannot load: " + (line.empty() ? std::string("unknown error") : line));
  }
  LoadedModel out;
  out.file = path;
  out.warning = warn.substr(0, warn.find('\n'));
  out.materials = gltfMaterials(model, path);
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const int s = model.defaultScene >= 0 && static_cast<size_t>(model.defaultScene) < model.scenes.size() ? model.defaultScene : 0;
    roots = model.scenes[s].nodes;
  } else {
    std::vector<bool> child(model.nodes.size(), false);
    for (const tinygltf::Node& n : model.nodes)
      for (int c : n.children) if (c >= 0 && static_cast<size_t>(c) < child.size()) child[c] = true;
    for (size_t i = 0; i < model.nodes.size(); ++i) if (!child[i]) roots.push_back(static_cast<int>(i));
  }
  for (int r : roots) walk(model, r, dmat4(1.0), 0, path, out);
  for (TriangleMesh& mesh : out.meshes) {
    if (mesh.material >= static_cast<int>(out.materials.size())) fail(path, "a primitive names a material that does not exist");
  }
  if (out.meshes.empty()) fail(path, "contains no triangles");
  return out;
}

}  // namespace penumbra
