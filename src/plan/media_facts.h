// What the plan reads of a scene's participating media: which of them scatter (and so
// feed a volume map) and how a reason names them.
#pragma once
#include "core/scene.h"
#include <string>
#include <vector>

namespace penumbra {

// The names of the media that scatter light (some sigma_s above 0), in scene order.
inline std::vector<std::string> scatteringMedia(const Scene& scene) {
  std::vector<std::string> names;
  for (const Medium& m : scene.media) {
    if (maxComponent(m.sigmaS) > 0.0f) names.push_back(m.name);
  }
  return names;
}

// "medium 'fog'", "media 'fog' and 'smoke'", "media 'a', 'b' and 'c'".
inline std::string mediaPhrase(const std::vector<std::string>& names) {
  if (names.empty()) return "no medium";
  std::string s = names.size() == 1 ? "medium " : "media ";
  for (size_t i = 0; i < names.size(); ++i) {
    s += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + ("'" + names[i] + "'");
  }
  return s;
}

}  // namespace penumbra
