// penumbra merge: part files of one frame checked (one job, one frame size, every
// pixel in exactly one part) and pasted into the frame, its error figure pooled.
#pragma once
#include "io/tone_map.h"
#include <string>
#include <vector>

namespace penumbra {

struct MergeOutcome {
  int width = 0, height = 0;
  size_t parts = 0;
  std::string error;  // the merged frame's error figure (describeError)
};

// Throws InputError (one line naming the parts or pixels) before writing anything when
// the parts do not make one frame; writes `output` (.png or .exr) whole or not at all,
// a PNG through `display` as render's --exposure and --tonemap do.
MergeOutcome mergeFrame(const std::vector<std::string>& parts, const std::string& output,
                        const DisplayOptions& display = {});

}  // namespace penumbra
