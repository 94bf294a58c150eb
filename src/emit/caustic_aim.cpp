// The caustic pass's aim: per light, cones (point, area) or discs (directional) towards
// the specular targets, one drawn per photon in proportion to its measure.
#include "emit/caustic_aim.h"
#include "core/sampling.h"
#include "emit/emit.h"
#include <algorithm>

namespace penumbra {

namespace {

// Photons that measure an area light's share, its budget weight, to 2-4% (1 sigma: their
// factors spread about twice their mean); only the split between lights depends on it.
constexpr int kShareSamples = 4096;

// A target as seen from a point outside it: the cone's axis and 1 - cos of its half-angle
// (as sin^2 / (1 + cos): the subtraction would cancel for a small or distant target).
struct Cone {
  Vec3 axis{0.0f};
  float oneMinusCos = 2.0f;  // inside the target: every direction
  bool inside = true;
};

Cone coneTo(const SceneSphere& t, const Vec3& from) {
  Cone cone;
  const Vec3 c = t.center - from;
  const float d2 = glm::dot(c, c), r2 = t.radius * t.radius;
  if (!(d2 > r2)) return cone;
  const float sin2 = r2 / d2, d = std::sqrt(d2);
  cone.axis = c / d;
  cone.oneMinusCos = sin2 / (1.0f + std::sqrt(std::max(0.0f, 1.0f - sin2)));
  cone.inside = false;
  return cone;
}

// A direction uniform in the cone (the whole sphere from inside the target).
Vec3 sampleCone(const Cone& cone, float u1, float u2) {
  if (cone.inside) return uniformSphere(u1, u2);
  const float t = u1 * cone.oneMinusCos;
  const float cosT = 1.0f - t, sinT = std::sqrt(std::max(0.0f, t * (2.0f - t))), phi = 2.0f * kPi * u2;
  return toWorld(Vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT), cone.axis);
}

// Whether the line from `from` along `dir` passes within the target: ahead of `from`
// (a cone) or either way (`line`: a directional light's disc). |c x dir|^2 is the
// squared distance from the centre without cancelling |c|^2 - along^2.
bool crosses(const SceneSphere& t, const Vec3& from, const Vec3& dir, bool line) {
  const Vec3 c = t.center - from;
  const float r2 = t.radius * t.radius;
  if (glm::dot(c, c) <= r2) return true;
  const Vec3 x = glm::cross(c, dir);
  return glm::dot(x, x) <= r2 && (line || glm::dot(c, dir) > 0.0f);
}

// The index `u` picks from `measure` in proportion.
size_t pick(const std::vector<float>& measure, float total, float u) {
  float left = u * total;
  size_t j = 0;
  while (j + 1 < measure.size() && left >= measure[j]) left -= measure[j++];
  return j;
}

// A delta light: fixed cones or discs, the full measure 4 pi or the scene's disc.
float sampleDelta(const Light& light, const SceneSphere& bounds, const CausticAim& aim, Rng& rng, PhotonRay& r) {
  const std::vector<SceneSphere>& targets = *aim.targets;
  const SceneSphere& t = targets[pick(aim.measure, aim.total, rng.uniform())];
  const float u1 = rng.uniform(), u2 = rng.uniform();
  const bool point = lightTraits(light).aim == AimKind::Cone;  // else a disc along its direction
  if (point) {
    r.dir = sampleCone(coneTo(t, light.position), u1, u2);
    r.origin = photonOrigin(light, r, bounds);
  } else {
    const float rad = t.radius * std::sqrt(u1), phi = 2.0f * kPi * u2;
    Vec3 tt, bb;
    orthonormalBasis(light.direction, tt, bb);
    const float back = glm::dot(t.center - bounds.center, light.direction) + SceneSphere::kSkyStart * bounds.radius;
    r.origin = t.center - light.direction * back + rad * (std::cos(phi) * tt + std::sin(phi) * bb);
    r.dir = light.direction;
  }
  const Vec3 from = point ? light.position : r.origin;
  int n = 0;
  for (const SceneSphere& s : targets) n += crosses(s, from, r.dir, !point);
  if (n == 0) return 0.0f;  // rounding at a cone's rim
  const float full = point ? 4.0f * kPi : kPi * bounds.radius * bounds.radius;
  return aim.total / (full * static_cast<float>(n));
}

// Whether target t is not wholly behind the emitting side at y (normal n).
bool facing(const SceneSphere& t, const Vec3& y, const Vec3& n) { return glm::dot(t.center - y, n) >= -t.radius; }

// A sphere light's cap facing target t: the normals n with dot(n, axis) >= cos, as
// facing() says of the point centre + radius x n; 1 - cos in [0, 2].
Cone capFacing(const Light& light, const SceneSphere& t) {
  Cone cap;
  const Vec3 c = t.center - light.position;
  const float d = glm::length(c);
  if (!(d > 0.0f)) {  // concentric: a target inside the light faces none of it
    cap.oneMinusCos = light.radius > t.radius ? 0.0f : 2.0f;
    return cap;
  }
  cap.axis = c / d;
  cap.oneMinusCos = std::clamp(1.0f - (light.radius - t.radius) / d, 0.0f, 2.0f);
  cap.inside = cap.oneMinusCos >= 2.0f;
  return cap;
}

// Where an area light's photon starts, and the unaimed start density (uniform by area)
// over this one's. A quad or mesh starts as unaimed (ratio 1). A sphere light starts
// on a cap that faces a target, picked by aim.measure, uniform in it, since elsewhere
// every target is behind the start; its density is the mixture of the caps holding it.
float startOf(const Light& light, const SceneSphere& bounds, const CausticAim& aim, Rng& rng, PhotonRay& start) {
  if (lightTraits(light).aim != AimKind::SphereCaps) {
    const float u1 = rng.uniform(), u2 = rng.uniform();
    start = sampleLightPhoton(light, bounds, u1, u2, 0.5f, 0.5f);
    return 1.0f;
  }
  const std::vector<SceneSphere>& targets = *aim.targets;
  const Cone cap = capFacing(light, targets[pick(aim.measure, aim.total, rng.uniform())]);
  const float u1 = rng.uniform(), u2 = rng.uniform();
  start = SphereLight::start(light, sampleCone(cap, u1, u2));
  double density = 0.0;  // per unit of the sphere's area 4 pi r^2
  for (size_t k = 0; k < targets.size(); ++k) {
    if (aim.measure[k] > 0.0f && facing(targets[k], start.origin, start.normal)) {
      density += double(aim.measure[k]) / aim.total * 2.0 / capFacing(light, targets[k]).oneMinusCos;
    }
  }
  return density > 0.0 ? static_cast<float>(1.0 / density) : 0.0f;
}

// An area light: a start y (startOf), then a direction from the cones of the targets
// facing y, in proportion to their solid angles. Unaimed, the direction's density is
// cos / pi about y's normal; aimed, (cones containing it) / (their total solid angle).
float sampleArea(const Light& light, const SceneSphere& bounds, const CausticAim& aim, Rng& rng, PhotonRay& r,
                 std::vector<float>& omega) {
  const std::vector<SceneSphere>& targets = *aim.targets;
  PhotonRay start;
  const float startRatio = startOf(light, bounds, aim, rng, start);
  const Vec3 y = start.origin, n = start.normal;
  omega.resize(targets.size());
  float total = 0.0f;
  for (size_t j = 0; j < targets.size(); ++j) {
    omega[j] = facing(targets[j], y, n) ? 2.0f * kPi * coneTo(targets[j], y).oneMinusCos : 0.0f;
    total += omega[j];
  }
  if (!(total > 0.0f) || !(startRatio > 0.0f)) return 0.0f;
  const size_t j = pick(omega, total, rng.uniform());
  const float u3 = rng.uniform(), u4 = rng.uniform();
  r = start;
  r.dir = sampleCone(coneTo(targets[j], y), u3, u4);
  const float cosTheta = glm::dot(r.dir, n);
  if (!(cosTheta > 0.0f)) return 0.0f;  // behind the emitting side
  int covering = 0;
  for (size_t k = 0; k < targets.size(); ++k) covering += omega[k] > 0.0f && crosses(targets[k], y, r.dir, false);
  if (covering == 0) return 0.0f;
  r.origin = offsetRayOrigin(y, n, start.error, r.dir);
  return startRatio * cosTheta * total / (kPi * static_cast<float>(covering));
}

}  // namespace

