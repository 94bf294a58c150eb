// Media bound to a scene: nested media's interfaces, the camera's and lights' media,
// closed and open meshes (the edge check and ray-parity containment), and a scene
// without media left untouched.
#include "core/error.h"
#include "io/closed_mesh.h"
#include "io/scene_loader.h"
#include "io/shapes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

using namespace penumbra;
namespace fs = std::filesystem;

namespace {

// Fog fills the scene; a big "smoke" box holds a "water" sphere holding a glass ball
// with no medium (vacuum inside).
std::string nested(const std::string& camera, const std::string& extraObjects = "") {
  return R"({"camera": {"position": )" + camera + R"(, "look_at": [0, 0, 0]},
    "lights": [{"type": "point", "position": [0, 0.5, 0]},
               {"type": "point", "position": [0, 0, 3.5]},
               {"type": "directional", "direction": [0, -1, 0]},
               {"type": "sphere", "center": [8, 0, 0], "radius": 0.5, "radiance": 2},
               {"type": "quad", "corner": [2.5, 2, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1]}],
    "materials": {"glass": {"transparent": {"ior": 1.5}}, "m": {"diffuse": 0.5}},
    "media": [{"name": "fog", "sigma_s": 0.1}, {"name": "smoke", "sigma_s": 1}, {"name": "water", "sigma_a": 0.2}],
    "objects": [
      {"type": "box", "min": [-3, -3, -3], "max": [3, 3, 3], "medium": "smoke"},
      {"type": "sphere", "center": [0, 0, 0], "radius": 2, "medium": "water", "material": "glass"},
      {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass"},
      {"type": "quad", "corner": [-10, -4, -10], "edge1": [20, 0, 0], "edge2": [0, 0, 20], "material": "m"})" +
         extraObjects + R"(],
    "render": {"model": "physical", "medium": "fog"}})";
}

constexpr int kFog = 0, kSmoke = 1, kWater = 2;

TEST(MediaBinding, NestedMediaSeparateInsideFromTheNextOut) {
  const Scene s = parseScene(nested("[0, 0, 10]"), "x.json");
  ASSERT_EQ(s.boundaryMeshes.size(), 1u);
  const MediumInterface box = s.boundaryMeshes[0].media;
  EXPECT_TRUE(box.separates);
  EXPECT_EQ(box.inside, kSmoke);
  EXPECT_EQ(box.outside, kFog);
  // spheres[0]: water in smoke; spheres[1]: the glass ball, vacuum in water.
  EXPECT_EQ(s.spheres[0].media.inside, kWater);
  EXPECT_EQ(s.spheres[0].media.outside, kSmoke);
  EXPECT_TRUE(s.spheres[0].media.separates);
  EXPECT_EQ(s.spheres[1].media.inside, kNoMedium);
  EXPECT_EQ(s.spheres[1].media.outside, kWater);
  // The floor quad is open: it changes no ray's medium.
  EXPECT_FALSE(s.meshes[0].media.separates);
  EXPECT_EQ(s.cameraMedium, kFog);
}

TEST(MediaBinding, TheCameraTakesTheInnermostMediumAroundIt) {
  EXPECT_EQ(parseScene(nested("[0, 0, 2.5]"), "x.json").cameraMedium, kSmoke);
  EXPECT_EQ(parseScene(nested("[0, 0, 1.5]"), "x.json").cameraMedium, kWater);
  EXPECT_EQ(parseScene(nested("[0, 0.5, 0.5]"), "x.json").cameraMedium, kNoMedium);  // in the glass ball
}

TEST(MediaBinding, LightsStartInTheMediumAroundThem) {
  const Scene s = parseScene(nested("[0, 0, 10]"), "x.json");
  EXPECT_EQ(s.lights[0].medium, kNoMedium);  // inside the glass ball
  EXPECT_EQ(s.lights[1].medium, kFog);       // outside the box
  EXPECT_EQ(s.lights[2].medium, kFog);       // directional: the scene's medium
  EXPECT_EQ(s.lights[3].medium, kFog);       // a sphere light is not inside itself
  EXPECT_EQ(s.lights[4].medium, kFog);       // the quad's centre, (3, 2, 0), is outside the box
}

