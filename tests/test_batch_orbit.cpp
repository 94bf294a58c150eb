// Batch orbits keep the horizon level: every camera an orbit makes turns about the
// world's up axis (or the orbit's "up") and takes that axis as camera.up, whatever
// roll the scene's own camera has; angle 0 stays on the +z side as before.
#include "plan/batch/batch_jobs.h"
#include "core/camera_frame.h"
#include "core/error.h"
#include "io/scene_loader.h"
#include "support/gltf_build.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using testing::ScratchDir;

// A box whose camera is rolled 30 degrees about its view axis (as many exported
// turntable files are), with a point light.
fs::path writeRolledModel(const ScratchDir& dir) {
  tinygltf::Model m = testing::emptyGltf();
  const float lo[3] = {-1, 0, -1}, hi[3] = {1, 1, 1};
  testing::addSceneNode(m, testing::addBoxMesh(m, lo, hi));
  const int node = testing::addCameraNode(m, 0.7, {0, 0.5, 6});
  m.nodes[node].rotation = {0, 0, std::sin(M_PI / 12), std::cos(M_PI / 12)};  // 30 degrees about z
  const fs::path file = dir.path() / "rolled.glb";
  EXPECT_TRUE(testing::writeGltfFile(m, file.string(), true));
  return file;
}

TEST(BatchOrbit, CamerasTurnAboutWorldUpWithTheHorizonLevel) {
  const ScratchDir dir;
  const fs::path model = writeRolledModel(dir);
  const Scene file = loadScene(model.string());
  ASSERT_GT(std::fabs(cameraFrame(file.camera).right.y), 0.4f);  // the file's own camera is rolled
  const fs::path jobs = dir.write("jobs.json", R"({"jobs": [{"scene": "rolled.glb", "output": "o_{i}.png",
      "orbit": {"count": 8, "center": [0, 0.5, 0], "radius": 4, "height": 1.5}}]})");
  const std::vector<BatchJob> orbit = readJobsFile(jobs.string());
  ASSERT_EQ(orbit.size(), 8u);
  for (size_t i = 0; i < orbit.size(); ++i) {
    const Scene s = loadScene(orbit[i].scene, orbit[i].overrides);
    const Camera& c = s.camera;
    EXPECT_EQ(c.up, Vec3(0, 1, 0)) << i;
    // Level: the image's right vector has no vertical component (1e-6: float).
    EXPECT_NEAR(cameraFrame(c).right.y, 0.0f, 1e-6f) << i;
    EXPECT_NEAR(glm::length(c.lookAt - Vec3(0, 0.5f, 0)), 0.0f, 1e-6f) << i;
    // On the circle of radius 4, 1.5 above the centre, at i x 45 degrees from +z.
    const double a = i * M_PI / 4;
    EXPECT_NEAR(glm::length(c.position - Vec3(4 * std::sin(a), 2.0, 4 * std::cos(a))), 0.0f, 1e-5f) << i;
  }
}

TEST(BatchOrbit, AGivenUpIsTheAxisAndTheCameraUp) {
  const ScratchDir dir;
  writeRolledModel(dir);
  const fs::path jobs = dir.write("jobs.json", R"({"jobs": [{"scene": "rolled.glb", "output": "o_{i}.png",
      "orbit": {"count": 6, "center": [1, 2, 3], "radius": 5, "height": 2, "up": [0, 0, 2]}}]})");
  for (const BatchJob& job : readJobsFile(jobs.string())) {
    const Camera c = loadScene(job.scene, job.overrides).camera;
    EXPECT_EQ(c.up, Vec3(0, 0, 1)) << job.name;
    EXPECT_NEAR(cameraFrame(c).right.z, 0.0f, 1e-6f) << job.name;
    // Every eye 2 along up from the centre, 5 from the axis.
    EXPECT_NEAR(c.position.z, 5.0f, 1e-5f) << job.name;
    EXPECT_NEAR(std::hypot(c.position.x - 1.0f, c.position.y - 2.0f), 5.0f, 1e-5f) << job.name;
  }
  const fs::path bad = dir.write("bad.json", R"({"jobs": [{"scene": "rolled.glb", "output": "o_{i}.png",
      "orbit": {"count": 2, "up": [0, 0, 0]}}]})");
  try {
    readJobsFile(bad.string());
    ADD_FAILURE() << "a zero up was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("jobs[0].orbit.up: must be a direction"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace penumbra
