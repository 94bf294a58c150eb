// penumbra batch's jobs: a jobs file (or a list of scenes) expanded into plain
// jobs (plan/batch/batch_run.h).
#pragma once
#include "plan/batch/batch_run.h"
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

// Whether `path` is a jobs file (a JSON object with "jobs") rather than a scene.
bool isJobsFile(const std::string& path);

// A jobs file:
//   {"set": [...], "jobs": [{"scene": "a.json", "set": [...], "views": ["beauty", "depth"],
//     "output": "out/{name}_{view}.png", "orbit": {"count": 16, "center": [0, 1, 0],
//     "radius": 5, "height": 1, "from": -60, "to": 60, "up": [0, 1, 0]}}, {"scenes": "scenes/fig0*.json",
//     "output": "out/{name}.png"}]}
// An orbit turns about `up` through its centre (default +y) and sets camera.up to it,
// so every frame's horizon is level. Paths are relative to the jobs file. Throws
// InputError naming the file and JSON path.
std::vector<BatchJob> readJobsFile(const std::string& path);

// One job per scene, every view into DIR/<scene stem>[_<view>].<ext>.
std::vector<BatchJob> jobsForScenes(const std::vector<std::string>& scenes, const std::string& dir,
                                    const std::vector<std::string>& views, const std::string& ext);

}  // namespace penumbra
