// The one reader of render.model: every stage asks modelOf for the model's facts.
#include "core/shading_model.h"
#include "core/scene.h"

namespace penumbra {

static_assert(kShadingModels[size_t(ShadingModel::Classic)].id == ShadingModel::Classic &&
                  kShadingModels[size_t(ShadingModel::Physical)].id == ShadingModel::Physical,
              "kShadingModels is indexed by ShadingModel");

const ShadingModelInfo& modelOf(const RenderSettings& render) { return shadingModelInfo(render.model); }

}  // namespace penumbra
