// A tile's part file: its pixels, its share of the error figure, and the metadata the
// merged frame will carry, under the keys penumbra:part.* (docs/tiles.md).
#pragma once
#include "core/pixel_bounds.h"
#include "io/image_io.h"
#include "plan/pipeline.h"
#include <string>
#include <vector>

namespace penumbra {

// The part keys. part.job is the frame's identity: equal in every part of one frame.
inline constexpr const char* kPartJob = "penumbra:part.job";
inline constexpr const char* kPartFrame = "penumbra:part.frame";          // "WxH"
inline constexpr const char* kPartBounds = "penumbra:part.bounds";        // "x0,x1,y0,y1"
inline constexpr const char* kPartContent = "penumbra:part.content";      // radiance, depth, normal
inline constexpr const char* kPartError = "penumbra:part.error";          // "SOURCE COUNT SHARED"
inline constexpr const char* kPartBias = "penumbra:part.bias";            // "PASSES HALF" of the bias check
inline constexpr const char* kPartProbes = "penumbra:part.probes";        // "SQUARES PROBED" (hex float)
inline constexpr const char* kPartExrKeys = "penumbra:part.exr_keys";     // the merged EXR's keys, in order
inline constexpr const char* kPartPngKeys = "penumbra:part.png_keys";     // the merged PNG's keys, in order

// The layer of the pixels that see an emitter (1, else 0): the lighting's figures leave them out.
inline constexpr const char* kEmitterLayer = "emitters";
Image emitterLayer(const EmitterMask& mask, int width, int height);
// The layers of the gathers' smoothing probes, by pass modulo 4 (SmoothingSums).
inline constexpr const char* kSmoothingLayers[SmoothingSums::kGroups] = {"smoothing_0", "smoothing_1", "smoothing_2",
                                                                         "smoothing_3"};
EmitterMask emitterMaskOf(const Image& layer);

// Tile I of N's file for a job output: "out/frame.png" -> "out/frame.tile2of4.exr".
std::string tilePartPath(const std::string& output, int index, int count);

// The stamp of a render command's frame: scene path, overrides (--seed, --spp, -D,
// --gate), plan overrides, --no-defaults and view; jobStamp's hash (plan/batch/job_state.h).
std::string renderFrameStamp(const std::string& scenePath, const std::vector<std::string>& overrides,
                             const std::vector<std::string>& options, const std::string& view);

// Writes the part of `result` inside `bounds` to `path` (.exr, float). `frameStamp`:
// the frame's identity; `exr` and `png`: the metadata of the whole frame written as
// EXR or PNG (its error keys are replaced by the merge's); `own`: the part file's own
// keys on top (a batch's penumbra:job).
void writeFramePart(const std::string& path, const RenderResult& result, const PixelBounds& bounds,
                    const std::string& frameStamp, const ImageMetadata& exr, const ImageMetadata& png,
                    const ImageMetadata& own = {});

}  // namespace penumbra
