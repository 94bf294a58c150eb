// What a rendered image's header says about how it was made: a short summary in
// every file, and in EXR files every setting that changes the image.
#pragma once
#include "core/scene.h"
#include "core/stats.h"
#include "io/image_io.h"
#include "plan/render_plan.h"
#include <string>

namespace penumbra {

// The attributes for the image of `scene` with the decisions of `plan`, rendered as view
// `aov`, written to `outputPath`. Every file: penumbra:scene, scene_file, aov, model
// and settings (one summary line). An EXR adds one penumbra:KEY per setting (listed
// in docs/scene-format.md, "Image metadata"); a PNG does not, so its bytes stay those
// of earlier versions. No value names a path beyond the scene file as given.
// The error figure's keys, as renderMetadata writes them: penumbra:error, and
// penumbra:error.noise_rmse, .lower_bound and .bias_rmse where known.
ImageMetadata errorMetadata(const ErrorEstimate& error);

ImageMetadata renderMetadata(const Scene& scene, const RenderPlan& plan, const RenderStats& stats,
                             const std::string& aov, const std::string& outputPath);

}  // namespace penumbra
