// The image a sweep measures its runs against when it renders its own: the run at every
// knob's highest value with --reference-passes times its progressive passes.
#pragma once
#include "core/image.h"
#include <functional>
#include <string>

namespace penumbra {

class RenderSession;
struct PlannedJob;
struct SweepRequest;  // cli/sweep_run.h

struct LongReference {
  Image image;
  std::string note;  // what it is, and how it was rendered (report.md)
};

// `highest` (the highest run's plan) with req.referencePasses x its passes: reloaded
// from `saved` when an earlier sweep left that very render there, else rendered on
// `session` (after `rendering()` is called) and saved there with its note.
LongReference longReference(RenderSession& session, const SweepRequest& req, const PlannedJob& highest,
                            const std::string& saved, const std::function<void()>& rendering);

}  // namespace penumbra
