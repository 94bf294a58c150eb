// Which pixels see an emitter (an area light, an emitting surface or the environment)
// directly or through mirrors and glass: their edges alias under the camera's samples
// and they carry no photon-map light, so the lighting's error figures leave them out.
#pragma once
#include "core/error_estimate.h"
#include "core/pixel_bounds.h"
#include "trace/shading.h"

namespace penumbra {

// A pixel's rays: a fixed kEmitterGrid x kEmitterGrid grid of its area. A pixel next to
// one whose grid met an emitter counts too: an edge that covers less than a grid cell
// of a pixel is caught by its neighbour.
constexpr int kEmitterGrid = 3;

// The mask of the frame (0 outside `bounds` when given), deterministic for any thread
// count; empty for the classic model, whose emitters are not told apart. Its rays are
// not counted in the render's.
EmitterMask emitterMask(const ShadingContext& ctx, const PixelBounds* bounds = nullptr);

}  // namespace penumbra
