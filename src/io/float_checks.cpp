// Whole-scene float checks: positions within kMaxCoordinate, sphere radii
// resolvable against the scene's extent, light radiance and power bounded.
#include "io/float_checks.h"

#include "core/light_sample.h"
#include "io/json_reader.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace penumbra {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

float largestAbs(const Vec3& p) {
  return std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
}

bool withinLimit(const Vec3& p) {
  return isFinite(p) && largestAbs(p) <= static_cast<float>(kMaxCoordinate);
}

// The tracer's bounding sphere (the box of all geometry, area-light surfaces
// included); directional lights' power is E pi R^2 over it.
SceneSphere geometryBounds(const Scene& scene) {
  Vec3 lo(kInf), hi(-kInf);
  for (const Sphere& s : scene.spheres) {
    lo = glm::min(lo, s.center - Vec3(s.radius));
    hi = glm::max(hi, s.center + Vec3(s.radius));
  }
  for (const TriangleMesh& m : scene.meshes) {
    for (const Vec3& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  SceneSphere bounds;
  if (glm::all(glm::lessThanEqual(lo, hi))) {
    bounds.center = 0.5f * (lo + hi);
    bounds.radius = std::max(0.5f * glm::length(hi - lo), 1e-6f);
  }
  return bounds;
}

}  // namespace

void checkRadius(const JsonNode& radius, float r, const Vec3& center) {
  const float m = largestAbs(center);
  const double least = kMinRadiusRatio * m;
  if (r < least) {
    radius.fail("must be >= 2^-18 x its centre's largest coordinate (" + number(m) + ") = " +
                number(least) + ", got " + number(r) +
                ": its surface could not be told from its centre in single precision");
  }
}

namespace {

// Where a light's brightness was given, so the message points at the key to change.
JsonNode brightnessNode(const JsonNode& light) {
  for (const char* key : {"power", "intensity", "radiance", "color"}) {
    if (light.has(key)) return light.child(key);
  }
  return light;
}

bool withinPower(const Color& c, float limit) {
  return isFinite(c) && maxComponent(c) <= limit;
}

// Lights past the JSON "lights" array come from a model file (glTF punctual lights)
// or from emitting materials (mesh lights): name the material, or the light's index.
[[noreturn]] void failOther(const JsonNode& root, const Scene& scene, size_t i, const std::string& problem) {
  const Light& light = scene.lights[i];
  if (lightTraits(light).support == LightSupport::Infinite && root.has("environment")) {
    const JsonNode env = root.child("environment");
    (env.has("intensity") ? env.child("intensity") : env).fail(problem);
  }
  if (light.material >= 0) {  // a mesh light names its emitting material
    const std::string& name = scene.materials[light.material].name;
    if (root.has("materials") && root.child("materials").has(name.c_str())) {
      const JsonNode m = root.child("materials").child(name);
      (m.has("emission") ? m.child("emission") : m).fail(problem);
    }
    root.fail("emissive material \"" + name + "\": " + problem);
  }
  root.fail("light " + std::to_string(i) + " of the model: " + problem);
}

void checkLights(const JsonNode& root, const Scene& scene) {
  if (scene.lights.empty()) return;
  const size_t listed = root.has("lights") ? root.child("lights").arraySize() : 0;
  const SceneSphere bounds = geometryBounds(scene);
  const std::string headroom =
      " (1e+30 keeps photon budgets and pixel sums finite in single precision)";
  Color total(0.0f);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    struct Where {
      const JsonNode& root;
      const Scene& scene;
      size_t i, listed;
      [[noreturn]] void fail(const std::string& problem) const {
        if (i < listed) brightnessNode(root.child("lights").element(i)).fail(problem);
        failOther(root, scene, i, problem);
      }
    } node{root, scene, i, listed};
    const Color radiance = light.radiance();
    if (!withinPower(radiance, kMaxRadiance)) {
      const char* what = isDeltaLight(light) ? "color x intensity" : "color x radiance";
      const std::string shown = isFinite(radiance) ? number(maxComponent(radiance)) : "inf";
      node.fail(std::string(what) + " = " + shown + " exceeds 1e+30" + headroom);
    }
    const Color power = lightPower(light, bounds);
    if (!withinPower(power, kMaxPower)) {
      const std::string shown = isFinite(power) ? number(maxComponent(power)) : "inf";
      node.fail("light power " + std::string(lightTraits(light).powerFormula) + " = " + shown + " W exceeds 1e+30" +
                headroom);
    }
    total += power;
    if (!withinPower(total, kMaxPower)) {
      node.fail("the total power of lights[0.." + std::to_string(i) + "] reaches " +
                number(maxComponent(total)) + " W, above 1e+30" + headroom);
    }
  }
}

void checkTriangleEdges(const JsonNode& root, const Scene& scene) {
  // Meshes carry their names, not their JSON paths: the message names the mesh.
  const JsonNode where = root.has("objects") ? root.child("objects") : root;
  for (const TriangleMesh& mesh : scene.meshes) {
    for (const auto& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        const glm::dvec3 e = glm::dvec3(mesh.positions[t[(k + 1) % 3]]) - glm::dvec3(mesh.positions[t[k]]);
        const double length = glm::length(e);
        if (length > kMaxTriangleEdge) {
          where.fail("mesh '" + mesh.name + "' has a triangle edge " + number(length) + " long, beyond 1e+13 " +
                    "(Embree's single-precision test misses hits on longer ones): split it or scale the scene down");
        }
      }
    }
  }
}

