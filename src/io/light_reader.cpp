// The "lights" section: one reader per type the file names (its "type" is the type's
// traits name), and the area lights' surfaces joining the scene as emitting objects.
#include "core/light_sample.h"
#include "core/emission_map.h"
#include "core/lights/emissive_mesh.h"
#include "io/emission_map_reader.h"
#include "io/float_checks.h"
#include "io/scene_sections.h"
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

namespace penumbra {

namespace {

// An area light's emitted radiance: `radiance` (W/(sr m^2)) or total `power` (W),
// with power = pi x area x radiance for a Lambertian emitter; not both.
void readEmission(const JsonNode& item, Light& light) {
  if (item.has("radiance") && item.has("power")) {
    item.child("power").fail("give radiance or power, not both");
  }
  if (item.has("power")) {
    const float power = item.child("power").asFloat(Range::atLeast(0.0));
    light.intensity = power / (kPi * lightArea(light));
  } else {
    light.intensity = item.floatOr("radiance", 1.0f, Range::atLeast(0.0));
  }
}

// A unit vector from a non-zero one, normalised in double (a float's squared length
// overflows beyond ~1e19).
Vec3 readDirection(const JsonNode& dir) {
  const glm::dvec3 d(dir.asVec3());
  const double length = glm::length(d);
  if (!(length > 0.0) || !std::isfinite(length)) dir.fail("must be a non-zero vector");
  return Vec3(d / length);
}

void readPointLight(const JsonNode& item, Light& light) {
  item.allowKeys({"type", "position", "color", "intensity"});
  light.position = readPosition(item.required("position", " for a point light"));
}

void readDirectionalLight(const JsonNode& item, Light& light) {
  item.allowKeys({"type", "direction", "color", "intensity"});
  light.direction = readDirection(item.required("direction", " for a directional light"));
}

void readQuadLight(const JsonNode& item, Light& light) {
  item.allowKeys({"type", "corner", "edge1", "edge2", "color", "radiance", "power"});
  light.position = readPosition(item.required("corner", " for a quad light"));
  light.edge1 = item.required("edge1", " for a quad light").asVec3();
  JsonNode edge2 = item.required("edge2", " for a quad light");
  light.edge2 = edge2.asVec3();
  const Vec3 p = light.position, e1 = light.edge1, e2 = light.edge2;
  checkPositions(edge2, {p + e1, p + e2, p + e1 + e2}, "the quad's corners");
  // In double: the float cross product's squared length overflows for edges beyond ~1e9.
  const double area = glm::length(glm::cross(glm::dvec3(light.edge1), glm::dvec3(light.edge2)));
  if (!(area > 1e-12) || !(area < 1e38)) edge2.fail("edge1 and edge2 span no area (or more than float can hold)");
}

// A spot: a point light aimed along `direction` with glTF's cone angles in degrees.
void readSpotLight(const JsonNode& item, Light& light) {
  item.allowKeys({"type", "position", "direction", "inner_angle", "outer_angle", "color", "intensity"});
  light.position = readPosition(item.required("position", " for a spot light"));
  light.direction = readDirection(item.required("direction", " for a spot light (the way it shines)"));
  const float outer = item.floatOr("outer_angle", 45.0f, Range::between(0.0, 90.0));
  if (!(outer > 0.0f)) item.child("outer_angle").fail("must be above 0 degrees");
  const float inner = item.floatOr("inner_angle", 0.0f, Range::between(0.0, 90.0));
  if (inner >= outer) item.child("inner_angle").fail("must be below outer_angle");
  setSpotCone(light, inner * kPi / 180.0f, outer * kPi / 180.0f);
}

// A round light's radius: above 0, with its centre +- radius inside the coordinate limits.
float readRadius(const JsonNode& radius, const Vec3& center) {
  const float r = radius.asFloat(Range::above(0.0));
  checkPositions(radius, {center - Vec3(r), center + Vec3(r)}, "center +- radius");
  return r;
}

void readSphereLight(const JsonNode& item, Light& light) {
  item.allowKeys({"type", "center", "radius", "color", "radiance", "power"});
  light.position = readPosition(item.required("center", " for a sphere light"));
  light.radius = readRadius(item.required("radius", " for a sphere light"), light.position);
}

// A disk: its centre, the normal of its emitting side, its radius.
void readDiskLight(const JsonNode& item, Light& light) {
  item.allowKeys({"type", "center", "normal", "radius", "color", "radiance", "power"});
  light.position = readPosition(item.required("center", " for a disk light"));
  light.direction = readDirection(item.required("normal", " for a disk light (the side it emits on)"));
  const JsonNode radius = item.required("radius", " for a disk light");
  light.radius = readRadius(radius, light.position);
  checkRadius(radius, light.radius, light.position);
  // Its area pi r^2 divides power and weights photons: it must not underflow.
  if (!(lightArea(light) > 0.0f)) radius.fail("is too small: pi r^2 is 0 in single precision");
}

// The types a scene file names, each with its reader of the type's own keys ("color"
// and the brightness are read for all). The names come from the types' traits.
struct LightReader {
  LightType type;
  void (*read)(const JsonNode& item, Light& light);
};
constexpr LightReader kLightReaders[] = {
    {LightType::Point, readPointLight}, {LightType::Directional, readDirectionalLight},
    {LightType::Quad, readQuadLight},   {LightType::Sphere, readSphereLight},
    {LightType::Spot, readSpotLight},   {LightType::Disk, readDiskLight},
};

std::vector<std::string> readerNames() {
  std::vector<std::string> names;
  for (const LightReader& r : kLightReaders) names.push_back(lightTraits(r.type).name);
  return names;
}

// ' ("point", "directional", ... or "spot")': what "type" may be.
std::string namesInWords(const std::vector<std::string>& names) {
  std::string list;
  for (size_t i = 0; i < names.size(); ++i) {
    list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + ("\"" + names[i] + "\"");
  }
  return " (" + list + ")";
}

// The mean of a map's texels (the light of a textured mesh that has no uvs).
Color meanTexel(const EmissionMap& map) {
  Color sum(0.0f);
  for (const Color& c : map.texels) sum += c;
  return map.texels.empty() ? Color(1.0f) : sum / float(map.texels.size());
}

std::string percent(float share) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f%%", 100.0 * share);
  return text;
}

}  // namespace

