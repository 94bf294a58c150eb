// The one reader of render.model: every stage asks modelOf for the model's facts.
#include "core/shading_model.h"
#include "core/scene.h"

namespace penumbra {

const ShadingModelInfo& modelOf(const RenderSettings& render) { return shadingModelInfo(render.model); }

}  // namespace penumbra