void checkSpheres(const JsonNode& root, const Scene& scene) {
  // Scene::spheres holds the objects' spheres in "objects" order, then (from
  // addEmitters) the emitting spheres of lights, whose material names the light: walk
  // both lists to name the JSON path.
  size_t sphere = 0, boundary = 0;
  if (root.has("objects")) {
    const JsonNode objects = root.child("objects");
    for (size_t i = 0; i < objects.arraySize(); ++i) {
      const JsonNode object = objects.element(i);
      if (object.child("type").asString() != "sphere") continue;
      // A medium's boundary (a medium, no material) went to Scene::boundarySpheres.
      const bool isBoundary = object.has("medium") && !object.has("material");
      const Sphere& sp = isBoundary ? scene.boundarySpheres[boundary++] : scene.spheres[sphere++];
      checkRadius(object.child("radius"), sp.radius, sp.center);
    }
  }
  for (; sphere < scene.spheres.size(); ++sphere) {
    const int li = scene.materials[size_t(scene.spheres[sphere].material)].light;
    if (li < 0) continue;
    const size_t i = static_cast<size_t>(li);
    const Light& light = scene.lights[i];
    const JsonNode radius = root.child("lights").element(i).child("radius");
    checkRadius(radius, light.radius, light.position);
    // Its area 4 pi r^2 divides power and weights photons: it must not underflow.
    if (!(lightArea(light) > 0.0f)) radius.fail("is too small: 4 pi r^2 is 0 in single precision");
  }
}

}  // namespace

Vec3 readPosition(const JsonNode& node) {
  const Vec3 p = node.asVec3();
  if (!withinLimit(p)) {
    node.fail("every coordinate must be within +-1e+15 (Embree's ray range with float "
              "precision to spare), got " + number(largestAbs(p)));
  }
  return p;
}

void checkPositions(const JsonNode& node, const std::vector<Vec3>& points, const char* what) {
  for (const Vec3& p : points) {
    if (!withinLimit(p)) {
      const std::string shown = isFinite(p) ? number(largestAbs(p)) : "not finite";
      node.fail(std::string(what) + " must be within +-1e+15 on every axis (Embree's ray range "
                "with float precision to spare), got " + shown);
    }
  }
}

void checkSceneNumbers(const JsonNode& root, const Scene& scene) {
  checkSpheres(root, scene);
  checkLights(root, scene);
  checkTriangleEdges(root, scene);
}

}  // namespace penumbra
