// The scene's settings sections: camera, render and photons.
#include "io/scene_sections.h"

namespace penumbra {

namespace {

// Largest photon count accepted: beyond this the photon map alone would need
// tens of gigabytes, which is a typo rather than a plan.
constexpr uint64_t kMaxPhotons = 1'000'000'000;

glm::dvec3 toDouble(const Vec3& v) { return glm::dvec3(v); }

}  // namespace

void readCamera(const JsonNode& node, Camera& out) {
  node.allowKeys({"position", "look_at", "up", "fov", "width", "height", "spp"});
  out.position = node.vec3Or("position", out.position);
  out.lookAt = node.vec3Or("look_at", out.lookAt);
  out.up = node.vec3Or("up", out.up);
  out.fovY = node.floatOr("fov", out.fovY, Range{0.0, 180.0, true, true});
  out.width = node.intOr("width", out.width, 1, 16384);
  out.height = node.intOr("height", out.height, 1, 16384);
  out.spp = node.intOr("spp", out.spp, 1, 4096);

  // Check the frame in double precision: the camera builds its basis from these
  // with a normalize and a cross product, which must not produce NaNs.
  glm::dvec3 view = toDouble(out.lookAt) - toDouble(out.position);
  double viewLength = glm::length(view);
  if (!(viewLength > 0.0) || !std::isfinite(viewLength)) {
    const JsonNode& at = node.has("look_at") ? node.child("look_at") : node;
    at.fail("look_at equals position, so the view direction is undefined");
  }
  glm::dvec3 up = toDouble(out.up);
  double upLength = glm::length(up);
  const JsonNode& upNode = node.has("up") ? node.child("up") : node;
  if (!(upLength > 0.0) || !std::isfinite(upLength)) upNode.fail("up must be non-zero");
  double sine = glm::length(glm::cross(view / viewLength, up / upLength));
  if (!(sine > 1e-6)) upNode.fail("up is parallel to the view direction (look_at - position)");
}

void readRender(const JsonNode& node, RenderSettings& out) {
  node.allowKeys({"model", "max_depth", "background", "ambient", "seed", "min_weight", "shadows",
                  "aov", "light_samples"});
  size_t model = node.enumOr("model", out.model == ShadingModel::Physical, {"classic", "physical"});
  out.model = model == 0 ? ShadingModel::Classic : ShadingModel::Physical;
  out.maxDepth = node.intOr("max_depth", out.maxDepth, 0, 64);
  out.background = node.colorOr("background", out.background);
  out.ambient = node.colorOr("ambient", out.ambient);
  out.seed = node.uintOr("seed", out.seed, 0, std::numeric_limits<uint64_t>::max());
  out.minWeight = node.floatOr("min_weight", out.minWeight, Range::between(0.0, 1.0));
  out.shadows = node.boolOr("shadows", out.shadows);
  // The views the tracer's parseAov() knows; checked here so a typo fails at load time.
  const std::vector<std::string> views = {"beauty", "depth", "normal", "indirect", "direct",
                                          "caustic"};
  if (node.has("aov")) out.aov = views[node.child("aov").asEnum(views)];
  out.lightSamples = node.intOr("light_samples", out.lightSamples, 1, 1024);
}

void readPhotons(const JsonNode& node, PhotonSettings& out) {
  node.allowKeys({"shadow", "indirect", "k_shadow", "k_indirect", "max_radius", "estimator",
                  "sampling", "max_bounces", "gate", "global", "caustic", "k_global", "k_caustic",
                  "passes", "alpha", "radius", "lookup", "lookup_cell"});
  out.shadowPhotons = node.uintOr("shadow", out.shadowPhotons, 0, kMaxPhotons);
  out.indirectPhotons = node.uintOr("indirect", out.indirectPhotons, 0, kMaxPhotons);
  out.kShadow = node.intOr("k_shadow", out.kShadow, 1, 10000);
  out.kIndirect = node.intOr("k_indirect", out.kIndirect, 1, 10000);
  out.maxRadius = node.floatOr("max_radius", out.maxRadius, Range::atLeast(0.0));
  size_t estimator = node.enumOr("estimator", out.estimator == IndirectEstimator::Density,
                                 {"classic", "density"});
  out.estimator = estimator == 0 ? IndirectEstimator::Classic : IndirectEstimator::Density;
  size_t sampling = node.enumOr("sampling", out.sampling == HemisphereSampling::Cosine,
                                {"uniform", "cosine"});
  out.sampling = sampling == 0 ? HemisphereSampling::Uniform : HemisphereSampling::Cosine;
  out.maxBounces = node.intOr("max_bounces", out.maxBounces, 0, 1024);
  if (node.has("gate")) {
    // true / false, or "on" / "off" / "auto".
    JsonNode gate = node.child("gate");
    if (gate.value().is_boolean()) {
      out.gateMode = gate.asBool() ? GateMode::On : GateMode::Off;
    } else if (!gate.value().is_string()) {
      gate.fail("must be true, false, \"on\", \"off\" or \"auto\", got " + gate.value().dump());
    } else {
      const size_t mode = gate.asEnum({"off", "on", "auto"});
      out.gateMode = static_cast<GateMode>(mode);
    }
  }
  out.gate = out.gateMode != GateMode::Off;
  out.globalPhotons = node.uintOr("global", out.globalPhotons, 0, kMaxPhotons);
  out.causticPhotons = node.uintOr("caustic", out.causticPhotons, 0, kMaxPhotons);
  out.kGlobal = node.intOr("k_global", out.kGlobal, 1, 10000);
  out.kCaustic = node.intOr("k_caustic", out.kCaustic, 1, 10000);
  out.passes = node.intOr("passes", out.passes, 1, 100000);
  out.alpha = node.floatOr("alpha", out.alpha, Range{0.0, 1.0, true, false});
  out.radius = node.floatOr("radius", out.radius, Range::atLeast(0.0));
  size_t lookup = node.enumOr("lookup", out.lookup == PhotonLookup::Precomputed,
                              {"exact", "precomputed"});
  out.lookup = lookup == 0 ? PhotonLookup::Exact : PhotonLookup::Precomputed;
  out.lookupCell = node.floatOr("lookup_cell", out.lookupCell, Range{0.05, 8.0, false, false});
}

}  // namespace penumbra
