// A progressive frame's finished passes saved beside its output when SIGTERM stops
// it (a scheduler's time limit or preemption), so the same command run again
// continues at the next pass and writes the pixels an uninterrupted run writes.
#pragma once
#include "core/error_estimate.h"
#include "core/image.h"
#include "core/map_kind.h"
#include "core/stats.h"
#include <optional>
#include <string>

namespace penumbra {

// The exit code of a process SIGTERM stopped, as a shell reports one the signal
// killed (128 + 15), whether its passes were saved or it had none to save.
inline constexpr int kExitTerminated = 143;

// Thrown out of a frame that stopped for SIGTERM, after saving its passes. Not a
// std::exception: no job's catch takes it for that job's failure; main exits kExitTerminated.
struct Terminated {
  std::string message;  // one line: what was saved where, or why nothing was
};

// Everything the pass loop needs to continue at pass `done` (0-based) of `passes`.
struct SavedPasses {
  std::string identity;  // the job, its settings and view (RenderSession::frame); compared whole
  int done = 0, passes = 0;
  double seconds = 0.0;  // the job's clock when it stopped: a time limit counts every run
  Image sum;             // the sum of passes 0..done-1
  PassSpread::Moments spread;
  // The counters the image's header and --stats report over every pass.
  MapCounts emitted, stored;
  RayCounts rays;
  PerMap<float> gatherRadius;
};

// The passes file of `output`: "<output>.passes"; a view of a layered file that holds
// several gets its own, "<output>.<view>.passes".
std::string savedPassesPath(const std::string& output, const std::string& view = "");

// Writes `s` to `path` through a temp file and a rename, with a format version and a
// checksum; its size in bytes. Throws InputError as writeFileAtomic does.
uint64_t savePasses(const std::string& path, const SavedPasses& s);

// The passes saved at `path` for `identity`, a frame of `passes` passes of
// width x height; nullopt when there is no file, and also when it is of another
// version, job or setting, truncated or corrupt: then `why` says which (one line).
std::optional<SavedPasses> loadPasses(const std::string& path, const std::string& identity, int passes, int width,
                                      int height, std::string& why);

// Removes `path` if it exists (the job finished, or --force); empty path: nothing.
void removeSavedPasses(const std::string& path);

}  // namespace penumbra
