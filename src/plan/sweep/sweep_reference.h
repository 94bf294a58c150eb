// The image a sweep measures its runs against when it renders its own: the run at every
// knob's highest value with --reference-passes times its progressive passes.
#pragma once
#include "core/image.h"
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

class RenderSession;
struct PlannedJob;
struct SweepRequest;  // plan/sweep/sweep_run.h

struct LongReference {
  Image image;
  std::string note;  // what it is, and how it was rendered (report.md)
  double noiseRmse = -1.0;  // its own noise estimate (sweepNoiseRmse); < 0 unknown
};

// The image given with --reference, read and measured against every run's film before
// anything is written (InputError naming both files and the run otherwise).
Image givenReference(const std::string& path, const std::string& scenePath,
                     const std::vector<std::pair<std::string, const PlannedJob*>>& runs);

// Whether `saved` holds the reference of `highest` (the highest run's plan) that
// longReference would render: a rerun reloads it.
bool referenceSaved(const SweepRequest& req, const PlannedJob& highest, const std::string& saved);

// `highest` (the highest run's plan) with req.referencePasses x its passes: reloaded
// from `saved` when an earlier sweep left that very render there, else rendered on
// `session` (after `rendering()` is called) and saved there with its note.
LongReference longReference(RenderSession& session, const SweepRequest& req, const PlannedJob& highest,
                            const std::string& saved, const std::function<void()>& rendering);

}  // namespace penumbra
