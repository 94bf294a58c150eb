// The no-light warning: what counts as light, and what the image shows without it.
#include "io/scene_warnings.h"
#include "core/math.h"
#include <fmt/format.h>

namespace penumbra {

std::string noLightWarning(const Scene& scene) {
  // Every light source ends up in Scene::lights: lights, emitting surfaces
  // (addMeshEmitters), the environment and the model scene's default sky.
  if (!scene.lights.empty()) return "";
  const bool ambient = modelOf(scene.render).id == ShadingModel::Classic && maxComponent(scene.render.ambient) > 0.0f;
  return fmt::format("{}{}: no light, emissive surface or environment: {}", kWarningNote,
                     scene.file.empty() ? "<scene>" : scene.file,
                     ambient ? "only the classic ambient term shows the surfaces" : "the image is black");
}

}  // namespace penumbra
