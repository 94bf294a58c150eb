// Emission without a render plan (emitter tests and benchmarks): the scene's own
// photons.* budgets, with the gate's shadow photons only where a plan could turn the
// gate on (photons.gate not off and render.shadows on).
#pragma once
#include "emit/emit.h"

namespace penumbra {

inline EmitOptions sceneEmit(const Scene& scene, EmitOptions options = {}) {
  options.budgets = budgetsOf(scene);
  if (scene.photons.gateMode == GateMode::Off || !scene.render.shadows) options.budgets[MapKind::Shadow] = 0;
  return options;
}

}  // namespace penumbra
