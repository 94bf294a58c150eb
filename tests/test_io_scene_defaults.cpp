// A glTF scene that frames and lights itself: a model without a camera gets one whose
// image its bounding sphere fills to 90% of the smaller side, a model without a light
// the studio environment, each with one note; LoadOptions{false} (--no-defaults) keeps
// the file as it is, and a camera or light the user gave is never replaced. Models are written with tinygltf's writer.
#include "core/camera_frame.h"
#include "core/lights/studio_environment.h"
#include "core/lights/environment_map.h"
#include "io/scene_defaults.h"
#include "io/scene_loader.h"
#include "support/gltf_build.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using testing::ScratchDir;

// A box model [lo, hi] with neither camera nor light.
fs::path writeBox(const ScratchDir& dir, const std::string& name, Vec3 lo, Vec3 hi) {
  tinygltf::Model m = testing::emptyGltf();
  const float l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
  testing::addSceneNode(m, testing::addBoxMesh(m, l, h));
  const fs::path file = dir.path() / name;
  EXPECT_TRUE(testing::writeGltfFile(m, file.string(), false));
  return file;
}

size_t notesWith(const Scene& s, const std::string& part) {
  return std::count_if(s.load.notes.begin(), s.load.notes.end(),
                       [&](const std::string& n) { return n.find(part) != std::string::npos; });
}

// Where a point lands in the image, as the tracer's pinhole maps it: -1..1 across
// the width and the height; depth along the view.
struct Projected {
  double x, y, depth;
};
Projected project(const Camera& c, const Vec3& p) {
  const CameraFrame f = cameraFrame(c);
  const glm::dvec3 d = glm::dvec3(p) - glm::dvec3(c.position);
  const double depth = glm::dot(d, glm::dvec3(f.forward));
  const double tanHalf = std::tan(0.5 * double(c.fovY) * M_PI / 180.0), aspect = double(c.width) / c.height;
  return {glm::dot(d, glm::dvec3(f.right)) / (depth * tanHalf * aspect), glm::dot(d, glm::dvec3(f.up)) / (depth * tanHalf),
          depth};
}

TEST(SceneDefaults, ACameraLessModelIsFramedWithItsBoundingSphereFillingTheSmallerSide) {
  const ScratchDir dir;
  // A wide flat slab off the origin, a tall post, a small (8 cm) model; several image
  // shapes (landscape, portrait) and fields of view, the fov and image size kept as given.
  struct Case {
    Vec3 lo, hi;
    const char* camera;
  };
  const Case cases[] = {{{8, 1, -5}, {12, 1.5f, -4}, R"({"width": 320, "height": 240, "fov": 30})"},
                        {{-0.2f, 0, -0.2f}, {0.2f, 6, 0.2f}, R"({"width": 160, "height": 320})"},
                        {{0.01f, 0.02f, 0.03f}, {0.09f, 0.1f, 0.07f}, R"({"width": 400, "height": 100, "fov": 70})"}};
  for (const Case& k : cases) {
    const fs::path file = writeBox(dir, "model.gltf", k.lo, k.hi);
    dir.write("model.json", std::string(R"({"camera": )") + k.camera + "}");
    const Scene s = loadScene(file.string());
    const Camera& c = s.camera;
    const nlohmann::json given = nlohmann::json::parse(k.camera);
    EXPECT_EQ(c.width, given["width"].get<int>());
    EXPECT_EQ(c.height, given["height"].get<int>());
    EXPECT_FLOAT_EQ(c.fovY, given.value("fov", 45.0f));
    EXPECT_EQ(c.up, Vec3(0, 1, 0));
    // A box's smallest enclosing ball is its circumsphere: centre and half diagonal.
    const glm::dvec3 centre = 0.5 * (glm::dvec3(k.lo) + glm::dvec3(k.hi));
    const double radius = 0.5 * glm::length(glm::dvec3(k.hi) - glm::dvec3(k.lo));
    EXPECT_LT(glm::length(glm::dvec3(c.lookAt) - centre), 1e-6 * glm::length(centre) + 1e-7);
    // A three-quarter view from +z, turned towards +x and a little above.
    EXPECT_GT(c.position.z, centre.z);
    EXPECT_GT(c.position.x, centre.x);
    EXPECT_GT(c.position.y, centre.y);
    // The sphere's silhouette, the cone of half-angle asin(r / d), on the image plane:
    // a circle of radius tan of it, 90% of the smaller half-extent (1e-4: float camera).
    const double d = glm::length(glm::dvec3(c.position) - centre);
    const double silhouette = std::tan(std::asin(radius / d));
    const double half = std::tan(0.5 * double(c.fovY) * M_PI / 180.0) * std::min(1.0, double(c.width) / c.height);
    EXPECT_NEAR(silhouette / half, 0.9, 1e-4);
    EXPECT_DOUBLE_EQ(kFrameFill, 0.9);
    // So every corner (on the sphere) is in front of the camera and inside the image.
    for (int i = 0; i < 8; ++i) {
      const Vec3 corner((i & 1) ? k.hi.x : k.lo.x, (i & 2) ? k.hi.y : k.lo.y, (i & 4) ? k.hi.z : k.lo.z);
      const Projected p = project(c, corner);
      EXPECT_GT(p.depth, 0.0);
      EXPECT_LE(std::fabs(p.x), 1.0) << "corner " << i;
      EXPECT_LE(std::fabs(p.y), 1.0) << "corner " << i;
    }
    EXPECT_TRUE(s.load.noCamera && s.load.framedCamera);
    EXPECT_EQ(notesWith(s, file.string() + ": no camera; one frames the model from ["), 1u);
  }
}

