// glTF loading: the file checked (gltf_document, gltf_checks) before and after
// tinygltf parses it, then the node forest walked with its transforms, triangle
// primitives as meshes, the camera and lights.
#include "io/gltf_loader.h"
#include "io/float_checks.h"

#include "io/gltf_attributes.h"
#include "io/gltf_cameras.h"
#include "io/gltf_checks.h"
#include "io/gltf_document.h"
#include "io/gltf_extensions.h"
#include "io/gltf_files.h"
#include "io/gltf_materials.h"
#include "core/light_sample.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

namespace penumbra {

namespace {

using glm::dmat4;

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw ModelError("glTF file " + path + ": " + problem);
}

// A primitive's indices, read in place. Index accessors hold UNSIGNED_BYTE/SHORT/INT
// in a buffer view (checkGltfModel), and each must name a vertex: all are checked up front, as the
// spec wants of the unused tail too. Without an accessor, element i is vertex i.
class IndexReader {
 public:
  IndexReader(const tinygltf::Model& m, int index, uint64_t vertices, const std::string& where, const std::string& path)
      : indexed_(index >= 0) {
    if (!indexed_) {
      span_.count = vertices;
      return;
    }
    span_ = accessorSpan(m, index, where, path);
    for (uint64_t i = 0; i < span_.count; ++i) {
      const uint32_t v = read(i);
      if (v >= vertices) {
        gltfFail(path, "accessors[" + std::to_string(index) + "]", "index " + std::to_string(v) + " (element " + std::to_string(i) +
                                                                       ") names a vertex its mesh does not have (" + std::to_string(vertices) + ")");
      }
    }
  }
  uint64_t count() const { return span_.count; }
  uint32_t operator[](uint64_t i) const { return indexed_ ? read(i) : static_cast<uint32_t>(i); }

 private:
  uint32_t read(uint64_t i) const {
    const unsigned char* p = span_.data + i * span_.stride;
    uint32_t v = 0;
    if (span_.componentSize == 1) v = *p;
    else if (span_.componentSize == 2) { uint16_t h; std::memcpy(&h, p, 2); v = h; }
    else std::memcpy(&v, p, 4);
    return v;
  }
  bool indexed_;
  AccessorSpan span_;
};

void addPrimitive(const tinygltf::Model& m, const tinygltf::Primitive& prim, const dmat4& world, const std::string& name,
                  const std::string& where, const std::string& path, LoadedModel& out) {
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) return;
  const int posIndex = prim.attributes.at("POSITION");  // checkGltfModel: present, VEC3 FLOAT
  const AccessorSpan posSpan = accessorSpan(m, posIndex, where, path);
  const size_t count = posSpan.count;
  TriangleMesh mesh;
  mesh.name = name;
  mesh.material = prim.material;
  const glm::dmat3 linear(world), normalMatrix = glm::transpose(glm::inverse(linear));
  mesh.positions.reserve(count + 1);  // padVertices: no reallocation
  forEachElement(posSpan, where + ".attributes.POSITION", path, false, [&](size_t, const double* p) {
    mesh.positions.push_back(Vec3(world * glm::dvec4(p[0], p[1], p[2], 1.0)));
    return true;
  });
  auto attr = prim.attributes.find("NORMAL");
  if (attr != prim.attributes.end()) {
    mesh.normals.reserve(count);
    forEachElement(accessorSpan(m, attr->second, where, path), where + ".attributes.NORMAL", path, true,
                   [&](size_t, const double* v) {
      const Vec3 n(glm::normalize(normalMatrix * glm::dvec3(v[0], v[1], v[2])));
      // A normal that cannot be normalised (zero, NaN) leaves the whole primitive
      // flat-shaded by its geometric normals: a guessed direction would be wrong.
      if (!isFinite(n) || std::fabs(glm::length(n) - 1.0f) > 1e-3f) {
        mesh.normals.clear();
        mesh.normals.shrink_to_fit();
        if (out.warning.empty()) out.warning = where + ".attributes.NORMAL: a normal of zero length or not finite; the primitive is flat-shaded";
        return false;
      }
      mesh.normals.push_back(n);
      return true;
    });
  }
  if ((attr = prim.attributes.find("TEXCOORD_0")) != prim.attributes.end()) {
    mesh.uvs.reserve(count);
    forEachElement(accessorSpan(m, attr->second, where, path), where + ".attributes.TEXCOORD_0", path, false,
                   [&](size_t i, const double* uv) {
      if (!(std::fabs(uv[0]) <= kMaxTexCoord && std::fabs(uv[1]) <= kMaxTexCoord)) {
        gltfFail(path, "accessors[" + std::to_string(attr->second) + "]",
                 "texture coordinate " + std::to_string(i) + " is beyond +-1e6");
      }
      mesh.uvs.emplace_back(uv[0], uv[1]);
      return true;
    });
  }
  const bool normalMapped = prim.material >= 0 && static_cast<size_t>(prim.material) < m.materials.size() &&
                            m.materials[prim.material].normalTexture.index >= 0;
  if (normalMapped && (attr = prim.attributes.find("TANGENT")) != prim.attributes.end()) {
    addTangents(m, attr->second, linear, where, path, mesh, out);
  }
  if ((attr = prim.attributes.find("COLOR_0")) != prim.attributes.end()) addColors(m, attr->second, where, path, mesh);
  // The triangles straight from the index accessor, with no list of indices beside them.
  const IndexReader idx(m, prim.indices, count, where + ".indices", path);
  const uint64_t n = idx.count();
  const bool flip = glm::determinant(linear) < 0.0;  // a mirroring node turns faces inside out
  mesh.triangles.reserve(n < 3 ? 0 : mode == TINYGLTF_MODE_TRIANGLES ? n / 3 : n - 2);
  auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    mesh.triangles.push_back(flip ? std::array<uint32_t, 3>{a, c, b} : std::array<uint32_t, 3>{a, b, c});
  };
  // Strips and fans become triangles, the strip's odd ones turned to keep the winding.
  for (uint64_t i = 0; i + 2 < n;) {
    if (mode == TINYGLTF_MODE_TRIANGLES) { add(idx[i], idx[i + 1], idx[i + 2]); i += 3; continue; }
    if (mode == TINYGLTF_MODE_TRIANGLE_FAN) add(idx[0], idx[i + 1], idx[i + 2]);
    else if (i % 2 == 0) add(idx[i], idx[i + 1], idx[i + 2]);
    else add(idx[i + 1], idx[i], idx[i + 2]);
    ++i;
  }
  if (!mesh.triangles.empty()) out.meshes.push_back(std::move(mesh));
}

