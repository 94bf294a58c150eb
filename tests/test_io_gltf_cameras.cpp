// --camera (LoadOptions::camera) on a glTF scene with several cameras: the first by
// default, one by index (0-based, the file's "cameras") or by camera or node name,
// auto frames the model; a name or index the file lacks, or a camera no node places,
// is one line naming the file and listing its cameras. A JSON scene: auto frames it.
#include "core/error.h"
#include "io/scene_loader.h"
#include "support/gltf_build.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <algorithm>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using testing::ScratchDir;

// A unit box with cameras 0 "front" (node "FrontNode", z = 6), 1 unnamed (node
// "SideNode", z = 9, aspect 2) and 2 "spare", which no node places.
fs::path writeModel(const ScratchDir& dir) {
  tinygltf::Model m = testing::emptyGltf();
  const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  testing::addSceneNode(m, testing::addBoxMesh(m, lo, hi));
  m.nodes[testing::addCameraNode(m, 0.6, {0.5, 0.5, 6})].name = "FrontNode";
  m.cameras.back().name = "front";
  m.nodes[testing::addCameraNode(m, 0.5, {0.5, 0.5, 9})].name = "SideNode";
  m.cameras.back().perspective.aspectRatio = 2.0;
  m.cameras.push_back(m.cameras.front());
  m.cameras.back().name = "spare";
  const fs::path file = dir.path() / "model.glb";
  EXPECT_TRUE(testing::writeGltfFile(m, file.string(), true));
  return file;
}

Scene load(const fs::path& file, const std::string& camera) {
  LoadOptions o;
  o.camera = camera;
  return loadScene(file.string(), {}, {}, o);
}

std::string refusal(const fs::path& file, const std::string& camera) {
  try {
    load(file, camera);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(loaded)";
}

TEST(GltfCameras, TheFirstByDefaultAnyByIndexOrName) {
  const ScratchDir dir;
  const fs::path file = writeModel(dir);
  for (const char* pick : {"", "0", "front", "FrontNode"}) {
    const Scene s = load(file, pick);
    EXPECT_EQ(s.camera.position, Vec3(0.5f, 0.5f, 6.0f)) << pick;
    EXPECT_EQ(s.camera.height, 480) << pick;
    EXPECT_FALSE(s.load.framedCamera) << pick;
  }
  for (const char* pick : {"1", "SideNode"}) {
    const Scene s = load(file, pick);
    EXPECT_EQ(s.camera.position, Vec3(0.5f, 0.5f, 9.0f)) << pick;
    EXPECT_NEAR(s.camera.fovY, 0.5 * 180.0 / M_PI, 1e-4) << pick;
    EXPECT_EQ(s.camera.height, 320) << pick;  // its aspect ratio 2 at the default width 640
  }
}

TEST(GltfCameras, AutoFramesTheModelOverTheFilesCameras) {
  const ScratchDir dir;
  const Scene s = load(writeModel(dir), "auto");
  EXPECT_TRUE(s.load.framedCamera);
  EXPECT_EQ(s.camera.lookAt, Vec3(0.5f));
  EXPECT_EQ(std::count_if(s.load.notes.begin(), s.load.notes.end(),
                          [](const std::string& n) {
                            return n.find(": --camera auto; one frames the model from [") != std::string::npos;
                          }),
            1);
  // A JSON scene is framed on what it holds: a unit sphere at (2, 0, 0).
  dir.write("plain.json", R"({"objects": [{"type": "sphere", "center": [2, 0, 0], "radius": 1}]})");
  const Scene json = load(dir / "plain.json", "auto");
  EXPECT_EQ(json.camera.lookAt, Vec3(2, 0, 0));
  EXPECT_TRUE(json.load.framedCamera);
  EXPECT_EQ(load(dir / "plain.json", "").camera.position, Camera().position);  // no option: as the file says
}

TEST(GltfCameras, ANameOrIndexTheFileLacksIsOneLineListingItsCameras) {
  const ScratchDir dir;
  const fs::path file = writeModel(dir);
  const std::string list =
      "; the file's cameras: 0 \"front\" (node \"FrontNode\"), 1 (node \"SideNode\"), "
      "2 \"spare\" (no node places it)";
  EXPECT_EQ(refusal(file, "3"), file.string() + ": --camera 3: no camera 3" + list);
  EXPECT_EQ(refusal(file, "99999999999999999999"), file.string() +
                                                       ": --camera 99999999999999999999: no camera "
                                                       "99999999999999999999" +
                                                       list);
  EXPECT_EQ(refusal(file, "back"), file.string() + ": --camera back: no camera named \"back\"" + list);
  EXPECT_EQ(refusal(file, "spare"),
            file.string() + ": --camera spare: cameras[2]: no node of the scene places it" + list);
  dir.write("plain.json", R"({"objects": [{"type": "sphere", "center": [2, 0, 0], "radius": 1}]})");
  EXPECT_EQ(refusal(dir / "plain.json", "0"), (dir / "plain.json").string() +
                                                  ": --camera 0: no camera 0; the file has no cameras (--camera auto "
                                                  "frames the model)");
}

// A camera the checks refuse as placed (beyond 1e15) is refused only when used: by
// default, as before, in the glTF file's words; auto or another camera loads.
TEST(GltfCameras, ACameraThatFailsTheChecksIsRefusedOnlyWhenUsed) {
  const ScratchDir dir;
  tinygltf::Model m = testing::emptyGltf();
  const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  testing::addSceneNode(m, testing::addBoxMesh(m, lo, hi));
  testing::addCameraNode(m, 0.6, {0, 0, 1e16});
  testing::addCameraNode(m, 0.6, {0.5, 0.5, 6});
  const fs::path file = dir.path() / "far.glb";
  ASSERT_TRUE(testing::writeGltfFile(m, file.string(), true));
  const std::string why = refusal(file, "");
  EXPECT_EQ(why.rfind("glTF file " + file.string() + ": cameras[0] (as placed by its node): position: ", 0), 0u) << why;
  EXPECT_NE(refusal(file, "0").find(": --camera 0: cameras[0] (as placed by its node): position: "), std::string::npos);
  EXPECT_TRUE(load(file, "auto").load.framedCamera);
  EXPECT_EQ(load(file, "1").camera.position, Vec3(0.5f, 0.5f, 6.0f));
}

}  // namespace
}  // namespace penumbra