// Points on a sphere: the enclosing ball is that sphere (Ritter's ball on a round
// model); a cloud in a box: every point inside, within 20% of half the largest
// pairwise distance (a lower bound on the minimal radius, by brute force); balls count
// with their radius; nothing gives an empty ball.
TEST(SceneDefaults, TheBoundingSphereEnclosesEveryItemAndHugsRoundModels) {
  std::vector<glm::dvec3> round;
  const glm::dvec3 at(3, -2, 5);
  for (int i = 0; i < 2000; ++i) {  // a Fibonacci lattice on the unit sphere
    const double z = 1.0 - (2.0 * i + 1.0) / 2000.0, phi = i * M_PI * (3.0 - std::sqrt(5.0));
    round.push_back(at + glm::dvec3(std::sqrt(1.0 - z * z) * std::cos(phi), std::sqrt(1.0 - z * z) * std::sin(phi), z));
  }
  auto over = [](const std::vector<glm::dvec3>& points, double r) {
    return [&points, r](const auto& f) {
      for (const glm::dvec3& p : points) f(p, r);
    };
  };
  BoundingSphere s = boundingSphere(over(round, 0.0));
  EXPECT_NEAR(s.radius, 1.0, 2e-3);
  EXPECT_LT(glm::length(s.centre - at), 2e-3);
  for (const glm::dvec3& p : round) EXPECT_LE(glm::length(p - s.centre), s.radius);

  std::vector<glm::dvec3> cloud;
  uint32_t state = 12345;
  auto next = [&] { return (state = state * 1664525u + 1013904223u) / 4294967296.0; };
  for (int i = 0; i < 300; ++i) cloud.push_back({4.0 * next(), next(), 2.0 * next()});
  s = boundingSphere(over(cloud, 0.0));
  double diameter = 0.0;
  for (const glm::dvec3& p : cloud) {
    EXPECT_LE(glm::length(p - s.centre), s.radius);
    for (const glm::dvec3& q : cloud) diameter = std::max(diameter, glm::length(p - q));
  }
  EXPECT_LE(s.radius, 1.2 * 0.5 * diameter);
  // The same cloud as balls of radius 0.5: each ball inside.
  s = boundingSphere(over(cloud, 0.5));
  for (const glm::dvec3& p : cloud) EXPECT_LE(glm::length(p - s.centre) + 0.5, s.radius);
  EXPECT_TRUE(boundingSphere(over({}, 0.0)).empty());
}

TEST(SceneDefaults, ALightlessModelGetsTheStudioAndOneNote) {
  const ScratchDir dir;
  const std::string model = writeBox(dir, "model.gltf", {0, 0, 0}, {1, 1, 1}).string();
  const Scene s = loadScene(model);
  ASSERT_EQ(s.lights.size(), 1u);
  const Light* sky = environmentOf(s);
  ASSERT_NE(sky, nullptr);
  EXPECT_EQ(sky->radiance(), Color(1.0f));
  ASSERT_NE(sky->environment, nullptr);  // the studio's map
  EXPECT_EQ(sky->environment->width, studio::kWidth);
  EXPECT_EQ(sky->environment->rotation, 0.0f);
  EXPECT_EQ(s.render.environmentBackground, Color(studio::kBackground));
  EXPECT_TRUE(s.load.noLight && s.load.defaultSky);
  EXPECT_EQ(s.load.modelFile, model);
  EXPECT_EQ(notesWith(s, ": no light; the studio environment lights it, a grey background behind"), 1u);
}

