// Area lights aim their caustic photons at the specular objects as point lights do:
// a glass sphere over a floor, lit from above by a point, quad, sphere or mesh light,
// gets the same caustic power per watt heading for it, and most aimed photons are
// stored; an aimed photon's mean power factor is the share of unaimed ones that head
// for the targets (overlapping cones, targets cut by or behind the emitting side).
#include "core/emission_map.h"
#include "support/emit_fixtures.h"
#include "core/math.h"
#include "core/lights/emissive_mesh.h"
#include "core/rng.h"
#include "emit/caustic_aim.h"
#include "emit/emit_physical.h"
#include "io/scene_loader.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>

namespace penumbra {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// A glass sphere (R = 0.5, ior 1.5) centred 1 above a 40 x 40 Lambert floor; the light
// is centred D = 4 above the sphere's centre, at (0, 5, 0).
constexpr double kR = 0.5, kD = 4.0;

std::string sceneWith(const std::string& light, const std::string& extraObject = "",
                      const std::string& extraMaterial = "") {
  return R"({
  "camera": {"position": [0, 3, 8], "look_at": [0, 1, 0], "width": 16, "height": 16},
  "lights": [)" + light + R"(],
  "materials": {"floor": {"diffuse": 0.5}, "glass": {"diffuse": 0, "transparent": {"ior": 1.5}})" +
         extraMaterial + R"(},
  "objects": [
    {"type": "quad", "corner": [-20, 0, 20], "edge1": [40, 0, 0], "edge2": [0, 0, -40], "material": "floor"},
    {"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "glass"})" +
         extraObject + R"(],
  "render": {"model": "physical", "seed": 11},
  "photons": {"gate": false, "global": 0, "caustic": 200000, "max_bounces": 16}
})";
}

// A square of side 0.4 centred on the light's place, emitting downwards (edge1 x edge2 = -y).
const char* kSquare = R"("corner": [-0.2, 5, -0.2], "edge1": [0.4, 0, 0], "edge2": [0, 0, 0.4])";
constexpr double kHalfSide = 0.2, kSphereLightRadius = 0.1;

struct Caustic {
  double power = 0.0;   // stored caustic power (green: the lights are white)
  double stored = 0.0;  // stored photons per emitted
};

Caustic causticOf(const std::string& json) {
  const testing::ScratchDir scratch;
  const std::string file = (scratch.path() / "scene.json").string();
  std::ofstream(file) << json;
  const Scene scene = loadScene(file);
  const TraceScene tracer(scene);
  const EmittedPhotons photons = emitPhysicalPhotons(scene, tracer, 0, sceneEmit(scene));
  return {photons.tally[MapKind::Caustic].stored[MapKind::Caustic].g,
          double(photons.batches.get<MapKind::Caustic>().size()) / double(photons.emitted[MapKind::Caustic])};
}

TEST(CausticAim, AreaLightsGiveThePointLightsCausticPerWattTowardsTheSphere) {
  // The flux each light sends towards the sphere, analytically:
  //  - point (I): I 2 pi (1 - cos alpha), sin alpha = R / D;
  //  - quad and its mesh twin (L = 1, half-side a): every point of the square sees the
  //    whole sphere above its horizon, so it sends L pi sin^2 alpha' cos beta' =
  //    L pi R^2 D / d^3 per unit area; over the square that is L pi R^2 Omega_sq, the
  //    square's solid angle from the sphere's centre, 4 atan(a^2 / (D sqrt(2 a^2 + D^2)));
  //  - sphere light (L = 1, radius rho): outside, a Lambertian sphere's field is a point
  //    light's of I = pi rho^2 L at its centre (up to the ~(rho / D)^2 where part of it
  //    sinks below a point's horizon), so pi rho^2 L 2 pi (1 - cos alpha).
  // The caustic is that flux times the share of it glass sends to the floor; the lights'
  // photons meet the sphere from directions within atan(a / D) = 3 degrees of each
  // other, which changes that share by far less than the noise. Noise: 200k aimed
  // photons, ~90% stored, each of one power (point) or within a few % of it (the
  // others' factor cos x Omega / pi varies that little over the square): ~0.1%
  // (1 sigma) per light. Tolerance 2%, as asked.
  const double oneMinusCos = 1.0 - std::sqrt(1.0 - kR * kR / (kD * kD));
  const double omegaSquare =
      4.0 * std::atan(kHalfSide * kHalfSide / (kD * std::sqrt(2.0 * kHalfSide * kHalfSide + kD * kD)));
  const double towardsQuad = kPiD * kR * kR * omegaSquare;
  const double I = 2.0;
  const Caustic point = causticOf(sceneWith(R"({"type": "point", "position": [0, 5, 0], "intensity": 2})"));
  const double perWatt = point.power / (I * 2.0 * kPiD * oneMinusCos);
  ASSERT_GT(perWatt, 0.5);
  EXPECT_GT(point.stored, 0.85);
  std::printf("point light: %.1f%% of photons stored\n", 100.0 * point.stored);

  struct Case {
    const char* name;
    Caustic caustic;
    double towards;
  };
  const double rho = kSphereLightRadius;
  const Case cases[] = {
      {"quad", causticOf(sceneWith(std::string(R"({"type": "quad", )") + kSquare + R"(, "radiance": 1})")),
       towardsQuad},
      {"sphere",
       causticOf(sceneWith(R"({"type": "sphere", "center": [0, 5, 0], "radius": 0.1, "radiance": 1})")),
       kPiD * rho * rho * 2.0 * kPiD * oneMinusCos},
      {"mesh",
       causticOf(sceneWith("",
                           std::string(R"(, {"type": "quad", )") + kSquare + R"(, "material": "lamp"})",
                           R"(, "lamp": {"emission": 1})")),
       towardsQuad},
  };
  for (const Case& c : cases) {
    const double ratio = c.caustic.power / c.towards / perWatt;
    std::printf("%s light: caustic per watt towards the sphere %.4f of the point light's; %.1f%% of photons stored\n",
                c.name, ratio, 100.0 * c.caustic.stored);
    EXPECT_NEAR(ratio, 1.0, 0.02) << c.name;
  }
  // Stored per emitted photon; unaimed, a quad's would be sin^2 alpha = 1.6% at most.
  // A sphere light starts on the caps that face the target, whose rims see it partly
  // below their horizon: fewer of its photons head for it.
  EXPECT_GT(cases[0].caustic.stored, 0.85);
  EXPECT_GT(cases[1].caustic.stored, 0.7);
  EXPECT_GT(cases[2].caustic.stored, 0.85);
}

// Whether the line from `o` along unit `d` passes within t ahead of o (or o is in t).
bool crossesTarget(const SceneSphere& t, const Vec3& o, const Vec3& d) {
  const glm::dvec3 c = glm::dvec3(t.center) - glm::dvec3(o), dir(d);
  const double r2 = double(t.radius) * t.radius, along = glm::dot(c, dir);
  return glm::dot(c, c) <= r2 || (along > 0.0 && glm::dot(c, c) - along * along <= r2);
}

// Mean and standard error per channel of values added one at a time.
struct Mean {
  glm::dvec3 sum{0.0}, squares{0.0};
  void add(const glm::dvec3& v) {
    sum += v;
    squares += v * v;
  }
  glm::dvec3 mean(int n) const { return sum / double(n); }
  glm::dvec3 sd(int n) const { return glm::sqrt(glm::max(squares / double(n) - mean(n) * mean(n), 0.0) / double(n)); }
};

TEST(CausticAim, MeanPowerFactorIsTheUnaimedShareHeadingForTheTargets) {
  // An aimed photon's power is the unaimed one's times its factor, the unaimed density
  // over the aimed one, so their mean is the unaimed photons' power whose first line
  // meets a target. Targets: two whose cones overlap (a direction in both is counted
  // once), one cut by the quad's plane (half of its cone is behind the emitting side),
  // one wholly behind the quad (left out of its mixture; the sphere light's top faces
  // it). A textured two-sided mesh light's photons carry texel / density. Brute force:
  // 2M unaimed photons per light (sd ~0.3% of the share); aimed: 400k photons, the sd
  // of their mean from their own spread. Tolerance 4 sd, per channel.
  const std::vector<SceneSphere> targets = {
      {Vec3(0.0f, 0.5f, 0.0f), 0.4f}, {Vec3(0.3f, 0.9f, 0.1f), 0.3f},
      {Vec3(1.5f, 2.05f, 0.0f), 0.3f}, {Vec3(0.0f, 5.0f, 0.0f), 0.5f}};
  const SceneSphere bounds{Vec3(0.0f, 1.0f, 0.0f), 10.0f};
  Light quad;
  quad.type = LightType::Quad;
  quad.position = Vec3(-0.5f, 2.0f, -0.5f);
  quad.edge1 = Vec3(1.0f, 0.0f, 0.0f);
  quad.edge2 = Vec3(0.0f, 0.0f, 1.0f);  // edge1 x edge2 = -y: it shines down
  Light sphere;
  sphere.type = LightType::Sphere;
  sphere.position = Vec3(0.0f, 2.0f, 0.0f);
  sphere.radius = 0.3f;
  // Two triangles of a square tilted 30 degrees, shining down and to -x.
  const Vec3 a(-0.6f, 2.2f, -0.5f), b(-0.6f, 2.2f, 0.5f), e(0.866f, -0.5f, 0.0f);
  const std::vector<Vec3> square = {a, b + e, b, a, a + e, b + e};
  const Light mesh = makeMeshLight(square, Color(1.0f), 0);
  ASSERT_LT(glm::cross(e, b - a).y, 0.0f);
  EmissionMap map;
  map.width = map.height = 2;
  map.texels = {Color(4.0f, 2.0f, 1.0f), Color(0.05f), Color(0.0f, 2.0f, 0.0f), Color(1.0f)};
  const std::vector<Vec2> uvs = {Vec2(0, 0), Vec2(1, 1), Vec2(0, 1), Vec2(0, 0), Vec2(1, 0), Vec2(1, 1)};
  Light textured = makeMeshLight(square, Color(1.0f), 0, uvs, &map);
  textured.twoSided = true;

  for (const Light* light : {&std::as_const(quad), &std::as_const(sphere), &mesh, &std::as_const(textured)}) {
    const std::string name = light == &textured ? "textured mesh" : std::to_string(int(light->type));
    Rng brute(hashKey(3, 1));
    constexpr int kUnaimed = 2000000, kAimed = 400000;
    Mean unaimed, aimed;
    for (int i = 0; i < kUnaimed; ++i) {
      const float u1 = brute.uniform(), u2 = brute.uniform(), u3 = brute.uniform(), u4 = brute.uniform();
      const PhotonRay r = sampleLightPhoton(*light, bounds, u1, u2, u3, u4);
      bool hit = false;
      for (const SceneSphere& t : targets) hit = hit || crossesTarget(t, r.origin, r.dir);
      unaimed.add(hit ? glm::dvec3(r.weight) : glm::dvec3(0.0));
    }
    const CausticAim aim = aimAt(*light, targets, bounds, hashKey(3, 2));
    Rng rng(hashKey(3, 3));
    std::vector<float> scratch;
    for (int i = 0; i < kAimed; ++i) {
      PhotonRay r;
      const double f = sampleAimed(*light, bounds, aim, rng, r, scratch);
      aimed.add(f > 0.0 ? f * glm::dvec3(r.weight) : glm::dvec3(0.0));
      if (f > 0.0) {  // within float rounding of a cone's rim (1e-5 of the radius)
        bool hit = false;
        for (const SceneSphere& t : targets) {
          hit = hit || crossesTarget({t.center, t.radius * 1.00001f}, r.origin, r.dir);
        }
        ASSERT_TRUE(hit) << name << ": an aimed photon with power heads for no target";
      }
    }
    const glm::dvec3 want = unaimed.mean(kUnaimed), got = aimed.mean(kAimed);
    const glm::dvec3 sd = glm::sqrt(unaimed.sd(kUnaimed) * unaimed.sd(kUnaimed) + aimed.sd(kAimed) * aimed.sd(kAimed));
    std::printf("%s light: unaimed share (g) %.5f, mean aimed factor %.5f (sd %.5f), budget share %.4f\n",
                name.c_str(), want.g, got.g, sd.g, aim.share);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 4.0 * sd[c]) << name << " channel " << c;
    const double share = luminance(Color(want));
    EXPECT_NEAR(aim.share, share, 0.15 * share) << name;  // 4096 photons: <= 4% sd
  }
}

}  // namespace
}  // namespace penumbra
