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

// Derived views render the beauty and write a per-pixel figure of it in its place:
// "error" its standard error, "bias" its photon-map bias (core/error_estimate.h),
// "spp" the camera samples each pixel took (core/adaptive_sampling.h).
enum class DerivedView { None, Error, Bias, Spp };

// In enum order after None.
inline constexpr std::array<const char*, 3> kDerivedViewNames = {"error", "bias", "spp"};

inline DerivedView derivedView(const std::string& name) {
  for (size_t i = 0; i < kDerivedViewNames.size(); ++i)
    if (name == kDerivedViewNames[i]) return static_cast<DerivedView>(i + 1);
  return DerivedView::None;
}

// Every view name a render accepts: the light and geometry views, then the derived ones.
inline std::string knownViews() {
  std::string known;
  for (const char* n : kViewNames) known += (known.empty() ? "" : ", ") + std::string(n);
  for (const char* n : kDerivedViewNames) known += ", " + std::string(n);
  return known;
}

// Parses a view name (a derived view renders the beauty); throws InputError naming
// the known views otherwise.
inline Aov parseAov(const std::string& name) {
  if (derivedView(name) != DerivedView::None) return Aov::Beauty;
  for (size_t i = 0; i < kViewNames.size(); ++i)
    if (name == kViewNames[i]) return static_cast<Aov>(i);
  throw InputError("--aov: unknown view '" + name + "' (use " + knownViews() + ")");
}

}  // namespace penumbra
