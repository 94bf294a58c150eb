// Temporary files that stand in for an output until it is renamed into place, and
// the SIGINT/SIGTERM cleanup that removes them so an interrupted write leaves
// only the old output behind.
#pragma once
#include <string>

namespace penumbra {

// Registers `path` for removal if the process is interrupted while it exists;
// unregisters on destruction (after the rename, or after the caller removed it).
class TempFileGuard {
 public:
  explicit TempFileGuard(const std::string& path);
  ~TempFileGuard();
  TempFileGuard(const TempFileGuard&) = delete;
  TempFileGuard& operator=(const TempFileGuard&) = delete;

 private:
  int slot_ = -1;  // -1: the path did not fit or every slot was taken (not removed on a signal)
};

// SIGINT and SIGTERM remove every registered temp file, then die of the signal as
// before (default action, so the parent sees the usual exit status). Also reads the
// test-only PENUMBRA_TEST_SIGNAL_AT=temp-file[:PREFIX[:N]] (temp_file.cpp): SIGINT
// raised as soon as the Nth temp file named PREFIX... is registered and exists.
void installTempFileCleanup();

// The handler's body: unlinks every registered temp file. Async-signal-safe.
void removeRegisteredTempFiles() noexcept;

// Writes `text` to `path` through a registered temp file in the same directory and
// a rename, so `path` is either the old file or the whole new one. Throws InputError.
void writeTextFileAtomic(const std::string& path, const std::string& text);

}  // namespace penumbra
