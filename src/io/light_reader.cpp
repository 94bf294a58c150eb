// The "lights" section: point and directional lights, and the quad and sphere
// area lights, whose surfaces also join the scene as emitting objects.
#include "core/light_sample.h"
#include "core/emission_map.h"
#include "core/lights/emissive_mesh.h"
#include "io/emission_map_reader.h"
#include "io/float_checks.h"
#include "io/scene_sections.h"
#include "io/shapes.h"
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
  JsonNode dir = item.required("direction", " for a spot light (the way it shines)");
  const glm::dvec3 d(dir.asVec3());
  const double length = glm::length(d);
  if (!(length > 0.0) || !std::isfinite(length)) dir.fail("must be a non-zero vector");
  light.direction = Vec3(d / length);
  const float outer = item.floatOr("outer_angle", 45.0f, Range::between(0.0, 90.0));
  if (!(outer > 0.0f)) item.child("outer_angle").fail("must be above 0 degrees");
  const float inner = item.floatOr("inner_angle", 0.0f, Range::between(0.0, 90.0));
  if (inner >= outer) item.child("inner_angle").fail("must be below outer_angle");
  setSpotCone(light, inner * kPi / 180.0f, outer * kPi / 180.0f);
}

void readSphereLight(const JsonNode& item, Light& light) {
  item.allowKeys({"type", "center", "radius", "color", "radiance", "power"});
  light.position = readPosition(item.required("center", " for a sphere light"));
  JsonNode radius = item.required("radius", " for a sphere light");
  light.radius = radius.asFloat(Range::above(0.0));
  checkPositions(radius, {light.position - Vec3(light.radius), light.position + Vec3(light.radius)},
                 "center +- radius");
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
  for (size_t i = 0; i < count; ++i) {
    JsonNode item = node.element(i);
    item.requireObject();
    Light light;
    size_t type = item.required("type", " (\"point\", \"directional\", \"quad\", \"sphere\" or \"spot\")")
                      .asEnum({"point", "directional", "quad", "sphere", "spot"});
    light.type = type == 4 ? LightType::Point : static_cast<LightType>(type);
    if (type == 4) {
      readSpotLight(item, light);
    } else if (light.type == LightType::Point) {
      item.allowKeys({"type", "position", "color", "intensity"});
      light.position = readPosition(item.required("position", " for a point light"));
    } else if (light.type == LightType::Directional) {
      item.allowKeys({"type", "direction", "color", "intensity"});
      JsonNode dir = item.required("direction", " for a directional light");
      glm::dvec3 d(dir.asVec3());
      double length = glm::length(d);
      if (!(length > 0.0) || !std::isfinite(length)) dir.fail("must be a non-zero vector");
      light.direction = Vec3(d / length);
    } else if (light.type == LightType::Quad) {
      readQuadLight(item, light);
    } else {
      readSphereLight(item, light);
    }
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
    if (isDeltaLight(light)) continue;
    // A black surface that glows: photons landing on it are absorbed, and camera
    // and specular rays see its radiance on the emitting side.
    Material m;
    m.name = "light " + std::to_string(i);
    m.ambient = m.diffuse = m.specular = Color(0.0f);
    m.emission = light.radiance();
    m.twoSidedEmission = light.type == LightType::Sphere;
    m.light = static_cast<int>(i);
    const int material = static_cast<int>(scene.materials.size());
    scene.materials.push_back(m);
    if (light.type == LightType::Quad) {
      TriangleMesh quad = makeQuad(light.position, light.edge1, light.edge2, material);
      quad.name = m.name;
      scene.meshes.push_back(std::move(quad));
    } else {
      scene.spheres.push_back({light.position, light.radius, material});
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
      map = readEmissionMap(scene.textures[size_t(m.emissionTexture)].path, m.uvTransform());
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