void addLight(const tinygltf::Model& m, int index, const dmat4& world, const std::string& ref, const std::string& path,
              LoadedModel& out) {
  if (index < 0 || static_cast<size_t>(index) >= m.lights.size()) gltfFail(path, ref, "light " + std::to_string(index) + " does not exist");
  const std::string where = "extensions.KHR_lights_punctual.lights[" + std::to_string(index) + "]";
  const tinygltf::Light& g = m.lights[index];
  const Color color =
      g.color.size() >= 3 ? Color(float(g.color[0]), float(g.color[1]), float(g.color[2])) : Color(1.0f);
  const float intensity = static_cast<float>(g.intensity);
  if (!(intensity >= 0.0f) || !std::isfinite(intensity) || !isFinite(color) ||
      std::min({color.r, color.g, color.b}) < 0.0f) {
    gltfFail(path, where, "has a negative or non-finite colour or intensity");
  }
  // Node scales compose: a deep enough tree makes the axis overflow, not vanish.
  auto axis = [&] {
    const Vec3 d(glm::normalize(glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0)));
    if (!isFinite(d)) gltfFail(path, where, "its node's transform leaves it no finite direction");
    return d;
  };
  const Vec3 position(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  Light light;
  if (g.type == "directional") {
    light = makeDirectionalLight(axis());
  } else if (g.type == "spot") {
    const Vec3 direction = axis();
    const double outer = g.spot.outerConeAngle, inner = g.spot.innerConeAngle;
    if (!(inner >= 0.0 && inner < outer && outer <= 0.5 * M_PI)) {
      gltfFail(path, where, "spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
    }
    light = makeSpotLight(position, direction, float(inner), float(outer));
  } else {
    light = makePointLight(position);
  }
  light.color = color;
  light.intensity = intensity;
  out.lights.push_back(light);
}

void walk(const tinygltf::Model& m, int node, const dmat4& parent, int depth, const std::string& path, LoadedModel& out) {
  // checkGltfModel proved the nodes a forest; the depth bounds the recursion.
  if (depth > 256) fail(path, "the node tree is deeper than 256 levels");
  const tinygltf::Node& n = m.nodes[node];
  const dmat4 world = parent * nodeMatrix(n);
  if (n.mesh >= 0) {
    if (static_cast<size_t>(n.mesh) >= m.meshes.size()) {
      gltfFail(path, "nodes[" + std::to_string(node) + "].mesh", "mesh " + std::to_string(n.mesh) + " does not exist");
    }
    const tinygltf::Mesh& mesh = m.meshes[n.mesh];
    const std::string name = mesh.name.empty() ? "mesh " + std::to_string(n.mesh) : mesh.name;
    for (size_t i = 0; i < mesh.primitives.size(); ++i) {
      const std::string where = "meshes[" + std::to_string(n.mesh) + "].primitives[" + std::to_string(i) + "]";
      addPrimitive(m, mesh.primitives[i], world, name, where, path, out);
    }
  }
  if (n.camera >= 0) placeGltfCamera(m, n.camera, node, world, path, out.cameras);
  auto ext = n.extensions.find("KHR_lights_punctual");
  if (ext != n.extensions.end() && ext->second.Has("light")) {
    addLight(m, ext->second.Get("light").GetNumberAsInt(), world,
             "nodes[" + std::to_string(node) + "].extensions.KHR_lights_punctual.light", path, out);
  }
  for (int child : n.children) walk(m, child, world, depth + 1, path, out);
}

// tinygltf's image callback with a check first: glTF images are PNG or JPEG, and
// OpenImageIO would otherwise be handed whatever the bytes happen to be.
bool keepPngOrJpeg(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int width, int height,
                   const unsigned char* bytes, int size, void* user) {
  const bool png = size >= 8 && std::memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0;
  const bool jpeg = size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
  if (!png && !jpeg) {
    if (err) *err += "images[" + std::to_string(index) + "]: not a PNG or JPEG image\n";
    return false;
  }
  return keepEncodedImage(image, index, err, warn, width, height, bytes, size, user);
}

}  // namespace

