// The transport models a scene can render in (render.model): their names, their
// BSDF family and the default, defined once; modelOf is the one reader of the choice.
#pragma once
#include "core/bsdf_family.h"
#include <array>
#include <cstddef>

namespace penumbra {

// classic: the report's Whitted + Phong model with its ambient term and photon
// roulette; physical: radiometric BSDFs and lights, caustic and global photon maps.
enum class ShadingModel { Classic, Physical };

struct ShadingModelInfo {
  ShadingModel id;
  const char* name;  // render.model's value
  BsdfFamily bsdf;   // what its integrator, emitter and loaders make of a material
};

// In enum order.
inline constexpr std::array<ShadingModelInfo, 2> kShadingModels = {{
    {ShadingModel::Classic, "classic", BsdfFamily::Phong},
    {ShadingModel::Physical, "physical", BsdfFamily::Radiometric},
}};

// What a scene that says nothing renders in: the report's scenes are classic.
inline constexpr ShadingModel kDefaultShadingModel = ShadingModel::Classic;
// ... and a glTF or OBJ file given as the scene: its materials are meant physically
// (io/scene_defaults.h applies it where render.model is not set).
inline constexpr ShadingModel kModelFileShadingModel = ShadingModel::Physical;

inline constexpr const ShadingModelInfo& shadingModelInfo(ShadingModel model) {
  return kShadingModels[static_cast<size_t>(model)];
}
inline constexpr const char* shadingModelName(ShadingModel model) { return shadingModelInfo(model).name; }

// The model a scene's settings choose (core/shading_model.cpp).
struct RenderSettings;
const ShadingModelInfo& modelOf(const RenderSettings& render);

}  // namespace penumbra
