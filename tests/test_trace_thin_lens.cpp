// The thin lens against its closed forms: no aperture is the pinhole bit for bit, every
// lens ray of a film point meets on the focus plane, an f-number's radius follows the
// 36 mm sensor, and an image shows a sharp point on the focus plane and the computed
// circle of confusion off it; the JSON keys and their refusals.
#include "core/error.h"
#include "core/thin_lens.h"
#include "io/scene_loader.h"
#include "io/shapes.h"
#include "support/render_fixtures.h"
#include <cmath>

namespace penumbra {
namespace {

constexpr float kFocus = 10.0f;  // the camera at z = 10 looks at the origin
constexpr float kAperture = 1.0f;

Camera lensCamera() {
  Camera c = axisCamera(Vec3(0.0f, 0.0f, kFocus), Vec3(0.0f), 30.0f);  // 65 x 49
  c.apertureRadius = kAperture;
  return c;
}

// Pixels per unit of tan(angle) on the film: the height over the tangent range it spans.
double pixelsPerTangent(const Camera& c) {
  return c.height / (2.0 * std::tan(0.5 * double(c.fovY) * 3.14159265358979323846 / 180.0));
}

// The circle of confusion's diameter in pixels for a point at depth d (along the view).
// The lens sits at the pinhole; the film keeps the pinhole's field of view, so a film
// point s (in tangent units: lateral offset over depth) sees along the pinhole ray to
// its point s fd on the focus plane at depth fd, and from lens point l its ray is at
// l + (s fd - l) z / fd at depth z. That ray meets a point P at depth d, lateral P,
// when l + (s fd - l) d / fd = P, i.e. s = P / d - l (1/d - 1/fd): the pinhole image
// P / d moved by l (fd - d) / (d fd). Over the aperture disk |l| <= A, the film points
// that see P fill a disk of diameter 2 A |d - fd| / (d fd) tangent units, which is the
// thin lens's c = D |d - fd| / d x v / fd with D = 2A and the image distance v measured
// in film units (v / fd the magnification at the focus plane). In pixels:
//   c = 2 A |d - fd| / (d fd) x height / (2 tan(fov / 2)).
double circleOfConfusion(const Camera& c, double d) {
  return 2.0 * kAperture * std::fabs(d - kFocus) / (d * kFocus) * pixelsPerTangent(c);
}

// A square of side `side` facing the camera at depth d, centred on the optical axis.
Scene squareAt(double d, double side) {
  Scene s;
  s.camera = lensCamera();
  s.camera.spp = 1024;
  s.materials.push_back(Material{});
  const float h = static_cast<float>(0.5 * side), z = static_cast<float>(kFocus - d);
  s.meshes.push_back(makeQuad(Vec3(-h, -h, z), Vec3(2 * h, 0, 0), Vec3(0, 2 * h, 0), 0));
  return s;
}

TEST(ThinLens, NoApertureGivesThePinholesRaysBitForBit) {
  Camera c = lensCamera();
  c.apertureRadius = 0.0f;
  const CameraRays rays(c);
  for (uint64_t key : {0ull, 1ull, 0x123456789abcdefull}) {
    const Ray a = rays.generate(3.25f, 40.5f), b = rays.generate(3.25f, 40.5f, key);
    EXPECT_EQ(a.origin, b.origin);
    EXPECT_EQ(a.dir, b.dir);
  }
}

TEST(ThinLens, EveryLensRayOfAFilmPointMeetsThePinholeRayOnTheFocusPlane) {
  // The pinhole ray's point at depth fd, and each lens ray's: within 1e-5 of fd; the
  // ray leaves from within the aperture, on the lens plane, and the same key gives the
  // same ray. 256 keys reach at least 0.9 A from the centre.
  const Camera c = lensCamera();
  const CameraRays rays(c);
  const Ray pin = rays.generate(10.5f, 7.25f);
  const Vec3 target = pin.origin + pin.dir * (kFocus / -pin.dir.z);
  float widest = 0.0f;
  for (uint64_t key = 0; key < 256; ++key) {
    const Ray r = rays.generate(10.5f, 7.25f, key);
    EXPECT_EQ(r.origin.z, kFocus);
    const float offset = glm::length(r.origin - c.position);
    EXPECT_LE(offset, kAperture * 1.000001f);
    widest = std::max(widest, offset);
    const Vec3 hit = r.origin + r.dir * ((r.origin.z) / -r.dir.z);
    EXPECT_LT(glm::length(hit - target), 1e-5f * kFocus) << "key " << key;
    EXPECT_EQ(rays.generate(10.5f, 7.25f, key).dir, r.dir);
  }
  EXPECT_GT(widest, 0.9f * kAperture);
}

TEST(ThinLens, AnFNumbersRadiusIsTheFocalLengthOverTwiceIt) {
  // A 3:2 image with a vertical fov of 2 atan(12 / 50): a 50 mm lens on 36 x 24 mm.
  // f/2 opens 12.5 mm = 0.0125 scene units (metres); a portrait image puts the 36 mm
  // on its height: 2 atan(18 / 50) is 50 mm there.
  Camera c;
  c.width = 300;
  c.height = 200;
  c.fovY = static_cast<float>(2.0 * std::atan(12.0 / 50.0) * 180.0 / 3.14159265358979323846);
  c.fNumber = 2.0f;
  EXPECT_NEAR(focalLengthMm(c), 50.0, 1e-4);
  EXPECT_NEAR(lensRadius(c), 0.0125f, 1e-7f);
  c.width = 200;
  c.height = 300;
  c.fovY = static_cast<float>(2.0 * std::atan(18.0 / 50.0) * 180.0 / 3.14159265358979323846);
  EXPECT_NEAR(focalLengthMm(c), 50.0, 1e-4);
  c.orthoHeight = 2.0f;
  EXPECT_EQ(lensRadius(c), 0.0f);
}

TEST(ThinLens, APointOnTheFocusPlaneStaysSharp) {
  // A square half a pixel wide on the focus plane, centred on the axis: every lens ray
  // of a film point reaches the same point of it, so all its coverage falls in the centre
  // pixel (0.25 of it, stratified film samples), exactly as the pinhole's.
  const double side = 0.5 / pixelsPerTangent(lensCamera()) * kFocus;
  Scene lens = squareAt(kFocus, side), pinhole = lens;
  pinhole.camera.apertureRadius = 0.0f;
  const Image a = Rig(lens).render(Aov::Depth), b = Rig(pinhole).render(Aov::Depth);
  const size_t centre = size_t(24) * 65 + 32;
  EXPECT_NEAR(a.coverage[centre], 0.25f, 0.01f);
  EXPECT_NEAR(a.coverage[centre], b.coverage[centre], 2.0f / 1024.0f);
  for (size_t i = 0; i < a.coverage.size(); ++i)
    if (i != centre) {
      EXPECT_EQ(a.coverage[i], 0.0f) << "pixel " << i % 65 << "," << i / 65;
    }
}

// The coverage image's second moment about its centroid, per axis, and the farthest
// covered pixel centre from it.
struct Spread {
  double variance = 0.0, reach = 0.0, total = 0.0;
};
Spread spreadOf(const Image& img) {
  double sum = 0.0, mx = 0.0, my = 0.0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double w = img.coverage[size_t(y) * img.width + x];
      sum += w;
      mx += w * (x + 0.5);
      my += w * (y + 0.5);
    }
  mx /= sum;
  my /= sum;
  Spread s;
  s.total = sum;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double w = img.coverage[size_t(y) * img.width + x];
      const double dx = x + 0.5 - mx, dy = y + 0.5 - my;
      s.variance += w * 0.5 * (dx * dx + dy * dy);
      if (w > 0.0) s.reach = std::max(s.reach, std::sqrt(dx * dx + dy * dy));
    }
  s.variance /= sum;
  return s;
}