// A cube as an OBJ with one vertex per face corner (24 vertices): closed once welded.
std::string cubeObj(bool open) {
  std::string obj;
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    for (int c : f) obj += "v " + std::to_string(c & 1 ? 1 : -1) + " " + std::to_string(c & 2 ? 1 : -1) + " " +
                           std::to_string(c & 4 ? 1 : -1) + "\n";
  }
  for (int i = 0; i < (open ? 5 : 6); ++i) {
    obj += "f " + std::to_string(4 * i + 1) + " " + std::to_string(4 * i + 2) + " " + std::to_string(4 * i + 3) + " " +
           std::to_string(4 * i + 4) + "\n";
  }
  return obj;
}

class MeshMedia : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("penumbra_media_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "closed.obj") << cubeObj(false);
    std::ofstream(dir_ / "open.obj") << cubeObj(true);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string withMesh(const std::string& file) const {
    return R"({"camera": {"position": [0, 0, 0.5]}, "lights": [{"type": "point", "position": [0, 5, 0]}],
      "media": [{"name": "fog", "sigma_s": 0.5}],
      "objects": [{"type": "mesh", "file": ")" + file + R"(", "scale": 2, "medium": "fog"}],
      "render": {"model": "physical"}})";
  }
  fs::path dir_;
};

TEST_F(MeshMedia, AClosedMeshIsAcceptedAndHoldsTheCamera) {
  const Scene s = parseScene(withMesh("closed.obj"), (dir_ / "x.json").string());
  ASSERT_EQ(s.boundaryMeshes.size(), 1u);
  EXPECT_TRUE(s.meshes.empty());
  EXPECT_EQ(s.boundaryMeshes[0].media.inside, 0);
  EXPECT_EQ(s.boundaryMeshes[0].media.outside, kNoMedium);
  EXPECT_EQ(s.cameraMedium, 0);
}

TEST_F(MeshMedia, AnOpenMeshIsRefusedNamingTheObject) {
  try {
    parseScene(withMesh("open.obj"), (dir_ / "x.json").string());
    FAIL() << "an open mesh took a medium";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("objects[0].medium"), std::string::npos) << m;
    EXPECT_NE(m.find("open (4 edges"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

TEST(ClosedMesh, EdgesVolumeAndContainment) {
  const TriangleMesh box = makeBox(Vec3(-1.0f, -2.0f, -3.0f), Vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(openEdgeCount(box), 0u);
  EXPECT_NEAR(enclosedVolume(box), 48.0, 1e-9);
  EXPECT_TRUE(meshContains(box, Vec3(0.0f)));
  EXPECT_TRUE(meshContains(box, Vec3(0.99f, 1.99f, -2.99f)));
  EXPECT_FALSE(meshContains(box, Vec3(1.01f, 0.0f, 0.0f)));
  EXPECT_FALSE(meshContains(box, Vec3(0.0f, 0.0f, 10.0f)));
  TriangleMesh open = box;
  open.triangles.pop_back();
  EXPECT_EQ(openEdgeCount(open), 3u);
  TriangleMesh flipped = box;  // one triangle wound against its neighbours
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_GT(openEdgeCount(flipped), 0u);
  TriangleMesh doubled = box;  // a face given twice: four triangles on its edges
  doubled.triangles.push_back(box.triangles[0]);
  EXPECT_GT(openEdgeCount(doubled), 0u);
}

TEST(MediaBinding, AScenesWithoutMediaIsUntouched) {
  const Scene s = parseScene(R"({"camera": {"position": [0, 0, 0.5], "look_at": [0, 0, -1]}, "lights": [{"type": "point", "position": [0, 0, 0]}],
      "objects": [{"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1]}], "render": {"model": "physical"}})",
                             "x.json");
  EXPECT_FALSE(s.hasMedia());
  EXPECT_FALSE(s.meshes[0].media.separates);
  EXPECT_EQ(s.cameraMedium, kNoMedium);
  EXPECT_EQ(s.lights[0].medium, kNoMedium);
}

}  // namespace
