// The scene's settings sections: camera, render and photons.
#include "core/adaptive_sampling.h"
#include "core/view.h"
#include "io/scene_sections.h"

#include "io/camera_checks.h"
#include "io/float_checks.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

// Largest photon count accepted: beyond this the photon map alone would need
// tens of gigabytes, which is a typo rather than a plan.
constexpr uint64_t kMaxPhotons = 1'000'000'000;

// A gather radius: 0 (none given), or one whose square, which the gathers and
// density estimates divide by, is a normal float and finite: 1e-18..1e15 (the
// coordinate limit; a larger radius covers the whole scene anyway).
float gatherRadius(const JsonNode& node, const char* key, float fallback) {
  if (!node.has(key)) return fallback;
  const JsonNode value = node.child(key);
  const float r = value.asFloat(Range::atLeast(0.0));
  if (r != 0.0f && !(r >= 1e-18f && r <= static_cast<float>(kMaxCoordinate))) {
    value.fail("must be 0 or between 1e-18 and 1e+15 (its square must be a normal float), got " +
               describeJson(value.value()));
  }
  return r;
}

}  // namespace

void readCamera(const JsonNode& node, Camera& out, double modelAspect) {
  node.allowKeys({"position", "look_at", "up", "fov", "width", "height", "spp", "ortho_height", "aperture_radius",
                  "f_number", "focus_distance"});
  if (node.has("position")) out.position = readPosition(node.child("position"));
  if (node.has("look_at")) out.lookAt = readPosition(node.child("look_at"));
  out.up = node.vec3Or("up", out.up);
  out.fovY = node.floatOr("fov", out.fovY, Range{0.0, 180.0, true, true});
  out.width = node.intOr("width", out.width, 1, 16384);
  out.height = node.intOr("height", out.height, 1, 16384);
  out.spp = node.intOr("spp", out.spp, 1, 4096);
  // An orthographic camera: the view's height in scene units.
  out.orthoHeight = node.floatOr("ortho_height", out.orthoHeight, Range::atLeast(0.0));
  // The thin lens (core/thin_lens.h); a model file's camera takes them from -D.
  out.apertureRadius = node.floatOr("aperture_radius", out.apertureRadius, Range::atLeast(0.0));
  out.fNumber = node.floatOr("f_number", out.fNumber, Range::above(0.0));
  out.focusDistance = node.floatOr("focus_distance", out.focusDistance, Range::above(0.0));
  // A new width keeps a model file's aspect ratio; checked below with the rest (the
  // height sets an orthographic camera's pixel step).
  if (modelAspect > 0.0 && node.has("width") && !node.has("height")) {
    out.height = std::clamp(static_cast<int>(std::lround(out.width / modelAspect)), 1, 16384);
  }

  // The checks every camera meets (io/camera_checks.h), failing at the key at fault.
  const CameraProblem problem = cameraProblem(out);
  if (!problem.message.empty()) {
    (node.has(problem.key.c_str()) ? node.child(problem.key) : node).fail(problem.message);
  }
}

void readRender(const JsonNode& node, RenderSettings& out) {
  node.allowKeys({"model", "max_depth", "background", "ambient", "seed", "min_weight", "shadows",
                  "aov", "light_samples", "packets", "transparent_background", "adaptive", "adaptive_threshold",
                  "adaptive_max_spp", "volume_samples", "medium"});  // medium: io/media_reader.h
  std::vector<std::string> models;
  for (const ShadingModelInfo& m : kShadingModels) models.push_back(m.name);
  out.model = static_cast<ShadingModel>(node.enumOr("model", static_cast<size_t>(out.model), models));
  out.maxDepth = node.intOr("max_depth", out.maxDepth, 0, 64);
  out.background = node.colorOr("background", out.background);
  out.ambient = node.colorOr("ambient", out.ambient);
  out.seed = node.uintOr("seed", out.seed, 0, std::numeric_limits<uint64_t>::max());
  out.minWeight = node.floatOr("min_weight", out.minWeight, Range::between(0.0, 1.0));
  out.shadows = node.boolOr("shadows", out.shadows);
  // Checked here so a typo fails at load time.
  std::vector<std::string> views(kViewNames.begin(), kViewNames.end());
  views.insert(views.end(), kDerivedViewNames.begin(), kDerivedViewNames.end());
  if (node.has("aov")) out.aov = views[node.child("aov").asEnum(views)];
  out.lightSamples = node.intOr("light_samples", out.lightSamples, 1, 1024);
  out.volumeSamples = node.intOr("volume_samples", out.volumeSamples, 1, 1024);
  out.packets = node.boolOr("packets", out.packets);
  out.transparentBackground = node.boolOr("transparent_background", out.transparentBackground);
  if (node.has("adaptive")) out.adaptive = node.boolOr("adaptive", false);
  out.adaptiveThreshold = node.floatOr("adaptive_threshold", out.adaptiveThreshold, Range::between(0.1, 1000.0));
  out.adaptiveMaxSpp = node.intOr("adaptive_max_spp", out.adaptiveMaxSpp, 1, kAdaptiveSppLimit);
}

void readPhotons(const JsonNode& node, PhotonSettings& out) {
  node.allowKeys({"shadow", "indirect", "k_shadow", "k_indirect", "max_radius", "estimator",
                  "sampling", "max_bounces", "gate", "global", "caustic", "k_global", "k_caustic",
                  "passes", "alpha", "radius", "lookup", "lookup_cell", "volume", "k_volume", "volume_radius"});
  out.shadowPhotons = node.uintOr("shadow", out.shadowPhotons, 0, kMaxPhotons);
  out.indirectPhotons = node.uintOr("indirect", out.indirectPhotons, 0, kMaxPhotons);
  out.kShadow = node.intOr("k_shadow", out.kShadow, 1, 10000);
  out.kIndirect = node.intOr("k_indirect", out.kIndirect, 1, 10000);
  out.maxRadius = gatherRadius(node, "max_radius", out.maxRadius);
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
  out.globalPhotons = node.uintOr("global", out.globalPhotons, 0, kMaxPhotons);
  out.causticPhotons = node.uintOr("caustic", out.causticPhotons, 0, kMaxPhotons);
  out.kGlobal = node.intOr("k_global", out.kGlobal, 1, 10000);
  out.kCaustic = node.intOr("k_caustic", out.kCaustic, 1, 10000);
  out.passes = node.intOr("passes", out.passes, 1, 100000);
  out.alpha = node.floatOr("alpha", out.alpha, Range{0.0, 1.0, true, false});
  out.radius = gatherRadius(node, "radius", out.radius);
  out.volumePhotons = node.uintOr("volume", out.volumePhotons, 0, kMaxPhotons);
  out.kVolume = node.intOr("k_volume", out.kVolume, 1, 10000);
  out.volumeRadius = gatherRadius(node, "volume_radius", out.volumeRadius);
  // In PhotonLookup's order.
  out.lookup = static_cast<PhotonLookup>(
      node.enumOr("lookup", static_cast<size_t>(out.lookup), {"exact", "precomputed", "auto"}));
  out.lookupCell = node.floatOr("lookup_cell", out.lookupCell, Range{0.05, 8.0, false, false});
}

}  // namespace penumbra