TEST(ThinLens, APointOffTheFocusPlaneSpreadsOverTheCircleOfConfusion) {
  // A square 1.5 pixels wide (as the pinhole sees it) in front of and behind the focus
  // plane. Its image is the square convolved with the circle of confusion (a uniform
  // disk of diameter c: per-axis variance c^2 / 16) and the pixel (a unit box: 1/12);
  // the square adds q^2 / 12. So the coverage's per-axis variance gives
  // c = 4 sqrt(variance - (q^2 + 1) / 12), within a pixel of the closed form, and no
  // covered pixel lies beyond the disk, the square's half-diagonal and a pixel's.
  const Camera cam = lensCamera();
  for (double d : {6.0, 20.0}) {
    const double q = 1.5, side = q / pixelsPerTangent(cam) * d;
    const Scene scene = squareAt(d, side);
    const Image img = Rig(scene).render(Aov::Depth);
    const Spread s = spreadOf(img);
    const double c = circleOfConfusion(cam, d);
    const double measured = 4.0 * std::sqrt(s.variance - (q * q + 1.0) / 12.0);
    EXPECT_NEAR(measured, c, 1.0) << "depth " << d << ": closed form " << c << " px";
    EXPECT_NEAR(s.total, q * q, 0.05 * q * q) << "depth " << d;  // the square's light, all of it
    EXPECT_LE(s.reach, 0.5 * c + q / std::sqrt(2.0) + std::sqrt(0.5)) << "depth " << d;
    EXPECT_GT(s.reach, 0.5 * c - 1.0) << "depth " << d;
    // The packet path and the single-ray path trace the same lens rays.
    Scene single = scene;
    single.render.packets = !scene.render.packets;
    EXPECT_EQ(Rig(single).render(Aov::Depth).coverage, img.coverage) << "depth " << d;
  }
}

TEST(ThinLens, TheJsonKeysSetTheLensAndBadValuesAreRefusedAtTheirKey) {
  const Scene s = parseScene(R"({"camera": {"f_number": 2.8, "focus_distance": 3}})", "x.json");
  EXPECT_EQ(s.camera.fNumber, 2.8f);
  EXPECT_EQ(s.camera.focusDistance, 3.0f);
  EXPECT_EQ(parseScene(R"({"camera": {"aperture_radius": 0.05}})", "x.json").camera.apertureRadius, 0.05f);
  const std::pair<const char*, const char*> bad[] = {
      {R"({"camera": {"aperture_radius": -0.1}})", "camera.aperture_radius"},
      {R"({"camera": {"f_number": 0}})", "camera.f_number"},
      {R"({"camera": {"f_number": -2}})", "camera.f_number"},
      {R"({"camera": {"focus_distance": 0}})", "camera.focus_distance"},
      {R"({"camera": {"focus_distance": -1}})", "camera.focus_distance"},
      {R"({"camera": {"aperture_radius": 0.1, "f_number": 2}})", "camera.f_number"},
      {R"({"camera": {"ortho_height": 2, "f_number": 2}})", "camera.f_number"},
  };
  for (const auto& [text, key] : bad) {
    try {
      parseScene(text, "x.json");
      ADD_FAILURE() << text << " must be refused";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace penumbra
