// The camera against its geometry: a pinhole's rays leave one point, an
// orthographic camera's run parallel from a film plane ortho_height tall, so a
// square's image keeps its size at any distance; the JSON key (glTF: test_io_model_import).
#include "core/error.h"
#include "io/scene_loader.h"
#include "io/shapes.h"
#include "support/render_fixtures.h"

namespace penumbra {
namespace {

Camera orthoCamera(float height) {
  Camera c;
  c.position = Vec3(0.0f, 0.0f, 10.0f);
  c.lookAt = Vec3(0.0f);
  c.width = 200;
  c.height = 100;
  c.orthoHeight = height;
  return c;
}

TEST(Camera, OrthographicRaysRunParallelFromAFilmPlaneOrthoHeightTall) {
  // Corners of the film land at +-(width/height x h/2, h/2) on the plane through the
  // camera, every ray along the view direction. Tolerance 1e-5.
  const CameraRays rays(orthoCamera(4.0f));
  const Ray topLeft = rays.generate(0.0f, 0.0f), bottomRight = rays.generate(200.0f, 100.0f);
  expectColorNear(topLeft.origin, Vec3(-4.0f, 2.0f, 10.0f), 1e-5f, "top left");
  expectColorNear(bottomRight.origin, Vec3(4.0f, -2.0f, 10.0f), 1e-5f, "bottom right");
  expectColorNear(topLeft.dir, Vec3(0.0f, 0.0f, -1.0f), 1e-6f, "direction");
  expectColorNear(bottomRight.dir, Vec3(0.0f, 0.0f, -1.0f), 1e-6f, "direction");
  EXPECT_EQ(rays.pixelSpread(), 0.0f);
}

TEST(Camera, AnOrthographicSquareKeepsItsImageSizeAtAnyDistance) {
  // A 2 x 2 square seen by an orthographic camera 4 units tall covers half the
  // image's height (50 of 100 rows) and a quarter of its 200 columns, whether it
  // is 3 or 30 units away.
  for (float distance : {3.0f, 30.0f}) {
    Scene scene;
    scene.camera = orthoCamera(4.0f);
    scene.camera.position = Vec3(0.0f, 0.0f, distance);
    scene.materials.push_back(Material{});
    scene.meshes.push_back(makeQuad(Vec3(-1, -1, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), 0));
    Rig rig(scene);
    const Image depth = rig.render(Aov::Depth);
    int covered = 0;
    for (const Color& p : depth.pixels) covered += p.r > 0.0f && std::isfinite(p.r) ? 1 : 0;
    EXPECT_EQ(covered, 50 * 50) << "at distance " << distance;
  }
}

TEST(Camera, TheJsonKeyMakesAnOrthographicCameraAndANegativeHeightIsRefused) {
  const Scene s = parseScene(R"({"camera": {"ortho_height": 6, "width": 300, "height": 200}})", "x.json");
  EXPECT_EQ(s.camera.orthoHeight, 6.0f);
  try {
    parseScene(R"({"camera": {"ortho_height": -1}})", "x.json");
    FAIL() << "a negative height must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("camera.ortho_height"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace penumbra
