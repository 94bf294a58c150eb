// The transport models a scene can render in (render.model), their names and the
// default, defined once for the loader, the plan, the integrators and the reports.
#pragma once
#include <array>
#include <cstddef>

namespace penumbra {

// classic: the report's Whitted + Phong model with its ambient term and photon
// roulette; physical: radiometric BSDFs and lights, caustic and global photon maps.
enum class ShadingModel { Classic, Physical };

// In enum order: render.model's values.
inline constexpr std::array<const char*, 2> kShadingModelNames = {"classic", "physical"};

// What a scene that says nothing renders in: the report's scenes are classic.
inline constexpr ShadingModel kDefaultShadingModel = ShadingModel::Classic;

inline const char* shadingModelName(ShadingModel model) { return kShadingModelNames[static_cast<size_t>(model)]; }

}  // namespace penumbra
