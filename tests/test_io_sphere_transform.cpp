// Sphere transforms and uv_scale in the scene format: scale about the origin then
// translate (as meshes), uniform only, and uv_scale read and range-checked.
#include "core/error.h"
#include "io/scene_loader.h"
#include <gtest/gtest.h>

namespace penumbra {
namespace {

std::string sceneWith(const std::string& object, const std::string& texture = "") {
  return R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
             "lights": [{"type": "point", "position": [0, 3, 3]}],
             "materials": {"m": {"diffuse": 0.5)" + texture + R"(}},
             "objects": [)" + object + "]}";
}

TEST(SphereTransform, ScaleAboutTheOriginThenTranslate) {
  const Scene s = parseScene(sceneWith(R"({"type": "sphere", "center": [1, 2, 3], "radius": 0.5, "material": "m",
                                          "scale": 2, "translate": [10, 0, -1]})"), "t.json");
  ASSERT_EQ(s.spheres.size(), 1u);
  EXPECT_EQ(s.spheres[0].center, Vec3(12.0f, 4.0f, 5.0f));
  EXPECT_FLOAT_EQ(s.spheres[0].radius, 1.0f);
  const Scene same = parseScene(sceneWith(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m",
                                             "scale": [3, 3, 3]})"), "t.json");
  EXPECT_FLOAT_EQ(same.spheres[0].radius, 3.0f);
}

TEST(SphereTransform, NonUniformScaleAndRotateAreRefused) {
  try {
    parseScene(sceneWith(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m",
                             "scale": [1, 2, 1]})"), "t.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("objects[0].scale: a sphere scales uniformly"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseScene(sceneWith(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m",
                                       "rotate": [0, 90, 0]})"), "t.json"), InputError);
}

TEST(UvScale, ReadAsANumberOrAPairAndRangeChecked) {
  const std::string sphere = R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"})";
  const Scene a = parseScene(sceneWith(sphere, R"(, "texture": {"file": "builtin:checker@64", "uv_scale": 4})"), "t.json");
  EXPECT_EQ(a.materials[0].uvScale, Vec2(4.0f));
  const Scene b = parseScene(sceneWith(sphere, R"(, "texture": {"file": "builtin:checker@64", "uv_scale": [2, 0.5]})"), "t.json");
  EXPECT_EQ(b.materials[0].uvScale, Vec2(2.0f, 0.5f));
  EXPECT_THROW(parseScene(sceneWith(sphere, R"(, "texture": {"file": "builtin:checker@64", "uv_scale": 0})"), "t.json"),
               InputError);
  EXPECT_THROW(parseScene(sceneWith(sphere, R"(, "texture": {"file": "builtin:checker@64", "uv_scale": [1, 2, 3]})"), "t.json"),
               InputError);
}

}  // namespace
}  // namespace penumbra
