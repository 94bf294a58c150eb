// Temporary files that stand in for an output until it is renamed into place, the
// one checked write-and-rename every output goes through, and the SIGINT/SIGTERM
// cleanup that removes them so an interrupted or failed write leaves only the old output.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

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
// before (default action, so the parent sees the usual exit status); SIGTERM while a
// TermDeferral lives only sets its flag. Also reads the
// test-only hooks (temp_file.cpp), each of the form PHASE[:PREFIX[:N]] and acting on
// the Nth (default first; "*": every) temp file whose name starts with PREFIX:
//   PENUMBRA_TEST_SIGNAL_AT=temp-file[:PREFIX[:N]]  SIGINT as soon as it exists;
//   PENUMBRA_TEST_DISK_FULL_AT=write[:PREFIX[:N]]   its write fails with ENOSPC
//                                                   after half its bytes;
// and PENUMBRA_TEST_TERM_AFTER_PASS=K: SIGTERM right after pass K of a frame (termHookAfterPass).
void installTempFileCleanup();

// While one lives, SIGTERM (a scheduler's time limit or preemption) does not kill the
// process: the handler sets a flag the owner polls at a point where it can save its
// work and stop (a progressive frame, between passes). A second SIGTERM, or one when
// none lives, removes the temp files and dies as before; SIGINT always does.
class TermDeferral {
 public:
  TermDeferral();
  ~TermDeferral();
  TermDeferral(const TermDeferral&) = delete;
  TermDeferral& operator=(const TermDeferral&) = delete;
};

// A SIGTERM arrived while a TermDeferral lived and nobody has died of it yet: it stays
// set, so whoever runs next (the next job of a batch) stops too.
bool terminationRequested() noexcept;

// The test hook: raises SIGTERM when `passesDone` is PENUMBRA_TEST_TERM_AFTER_PASS.
void termHookAfterPass(int passesDone);

// The handler's body: unlinks every registered temp file. Async-signal-safe.
void removeRegisteredTempFiles() noexcept;

// Writes `size` bytes to `path` through a registered temp file in the same directory:
// a checked write(2) loop, fsync and close, then a rename, so `path` is either the
// old file or the whole new one and no temp file is left. Throws InputError
// "PATH: cannot write WHAT: REASON" (a full disk, an I/O error, a missing directory).
void writeFileAtomic(const std::string& path, const void* data, size_t size, const std::string& what = "file");
// The same for a file written from pieces in order (a header and arrays it does not copy).
struct FilePiece {
  const void* data = nullptr;
  size_t size = 0;
};
void writeFileAtomic(const std::string& path, const std::vector<FilePiece>& pieces, const std::string& what);
void writeTextFileAtomic(const std::string& path, const std::string& text);

// The temp name the next write of `path` takes: beside it, ".tmp<pid>-<counter>"
// after its stem (shortened to fit NAME_MAX), its extension last. Each call takes a
// new counter value.
std::string tempPathFor(const std::string& path);

// Why `path` cannot be written as an output, "" when it can: its directory is missing
// or not writable, it is a directory, its file system has not one block free, its
// name is longer than the directory allows (NAME_MAX), or it or its temp file's path
// is longer than PATH_MAX. Run before any work, so nothing the write-and-rename needs
// is refused after a render.
std::string outputPathProblem(const std::string& path);

}  // namespace penumbra
