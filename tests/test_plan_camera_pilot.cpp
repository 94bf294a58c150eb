// The camera pilot against geometry whose answer is exact: an orthographic camera on
// half-covered, textured and mirrored views, and a tile that sees only the empty half.
#include "plan/camera_pilot.h"
#include "io/shapes.h"
#include "support/scene_fixtures.h"
#include <gtest/gtest.h>

namespace penumbra {
namespace {

// An orthographic camera looking down -z at a view 2 tall and 8/3 wide (x in
// [-4/3, 4/3]), and a diffuse quad covering x < 0 of it.
Scene halfCoveredScene() {
  Scene scene;
  scene.camera.orthoHeight = 2.0f;
  scene.camera.width = 640;
  scene.camera.height = 480;
  scene.materials = {makeMaterial("grey", Color(0.0f), Color(0.5f))};
  scene.meshes.push_back(makeQuad(Vec3(-2, -2, 0), Vec3(2, 0, 0), Vec3(0, 4, 0), 0));
  return scene;
}

TEST(CameraPilot, CountsTheHalfOfTheViewThatMeetsASurface) {
  const Scene scene = halfCoveredScene();
  const TraceScene tracer(scene);
  // The grid's 32 columns: the left 16 meet the quad, the right 16 leave the scene.
  const CameraPilot p = measureCamera(scene, tracer, PixelBounds::frame(640, 480));
  EXPECT_DOUBLE_EQ(p.pointsPerSample, 0.5);
  EXPECT_DOUBLE_EQ(p.diffusePerSample, 0.5);
  EXPECT_DOUBLE_EQ(p.missesPerSample, 0.5);
  EXPECT_DOUBLE_EQ(p.texturesPerSample, 0.0);
  // A tile of the right half sees nothing.
  const CameraPilot right = measureCamera(scene, tracer, PixelBounds{320, 640, 0, 480});
  EXPECT_DOUBLE_EQ(right.pointsPerSample, 0.0);
  EXPECT_DOUBLE_EQ(right.missesPerSample, 1.0);
}

TEST(CameraPilot, FollowsAMirrorToWhatItShows) {
  // A mirror filling the view sends every ray straight back, onto a diffuse wall
  // behind the camera: two surfaces per sample, one of them diffuse.
  Scene scene = halfCoveredScene();
  Material mirror = makeMaterial("mirror", Color(0.0f), Color(0.0f));
  mirror.kr = 1.0f;
  scene.materials.push_back(mirror);
  scene.meshes.clear();
  scene.meshes.push_back(makeQuad(Vec3(-3, -3, 0), Vec3(6, 0, 0), Vec3(0, 6, 0), 1));
  scene.meshes.push_back(makeQuad(Vec3(-3, -3, 10), Vec3(6, 0, 0), Vec3(0, 6, 0), 0));
  const TraceScene tracer(scene);
  const CameraPilot p = measureCamera(scene, tracer, PixelBounds::frame(640, 480));
  EXPECT_DOUBLE_EQ(p.pointsPerSample, 2.0);
  EXPECT_DOUBLE_EQ(p.diffusePerSample, 1.0);
  EXPECT_DOUBLE_EQ(p.missesPerSample, 0.0);
  // At max_depth 1 the recursion stops at the mirror.
  scene.render.maxDepth = 1;
  const CameraPilot shallow = measureCamera(scene, tracer, PixelBounds::frame(640, 480));
  EXPECT_DOUBLE_EQ(shallow.pointsPerSample, 1.0);
  EXPECT_DOUBLE_EQ(shallow.diffusePerSample, 0.0);
}

TEST(CameraPilot, CountsEveryTextureAShadedMaterialReads) {
  // A base colour map and a normal map on the quad: two lookups at each of its points.
  Scene scene = halfCoveredScene();
  scene.materials[0].texture = 0;
  scene.materials[0].normalTexture = 1;
  const TraceScene tracer(scene);
  const CameraPilot p = measureCamera(scene, tracer, PixelBounds::frame(640, 480));
  EXPECT_DOUBLE_EQ(p.texturesPerSample, 1.0);
}

}  // namespace
}  // namespace penumbra
