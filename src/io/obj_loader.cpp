// OBJ loading: tinyobjloader parse, vertex unification, normals, uvs and colours; MTL
// materials mapped onto penumbra's, and the mesh split by material.
#include "io/obj_loader.h"
#include "io/input_file.h"

#include "io/mesh_normals.h"
#include "io/obj_scan.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <filesystem>
#include <unordered_map>

namespace penumbra {

namespace {

// A face corner's (position, normal, uv) indices; -1 = attribute not used.
struct CornerKey {
  int v, n, t;
  bool operator==(const CornerKey& o) const { return v == o.v && n == o.n && t == o.t; }
};

struct CornerHash {
  size_t operator()(const CornerKey& k) const {
    uint64_t h = static_cast<uint32_t>(k.v);
    h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(k.n);
    h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(k.t);
    return static_cast<size_t>(h ^ (h >> 29));
  }
};

std::string firstLine(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  return line.empty() ? "unknown parse error" : line;
}

void checkIndex(int index, size_t count, const char* what, const std::string& path) {
  if (index < 0 || static_cast<size_t>(index) >= count) {
    throw ObjError(std::string("OBJ file ") + path + ": a face refers to " + what + " " +
                   std::to_string(static_cast<int64_t>(index) + 1) + " but the file has " +
                   std::to_string(count));
  }
}

// Parses `path` into one mesh; faceMaterial (if given) gets each triangle's MTL
// material id (-1 = none), in triangle order.
TriangleMesh readObj(const std::string& path, tinyobj::ObjReader& reader, std::vector<int>* faceMaterial,
                     const LoadLimits& limits, std::vector<std::string>* mtlFiles) {
  if (const std::string why = unreadableFileReason(path); !why.empty()) {
    throw ObjError("cannot open OBJ file " + path + ": " + why);
  }
  const ObjScan scan = scanObj(path, limits);
  if (mtlFiles) *mtlFiles = scan.mtlFiles;
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  if (!reader.ParseFromFile(path, config)) {
    throw ObjError("cannot parse OBJ file " + path + ": " + firstLine(reader.Error()));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const size_t numPositions = attrib.vertices.size() / 3;
  const size_t numNormals = attrib.normals.size() / 3;
  const size_t numUvs = attrib.texcoords.size() / 2;
  // tinyobjloader keeps `v x y z r g b` colours only when every vertex has one.
  const bool colours = !attrib.colors.empty() && attrib.colors.size() == attrib.vertices.size();

  // Gather triangle corners; a corner-less attribute anywhere drops it everywhere,
  // since a mesh carries normals and uvs for all vertices or for none.
  std::vector<tinyobj::index_t> corners;
  bool allNormals = numNormals > 0, allUvs = numUvs > 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const unsigned char fv = shape.mesh.num_face_vertices[f];
      if (fv == 3 && offset + 3 <= shape.mesh.indices.size()) {
        if (faceMaterial) {
          faceMaterial->push_back(f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1);
        }
        for (size_t k = 0; k < 3; ++k) {
          const tinyobj::index_t& idx = shape.mesh.indices[offset + k];
          checkIndex(idx.vertex_index, numPositions, "vertex", path);
          allNormals = allNormals && idx.normal_index >= 0;
          allUvs = allUvs && idx.texcoord_index >= 0;
          corners.push_back(idx);
        }
      }
      offset += fv;
    }
  }
  if (corners.empty()) throw ObjError("OBJ file " + path + " contains no triangles");

  // Split by material, each group keeps its uvs if all of its corners have them (a
  // corner without one is marked NaN here and the group drops them); whole, the file.
  const bool keepUvs = faceMaterial ? numUvs > 0 : allUvs;
  for (const tinyobj::index_t& idx : corners) {
    if (allNormals) checkIndex(idx.normal_index, numNormals, "normal", path);
    if (keepUvs && idx.texcoord_index >= 0) checkIndex(idx.texcoord_index, numUvs, "texture coordinate", path);
  }
  auto position = [&](int i) {
    return Vec3(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
  };
  // A zero or non-finite file normal cannot be renormalised: recompute them all.
  for (const tinyobj::index_t& idx : corners) {
    if (!allNormals) break;
    int i = idx.normal_index;
    Vec3 n(attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]);
    float len = glm::length(n);
    if (!(len > 0.0f) || !std::isfinite(len)) allNormals = false;
  }

