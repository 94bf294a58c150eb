// What `penumbra check` says about a loaded scene: its model and contents, where its
// geometry is, and what loading added to a glTF scene (or would without --no-defaults).
#pragma once
#include "core/scene.h"
#include <string>

namespace penumbra {

// "ok (classic, 3 meshes with 12 triangles, ...)\n", then the bounds line and the
// defaults line when they apply; every line ends with a newline.
std::string checkReport(const Scene& scene);

}  // namespace penumbra
