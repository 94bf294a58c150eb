// What loading warns about (a scene that renders without light): warnings travel with
// the load notes and are printed as they are where notes get "note: " in front
// (plan/command_support.h noteLine).
#pragma once
#include "core/scene.h"
#include <string>
#include <string_view>

namespace penumbra {

// The start of a load note that is a warning; the commands print it as it is.
inline constexpr std::string_view kWarningNote = "warning: ";

// "warning: FILE: no light, emissive surface or environment: ..." when nothing in
// `scene` (after its defaults) emits light, else "". The classic model's ambient term
// still shows surfaces, and the line says so; otherwise the image is black.
std::string noLightWarning(const Scene& scene);

}  // namespace penumbra
