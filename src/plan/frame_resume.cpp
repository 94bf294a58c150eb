// A frame's saved passes: resumed where they are this frame's, and written when
// SIGTERM comes between passes (plan/saved_passes.h holds the format).
#include "plan/frame_run.h"
#include "plan/saved_passes.h"
#include "core/error.h"
#include "io/temp_file.h"
#include <fmt/format.h>
#include <filesystem>
#include <optional>

namespace penumbra {

void resumeFrame(FrameRun& f) {
  const FrameOptions::Resume& r = f.options.resume;
  std::vector<std::string>& notes = f.result.notes;
  if (r.discard) {
    std::error_code ec;
    if (std::filesystem::exists(r.path, ec)) notes.push_back(r.path + ": saved passes discarded (--force)");
    removeSavedPasses(r.path);
    return;
  }
  std::string why;
  const Stopwatch reading;
  std::optional<SavedPasses> s = loadPasses(r.path, r.identity, f.passes, f.scene.camera.width,
                                            f.scene.camera.height, why);
  if (!s) {
    if (!why.empty()) notes.push_back(fmt::format("{}: saved passes not used ({}): starting at pass 1", r.path, why));
    return;
  }
  f.first = f.done = s->done;
  f.result.image = std::move(s->sum);
  f.spread.restore(std::move(s->spread));
  f.stats.emitted = s->emitted;
  f.stats.stored = s->stored;
  f.stats.rays = s->rays;
  f.stats.gatherRadius = s->gatherRadius;
  // A time limit counts the job's seconds in every run.
  f.clock = [clock = std::move(f.clock), before = s->seconds] { return before + clock(); };
  f.passStart = f.clock();
  notes.push_back(fmt::format("{}: resumed at pass {} of {} (read in {:.2f} s)", r.path, f.done + 1, f.passes,
                              reading.seconds()));
}

[[noreturn]] void saveAndStop(FrameRun& f) {
  const FrameOptions::Resume& r = f.options.resume;
  const std::string passes = f.budgeted ? fmt::format("{} passes", f.done) : fmt::format("{} of {} passes", f.done, f.passes);
  SavedPasses s;
  s.identity = r.identity;
  s.done = f.done;
  s.passes = f.passes;
  s.seconds = f.clock();
  s.sum = std::move(f.result.image);
  s.spread = f.spread.moments();
  s.emitted = f.stats.emitted;
  s.stored = f.stats.stored;
  s.rays = f.stats.rays;
  s.gatherRadius = f.stats.gatherRadius;
  const Stopwatch saving;
  uint64_t bytes = 0;
  try {
    bytes = savePasses(r.path, s);
  } catch (const InputError& e) {
    throw Terminated{fmt::format("SIGTERM: {} not saved: {}", passes, e.what())};
  }
  throw Terminated{fmt::format("SIGTERM: saved {} to {} ({:.1f} MB, {:.2f} s); the same command resumes at pass {}",
                               passes, r.path, bytes / 1e6, saving.seconds(), f.done + 1)};
}

}  // namespace penumbra