// Shadow photons name their light in 16 bits (core/photon.h).
constexpr size_t kMaxLights = 65535;

void readLights(const JsonNode& node, std::vector<Light>& out) {
  size_t count = node.arraySize();
  if (count > kMaxLights) {
    node.fail("at most " + std::to_string(kMaxLights) + " lights, got " + std::to_string(count));
  }
  static const std::vector<std::string> names = readerNames();
  for (size_t i = 0; i < count; ++i) {
    JsonNode item = node.element(i);
    item.requireObject();
    Light light;
    const LightReader& reader = kLightReaders[item.required("type", namesInWords(names)).asEnum(names)];
    light.type = reader.type;
    reader.read(item, light);
    light.color = item.colorOr("color", light.color);
    if (isDeltaLight(light)) {
      light.intensity = item.floatOr("intensity", light.intensity, Range::atLeast(0.0));
    } else {
      readEmission(item, light);
    }
    out.push_back(light);
  }
}

void addEmitters(Scene& scene) {
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    EmitterShape shape = emitterOf(light);
    if (!shape.mesh && !shape.sphere) continue;
    // A black surface that glows: photons landing on it are absorbed, and camera
    // and specular rays see its radiance on the emitting side.
    Material m;
    m.name = "light " + std::to_string(i);
    m.ambient = m.diffuse = m.specular = Color(0.0f);
    m.emission = light.radiance();
    m.twoSidedEmission = shape.twoSided;
    m.light = static_cast<int>(i);
    const int material = static_cast<int>(scene.materials.size());
    scene.materials.push_back(m);
    if (shape.mesh) {
      shape.mesh->material = material;
      shape.mesh->name = m.name;
      scene.meshes.push_back(std::move(*shape.mesh));
    } else {
      shape.sphere->material = material;
      scene.spheres.push_back(*shape.sphere);
    }
  }
}

void addMeshEmitters(Scene& scene) {
  for (size_t mi = 0; mi < scene.materials.size(); ++mi) {
    Material& m = scene.materials[mi];
    if (m.light >= 0 || !(maxComponent(m.emission) > 0.0f)) continue;
    // Its triangles, and with an emissive texture their uvs (a mesh without uvs
    // leaves the light untextured, at the texture's mean colour).
    std::vector<Vec3> triangles;
    std::vector<Vec2> uvs;
    bool everyMeshHasUvs = true;
    for (const TriangleMesh& mesh : scene.meshes) {
      if (mesh.material != static_cast<int>(mi)) continue;
      everyMeshHasUvs = everyMeshHasUvs && !mesh.uvs.empty();
      for (const auto& t : mesh.triangles) {
        triangles.insert(triangles.end(), {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]});
        if (!mesh.uvs.empty()) uvs.insert(uvs.end(), {mesh.uvs[t[0]], mesh.uvs[t[1]], mesh.uvs[t[2]]});
      }
    }
    if (triangles.empty()) continue;  // an unused emitting material lights nothing
    std::optional<EmissionMap> map;
    Color radiance = m.emission;
    if (m.emissionTexture >= 0) {
      const Texture& texture = scene.textures[size_t(m.emissionTexture)];
      map = readEmissionMap(texture.path, m.uvTransform());
      map->sampling = texture.sampler.value_or(TextureSampling{});
      if (!everyMeshHasUvs) {
        radiance *= meanTexel(*map);
        map.reset();
      }
    }
    if (scene.lights.size() >= kMaxLights) {
      throwInputError(scene.file + ": at most " + std::to_string(kMaxLights) +
                      " lights, counting one per emitting material");
    }
    Light light = makeMeshLight(triangles, radiance, static_cast<int>(mi), uvs, map ? &*map : nullptr);
    if (light.areaCdf.empty()) continue;
    if (light.emission && light.emission->meanLuminance < kDecorativeEmission) {
      scene.load.notes.push_back("material " + m.name + ": its emissive texture averages " +
                                 percent(light.emission->meanLuminance) +
                                 " of full emission: it glows where seen and lights nothing");
      continue;
    }
    light.twoSided = m.twoSidedEmission;
    m.light = static_cast<int>(scene.lights.size());
    if (!m.emitterShades) {
      // As a quad light's surface: black, it only glows.
      m.ambient = m.diffuse = m.specular = Color(0.0f);
      m.kr = 0.0f;
      m.transparent = false;
      m.metalRough = false;
      m.pR = m.pT = 0.0f;
      m.texture = -1;
    }
    scene.lights.push_back(std::move(light));
  }
}

}  // namespace penumbra
