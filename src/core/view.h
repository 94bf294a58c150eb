// The views a render can write (render.aov, --aov, batch "views") and their names,
// defined once for the loader, the plan and the tracer.
#pragma once
#include "core/error.h"
#include <array>
#include <cstddef>
#include <string>

namespace penumbra {

// Indirect is the ambient/indirect term (classic) or the global map (physical);
// Direct and Caustic exist in the physical model only.
enum class Aov { Beauty, Depth, Normal, Indirect, Direct, Caustic };

// In enum order.
inline constexpr std::array<const char*, 6> kViewNames = {"beauty", "depth", "normal", "indirect", "direct",
                                                          "caustic"};

inline const char* viewName(Aov aov) { return kViewNames[static_cast<size_t>(aov)]; }

// Depth and normals are geometry: they carry no light, so no photons, passes or budget.
inline bool readsLight(Aov aov) { return aov != Aov::Depth && aov != Aov::Normal; }

// The "error" view renders the beauty and writes its per-pixel standard error
// (core/error_estimate.h) in its place.
inline constexpr const char* kErrorView = "error";
inline bool isErrorView(const std::string& name) { return name == kErrorView; }

// Parses a view name (the error view renders the beauty); throws InputError naming
// the known views otherwise.
inline Aov parseAov(const std::string& name) {
  if (isErrorView(name)) return Aov::Beauty;
  std::string known;
  for (size_t i = 0; i < kViewNames.size(); ++i) {
    if (name == kViewNames[i]) return static_cast<Aov>(i);
    known += (i == 0 ? "" : ", ") + std::string(kViewNames[i]);
  }
  throw InputError("--aov: unknown view '" + name + "' (use " + known + " or " + kErrorView + ")");
}

}  // namespace penumbra