LoadedModel loadGltfModel(const std::string& path, const LoadLimits& limits) {
  namespace fs = std::filesystem;
  // Everything tinygltf would act on unchecked is settled first: the JSON's depth,
  // version, required extensions, buffer bounds and which files it may read.
  GltfSource source = readGltfSource(path, limits);
  const std::string folder = fs::absolute(path).parent_path().lexically_normal().string();
  GltfFiles files;
  checkGltfDocument(source, path, folder, limits, files);

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(files.callbacks());
  loader.SetImageLoader(keepPngOrJpeg, nullptr);
  std::string err, warn;
  const bool ok = source.binary
                      ? loader.LoadBinaryFromMemory(&model, &err, &warn, source.bytes.data(),
                                                    static_cast<unsigned int>(source.bytes.size()), folder)
                      : loader.LoadASCIIFromString(&model, &err, &warn, source.json.data(),
                                                   static_cast<unsigned int>(source.json.size()), folder);
  if (!files.problem().empty()) fail(path, files.problem());
  if (!ok) {
    std::string line = err.substr(0, err.find('\n'));
    fail(path, "cannot load: " + (line.empty() ? std::string("unknown error") : line));
  }
  source = GltfSource{};  // tinygltf copied the buffers: the file's bytes would only add to the peak
  LoadedModel out;
  out.file = path;
  out.files = files.read();
  out.files.insert(out.files.begin(), path);
  std::vector<std::string> warnings;
  const std::vector<int> roots = checkGltfModel(model, path, warnings);
  checkGltfBudget(model, roots, path, limits);
  out.warning = !warnings.empty() ? warnings.front() : warn.substr(0, warn.find('\n'));
  out.ignoredExtensions = ignoredGltfExtensions(model.extensionsUsed);
  out.materials = gltfMaterials(model, path, folder);
  out.cameras = gltfCameras(model);
  for (int r : roots) walk(model, r, dmat4(1.0), 0, path, out);
  for (TriangleMesh& mesh : out.meshes) {
    if (mesh.material >= static_cast<int>(out.materials.size())) fail(path, "a primitive names a material that does not exist");
  }
  if (out.meshes.empty()) fail(path, "contains no triangles");
  return out;
}

}  // namespace penumbra
