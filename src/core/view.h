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

// Parses a view name; throws InputError naming the known views otherwise.
inline Aov parseAov(const std::string& name) {
  std::string known;
  for (size_t i = 0; i < kViewNames.size(); ++i) {
    if (name == kViewNames[i]) return static_cast<Aov>(i);
    known += (i == 0 ? "" : i + 1 == kViewNames.size() ? " or " : ", ") + std::string(kViewNames[i]);
  }
  throw InputError("--aov: unknown view '" + name + "' (use " + known + ")");
}

}  // namespace penumbra