bool aimsCausticPhotons(const Light& light) {
  // A spot shares the point light's type, but its cone would cut the aim.
  return lightTraits(light).aim != AimKind::None && !light.isSpot();
}

CausticAim aimAt(const Light& light, const std::vector<SceneSphere>& targets, const SceneSphere& bounds,
                 uint64_t key) {
  CausticAim aim;
  aim.targets = &targets;
  if (!aimsCausticPhotons(light) || targets.empty()) return aim;
  if (isDeltaLight(light)) {
    const bool point = lightTraits(light).aim == AimKind::Cone;
    for (const SceneSphere& t : targets) {
      aim.measure.push_back(point ? 2.0f * kPi * coneTo(t, light.position).oneMinusCos : kPi * t.radius * t.radius);
      aim.total += aim.measure.back();
    }
    const float full = point ? 4.0f * kPi : kPi * bounds.radius * bounds.radius;
    aim.share = std::min(1.0, double(aim.total) / full);
    return aim;
  }
  if (lightTraits(light).aim == AimKind::SphereCaps) {  // its caps, by their targets' solid angles from its centre
    for (const SceneSphere& t : targets) {
      const bool faces = capFacing(light, t).oneMinusCos > 0.0f;
      aim.measure.push_back(faces ? 2.0f * kPi * coneTo(t, light.position).oneMinusCos : 0.0f);
      aim.total += aim.measure.back();
    }
    if (!(aim.total > 0.0f)) return aim;
  }
  // The mean factor over aimed photons is the share of unaimed photons that would head
  // for a target: measured, since it varies over the light's surface.
  Rng rng(key);
  std::vector<float> scratch;
  PhotonRay r;
  double sum = 0.0;
  for (int i = 0; i < kShareSamples; ++i) {
    const float factor = sampleArea(light, bounds, aim, rng, r, scratch);
    if (factor > 0.0f) sum += factor * luminance(r.weight);
  }
  aim.share = std::min(1.0, sum / kShareSamples);
  return aim;
}

float sampleAimed(const Light& light, const SceneSphere& bounds, const CausticAim& aim, Rng& rng,
                  PhotonRay& r, std::vector<float>& scratch) {
  if (aim.targets == nullptr || aim.targets->empty()) return 0.0f;
  return isDeltaLight(light) ? sampleDelta(light, bounds, aim, rng, r)
                             : sampleArea(light, bounds, aim, rng, r, scratch);
}

}  // namespace penumbra