TEST(SceneDefaults, AModelsOwnEnvironmentIsKept) {
  // An environment beside the model lights it: no studio, no background of its own.
  const ScratchDir dir;
  writeBox(dir, "model.gltf", {0, 0, 0}, {1, 1, 1});
  dir.write("model.json", R"({"environment": {"color": 0.5}})");
  const Scene s = loadScene((dir.path() / "model.gltf").string());
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(environmentOf(s)->environment, nullptr);
  EXPECT_FALSE(s.render.environmentBackground.has_value());
  EXPECT_FALSE(s.load.defaultSky);
}

TEST(SceneDefaults, NoDefaultsKeepsTheFileAsItIs) {
  const ScratchDir dir;
  const Scene s = loadScene(writeBox(dir, "model.gltf", {0, 0, 0}, {1, 1, 1}).string(), {}, {}, LoadOptions{false, nullptr, ""});
  const Camera plain;
  EXPECT_EQ(s.camera.position, plain.position);
  EXPECT_EQ(s.camera.lookAt, plain.lookAt);
  EXPECT_TRUE(s.lights.empty());
  EXPECT_TRUE(s.load.noCamera && s.load.noLight);  // what check reports it would add
  EXPECT_FALSE(s.load.framedCamera || s.load.defaultSky);
  EXPECT_EQ(notesWith(s, "no camera"), 0u);
  EXPECT_EQ(notesWith(s, "no light;"), 0u);  // no sky is added ...
  EXPECT_EQ(notesWith(s, "warning: "), 1u);  // ... and the scene without light says so
}

TEST(SceneDefaults, WhatTheUserGaveIsNeverReplaced) {
  const ScratchDir dir;
  // The model's own camera and light.
  tinygltf::Model m = testing::emptyGltf();
  const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  testing::addSceneNode(m, testing::addBoxMesh(m, lo, hi));
  testing::addCameraNode(m, 0.6, {0.5, 0.5, 6});
  tinygltf::Light light;
  light.type = "point";
  light.intensity = 5;
  m.lights.push_back(light);
  m.nodes[testing::addSceneNode(m, -1, {0, 3, 0})].extensions["KHR_lights_punctual"] =
      tinygltf::Value(tinygltf::Value::Object{{"light", tinygltf::Value(0)}});
  m.extensionsUsed = {"KHR_lights_punctual"};
  ASSERT_TRUE(testing::writeGltfFile(m, (dir / "own.glb").string(), true));
  const Scene own = loadScene((dir / "own.glb").string());
  EXPECT_EQ(own.camera.position, Vec3(0.5f, 0.5f, 6.0f));
  ASSERT_EQ(own.lights.size(), 1u);
  EXPECT_EQ(own.lights[0].type, LightType::Point);
  EXPECT_FALSE(own.load.noCamera || own.load.noLight);
  EXPECT_TRUE(own.load.notes.empty());

  // A camera placed and an environment given by the JSON beside the model, or by --set.
  const fs::path box = writeBox(dir, "box.gltf", {0, 0, 0}, {1, 1, 1});
  dir.write("box.json", R"({"camera": {"position": [0, 1, 9]}, "environment": {"intensity": 0.5}})");
  const Scene side = loadScene(box.string());
  EXPECT_EQ(side.camera.position, Vec3(0, 1, 9));
  ASSERT_EQ(side.lights.size(), 1u);
  EXPECT_FLOAT_EQ(side.lights[0].intensity, 0.5f);
  EXPECT_FALSE(side.load.framedCamera || side.load.defaultSky);
  fs::remove(dir / "box.json");
  const Scene set = loadScene(box.string(), {"camera.look_at=[0,0.5,0]"});
  EXPECT_FALSE(set.load.framedCamera);
  EXPECT_TRUE(set.load.defaultSky);

  // A JSON scene is never given defaults.
  dir.write("plain.json", R"({"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]})");
  const Scene json = loadScene((dir / "plain.json").string());
  EXPECT_TRUE(json.lights.empty());
  EXPECT_FALSE(json.load.noCamera || json.load.noLight);
  EXPECT_TRUE(json.load.modelFile.empty());  // its PNG keeps the clamp curve
}

}  // namespace
}  // namespace penumbra
