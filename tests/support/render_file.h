// One render of a scene file through the pipeline, as `penumbra render` runs it,
// kept in memory: the request tests build most often.
#pragma once
#include "plan/pipeline.h"
#include <string>
#include <utility>
#include <vector>

namespace penumbra::testing {

// `threads` 0: all cores; `aov` empty: the scene's view.
inline RenderResult renderFile(const std::string& path, std::vector<std::string> overrides = {}, int threads = 0,
                               const std::string& aov = "") {
  RenderRequest req;
  req.scenePath = path;
  req.overrides = std::move(overrides);
  req.session.threads = threads;
  req.aov = aov;
  return runRender(req);
}

}  // namespace penumbra::testing
