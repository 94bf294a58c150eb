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

// Views derived from a render of the beauty, written in its place: "error", its
// per-pixel standard error (core/error_estimate.h); "spp", the camera samples each
// pixel took (core/adaptive_sampling.h).
enum class DerivedView { None, Error, Spp };
// In enum order, from Error on.
inline constexpr std::array<const char*, 2> kDerivedViewNames = {"error", "spp"};

inline DerivedView derivedView(const std::string& name) {
  for (size_t i = 0; i < kDerivedViewNames.size(); ++i) {
    if (name == kDerivedViewNames[i]) return static_cast<DerivedView>(i + 1);
  }
  return DerivedView::None;
}

// Parses a view name (a derived view renders the beauty); throws InputError naming
// the known views otherwise.
inline Aov parseAov(const std::string& name) {
  if (derivedView(name) != DerivedView::None) return Aov::Beauty;
  std::string known;
  for (size_t i = 0; i < kViewNames.size(); ++i) {
    if (name == kViewNames[i]) return static_cast<Aov>(i);
    known += (i == 0 ? "" : ", ") + std::string(kViewNames[i]);
  }
  for (const char* d : kDerivedViewNames) known += ", " + std::string(d);
  throw InputError("--aov: unknown view '" + name + "' (use " + known + ")");
}

}  // namespace penumbra