  TriangleMesh mesh;
  mesh.name = std::filesystem::path(path).stem().string();
  std::unordered_map<CornerKey, uint32_t, CornerHash> unified;
  std::vector<int> positionOf;  // unified vertex -> OBJ position index
  std::vector<std::array<uint32_t, 3>> positionTriangles;
  for (size_t c = 0; c < corners.size(); c += 3) {
    std::array<uint32_t, 3> tri, byPosition;
    for (size_t k = 0; k < 3; ++k) {
      const tinyobj::index_t& idx = corners[c + k];
      CornerKey key{idx.vertex_index, allNormals ? idx.normal_index : -1,
                    keepUvs ? idx.texcoord_index : -1};
      auto [it, inserted] = unified.try_emplace(key, static_cast<uint32_t>(mesh.positions.size()));
      if (inserted) {
        Vec3 p = position(key.v);
        if (!isFinite(p)) {
          throw ObjError("OBJ file " + path + ": vertex " + std::to_string(key.v + 1) +
                         " is not finite");
        }
        mesh.positions.push_back(p);
        positionOf.push_back(key.v);
        if (colours) {
          const auto* rgb = &attrib.colors[3 * size_t(key.v)];
          mesh.colors.push_back(glm::clamp(glm::vec4(float(rgb[0]), float(rgb[1]), float(rgb[2]), 1.0f), 0.0f, 1.0f));
        }
        if (allNormals) {
          Vec3 n(attrib.normals[3 * key.n], attrib.normals[3 * key.n + 1],
                 attrib.normals[3 * key.n + 2]);
          mesh.normals.push_back(glm::normalize(n));
        }
        if (keepUvs) {
          // OBJ puts v = 0 at the image's bottom row; textures are looked up with
          // t = 0 at the top (OpenImageIO, and glTF's uvs): flip v here, once.
          mesh.uvs.push_back(key.t >= 0 ? Vec2(attrib.texcoords[2 * key.t], 1.0f - attrib.texcoords[2 * key.t + 1])
                                        : Vec2(std::nanf("")));
        }
      }
      tri[k] = it->second;
      byPosition[k] = static_cast<uint32_t>(key.v);
    }
    mesh.triangles.push_back(tri);
    positionTriangles.push_back(byPosition);
  }

  if (!allNormals) {
    // Smooth over OBJ positions, not unified vertices, so a uv seam does not
    // split the normal: vertices sharing a position share its normal.
    std::vector<Vec3> objPositions(numPositions);
    for (size_t i = 0; i < numPositions; ++i) objPositions[i] = position(static_cast<int>(i));
    std::vector<Vec3> smooth = angleWeightedNormals(objPositions, positionTriangles);
    mesh.normals.reserve(mesh.positions.size());
    for (int p : positionOf) mesh.normals.push_back(smooth[p]);
  }
  return mesh;
}

Color rgb(const tinyobj::real_t* c) { return Color(c[0], c[1], c[2]); }

// One MTL material as penumbra's (docs/scene-format.md, "OBJ materials").
ModelMaterial mapMtl(const tinyobj::material_t& t, const std::filesystem::path& dir) {
  ModelMaterial out;
  Material& m = out.material;
  m.name = t.name;
  const Color ka = rgb(t.ambient), ke = rgb(t.emission), tf = rgb(t.transmittance);
  // An ambient "reflectance" above 1 is no reflectance: old exports (the Cornell box
  // OBJ among them) mark their light that way, so it is read as emission.
  const bool kaGlows = maxComponent(ke) <= 0.0f && maxComponent(ka) > 1.0f;
  m.ambient = kaGlows ? Color(0.0f) : ka;
  m.emission = kaGlows ? ka : ke;
  m.diffuse = rgb(t.diffuse);
  m.specular = rgb(t.specular);
  m.shininess = maxComponent(m.specular) > 0.0f ? std::max(0.0f, float(t.shininess)) : 0.0f;
  if ((t.illum == 3 || t.illum == 5) && maxComponent(m.specular) > 0.0f) {
    m.kr = std::min(1.0f, maxComponent(m.specular));  // a mirror: penumbra's is uncoloured
    m.specular = Color(0.0f);
  }
  if (t.metallic > 0.0f || t.roughness > 0.0f) {
    // The PBR extension's Pm / Pr: glTF's metallic-roughness over the Kd base colour.
    m.metalRough = true;
    m.metallic = std::clamp(float(t.metallic), 0.0f, 1.0f);
    m.roughness = std::clamp(float(t.roughness), 0.0f, 1.0f);
    m.specular = Color(0.0f);
    m.shininess = 0.0f;
    m.kr = 0.0f;
  }
  if (t.dissolve < 1.0f) {  // d < 1 or Tr > 0: glass (penumbra has no partial opacity)
    m.transparent = true;
    m.ior = t.ior > 0.0f && t.ior != 1.0f ? float(t.ior) : 1.5f;  // Ni 1 is MTL's default
    m.tint = maxComponent(tf) > 0.0f ? tf : Color(1.0f);
  }
  auto file = [&](const std::string& name) {
    const std::filesystem::path tex(name);
    return (tex.is_relative() ? dir / tex : tex).lexically_normal().string();
  };
  if (!t.diffuse_texname.empty()) out.texture = file(t.diffuse_texname);
  if (!t.emissive_texname.empty()) out.emissionTexture = file(t.emissive_texname);
  // norm, else map_Bump / bump: read as a tangent-space normal map (what exporters
  // write there today), -bm its scale.
  const std::string& normal = t.normal_texname.empty() ? t.bump_texname : t.normal_texname;
  if (!normal.empty()) {
    out.normalTexture = file(normal);
    const tinyobj::texture_option_t& opt = t.normal_texname.empty() ? t.bump_texopt : t.normal_texopt;
    out.material.normalScale = std::isfinite(opt.bump_multiplier) ? float(opt.bump_multiplier) : 1.0f;
  }
  return out;
}

}  // namespace

