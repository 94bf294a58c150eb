// A sweep's own long reference: one longer render by the same consistent estimator,
// kept beside the results with a note that says what it is, so a rerun reloads it.
#include "plan/sweep/sweep_reference.h"
#include "plan/sweep/sweep_run.h"
#include "plan/cpu_report.h"
#include "plan/render_session.h"
#include "core/error.h"
#include "core/error_estimate.h"
#include "io/image_io.h"
#include <fmt/format.h>
#include <array>
#include <cstdlib>
#include <filesystem>

namespace penumbra {
namespace {
// The reference's own noise figures, for a rerun that reloads it to mark runs within
// it: over the lighting's pixels and over the whole image (--error-of), in enum order.
constexpr std::array<const char*, 2> kNoiseAttributes = {"penumbra:sweep_reference_lighting_noise_rmse",
                                                         "penumbra:sweep_reference_noise_rmse"};
}  // namespace

Image givenReference(const std::string& path, const std::string& scenePath,
                     const std::vector<std::pair<std::string, const PlannedJob*>>& runs) {
  Image reference = readImage(path);
  for (const auto& [id, job] : runs) {
    const Camera& c = job->scene.camera;
    if (c.width == reference.width && c.height == reference.height) continue;
    throw InputError(fmt::format("--reference {} is {}x{}, but {} renders {}x{} (sweep run '{}')", path, reference.width,
                                 reference.height, scenePath, c.width, c.height, id));
  }
  return reference;
}

namespace {
// What the reference is, as its image records it.
std::string referenceWhat(const SweepRequest& req, const PlannedJob& highest) {
  return fmt::format("{} passes of the run at every knob's highest value ({})",
                     highest.scene.photons.passes * req.referencePasses, req.spec.runs[req.spec.highest].id);
}
}  // namespace

bool referenceSaved(const SweepRequest& req, const PlannedJob& highest, const std::string& saved) {
  return imageComplete(saved) && readImageAttribute(saved, "penumbra:sweep_reference") == referenceWhat(req, highest);
}

LongReference longReference(RenderSession& session, const SweepRequest& req, const PlannedJob& highest,
                            const std::string& saved, const std::function<void()>& rendering) {
  const SweepRun& run = req.spec.runs[req.spec.highest];
  const int passes = highest.scene.photons.passes * req.referencePasses;
  const std::string what = referenceWhat(req, highest);
  LongReference out;
  if (referenceSaved(req, highest, saved)) {
    out.image = readImage(saved);
    out.note = what + ", reloaded from `reference.exr`. " + readImageAttribute(saved, "penumbra:sweep_reference_note");
    const std::string noise = readImageAttribute(saved, kNoiseAttributes[static_cast<size_t>(req.errorOf)]);
    if (!noise.empty()) out.noiseRmse = std::atof(noise.c_str());
    return out;
  }
  std::vector<std::string> overrides = run.overrides;
  overrides.push_back("photons.passes=" + std::to_string(passes));
  JobRequest request;  // no budget: exactly the passes above
  request.scenePath = req.scenePath;
  request.overrides = overrides;
  request.view = req.aov;
  PlannedJob job = session.plan(request);
  session.prepare(job);
  rendering();
  const CpuSpan clock;
  RenderResult r = session.frame(job, session.photons(job));
  const std::string note = fmt::format("Rendered by this sweep in {:.1f} s. Its own error estimate, how far it is "
                                       "from converged: {} (docs/accuracy.md)",
                                       clock.wallSeconds(), describeError(r.stats.error));
  out.note = what + ", saved as `reference.exr`. " + note;
  out.noiseRmse = sweepNoiseRmse(r.stats.error, req.errorOf);
  ImageMetadata meta = {{"penumbra:sweep_reference", what}, {"penumbra:sweep_reference_note", note}};
  for (ErrorFigure figure : {ErrorFigure::Lighting, ErrorFigure::Image}) {
    meta.emplace_back(kNoiseAttributes[static_cast<size_t>(figure)],
                      fmt::format("{:.9g}", sweepNoiseRmse(r.stats.error, figure)));
  }
  writeImage(saved, r.image, meta);
  out.image = std::move(r.image);
  return out;
}

}  // namespace penumbra