TriangleMesh loadObj(const std::string& path) {
  tinyobj::ObjReader reader;
  return readObj(path, reader, nullptr, {}, nullptr);
}

LoadedModel loadObjModel(const std::string& path, const LoadLimits& limits) {
  tinyobj::ObjReader reader;
  std::vector<int> faceMaterial;
  LoadedModel model;
  TriangleMesh all = readObj(path, reader, &faceMaterial, limits, &model.files);
  model.files.insert(model.files.begin(), path);
  model.file = path;
  model.warning = firstLine(reader.Warning());
  if (reader.Warning().empty()) model.warning.clear();
  const std::filesystem::path dir = std::filesystem::absolute(path).parent_path();
  for (const tinyobj::material_t& t : reader.GetMaterials()) model.materials.push_back(mapMtl(t, dir));
  // One mesh per material, in order of first use, each with only its own vertices.
  std::vector<int> meshOf(model.materials.size() + 1, -1);  // material id + 1 -> mesh
  std::unordered_map<uint64_t, uint32_t> remap;  // (mesh << 32 | vertex) -> its index there
  for (size_t f = 0; f < all.triangles.size(); ++f) {
    int id = faceMaterial[f];
    if (id < -1 || id >= static_cast<int>(model.materials.size())) id = -1;
    int& k = meshOf[id + 1];
    if (k < 0) {
      k = static_cast<int>(model.meshes.size());
      TriangleMesh part;
      part.name = all.name + (id >= 0 ? ":" + model.materials[id].material.name : "");
      part.material = id;
      model.meshes.push_back(std::move(part));
    }
    TriangleMesh& part = model.meshes[k];
    std::array<uint32_t, 3> tri;
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = all.triangles[f][c];
      auto [it, inserted] = remap.try_emplace((static_cast<uint64_t>(k) << 32) | v,
                                              static_cast<uint32_t>(part.positions.size()));
      if (inserted) {
        part.positions.push_back(all.positions[v]);
        if (!all.normals.empty()) part.normals.push_back(all.normals[v]);
        if (!all.uvs.empty()) part.uvs.push_back(all.uvs[v]);
        if (!all.colors.empty()) part.colors.push_back(all.colors[v]);
      }
      tri[c] = it->second;
    }
    part.triangles.push_back(tri);
  }
  for (TriangleMesh& part : model.meshes) {
    for (const Vec2& uv : part.uvs) {
      if (std::isnan(uv.x)) {
        part.uvs.clear();
        break;
      }
    }
  }
  return model;
}

}  // namespace penumbra
