// The registry is a fixed array of slots with atomic states, no allocation and no
// locks, because the signal handler reads it: it may run between any two
// instructions of the thread that is filling a slot.
#include "io/temp_file.h"
#include "core/error.h"
#include <fcntl.h>
#include <sys/statvfs.h>
#include <fmt/format.h>
#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

constexpr int kSlots = 16;
constexpr size_t kPathMax = PATH_MAX;
enum : int { kFree = 0, kFilling = 1, kArmed = 2 };

struct Slot {
  std::atomic<int> state{kFree};
  char path[kPathMax];
};
Slot gSlots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the handler needs lock-free atomics");

// Test-only hooks, read once when the cleanup is installed: VARIABLE=PHASE[:PREFIX[:N]]
// acts on the Nth (default first; "*": every) temp file whose name starts with PREFIX
// (default any), so a test interrupts or fails a write at a known point instead of
// racing it. Unset, a hook costs one relaxed load.
struct TempFileHook {
  std::atomic<bool> armed{false};
  std::string prefix;
  int nth = 1;
  bool every = false;
  std::atomic<int> seen{0};

  void read(const char* variable, const std::string& phase) {
    const char* env = std::getenv(variable);
    if (!env) return;
    const std::string spec(env);
    if (spec.compare(0, phase.size(), phase) != 0) return;
    std::string rest = spec.substr(phase.size());
    if (!rest.empty() && rest[0] != ':') return;
    if (!rest.empty()) rest.erase(0, 1);
    const size_t colon = rest.rfind(':');
    if (colon != std::string::npos) {
      every = rest.compare(colon + 1, std::string::npos, "*") == 0;
      nth = every ? 1 : std::atoi(rest.c_str() + colon + 1);
      rest.erase(colon);
    }
    prefix = rest;
    armed.store(nth > 0);
  }
  // True for the one temp file the hook names.
  bool fires(const std::string& path) {
    if (!armed.load(std::memory_order_relaxed)) return false;
    if (fs::path(path).filename().string().compare(0, prefix.size(), prefix) != 0) return false;
    return every || seen.fetch_add(1) + 1 == nth;
  }
};
// The temp file exists, then SIGINT arrives, as if Ctrl-C came mid-write.
TempFileHook gSignalHook;
// The temp file's write stops with ENOSPC after half its bytes, as on a full disk.
TempFileHook gDiskFullHook;

void signalHook(const std::string& path) {
  if (!gSignalHook.fires(path)) return;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT, 0644);
  if (fd >= 0) ::close(fd);
  std::raise(SIGINT);
}

// Live TermDeferrals, and whether a SIGTERM came while one lived.
std::atomic<int> gTermDeferrals{0};
std::atomic<bool> gTermRequested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the handler needs lock-free atomics");
// PENUMBRA_TEST_TERM_AFTER_PASS, read once; 0: unset.
std::atomic<int> gTermAfterPass{0};

extern "C" void onTerminatingSignal(int sig) {
  if (sig == SIGTERM && gTermDeferrals.load() > 0 && !gTermRequested.exchange(true)) return;
  removeRegisteredTempFiles();
  // The default action back, then SA_NODEFER lets this raise take it now.
  struct sigaction dfl;
  std::memset(&dfl, 0, sizeof dfl);
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  std::raise(sig);
}

// The longest file name `dir` allows (NAME_MAX, 255 on Linux file systems).
size_t nameMax(const fs::path& dir) {
  const long n = ::pathconf(dir.empty() ? "." : dir.c_str(), _PC_NAME_MAX);
  return n > 0 ? static_cast<size_t>(n) : NAME_MAX;
}

// Names tried before a write gives up: each taken one is a leftover of a killed process.
constexpr int kTempNameAttempts = 64;

// What a temp name adds at most: ".tmp", the pid and "-" and the counter at full width.
constexpr size_t kTempTagMax = 4 + 10 + 1 + 10;

// Writes every piece's bytes in order (write(2) may take fewer, or be interrupted); 0 or
// the errno. `failAfter` < SIZE_MAX: the disk-full hook's ENOSPC once that many bytes are written.
int writeAll(int fd, const std::vector<FilePiece>& pieces, size_t failAfter) {
  size_t written = 0;
  for (const FilePiece& piece : pieces) {
    const auto* data = static_cast<const unsigned char*>(piece.data);
    const size_t end = std::min(piece.size, failAfter - written);
    for (size_t done = 0; done < end;) {
      const ssize_t n = ::write(fd, data + done, std::min<size_t>(end - done, size_t{1} << 30));
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) return errno;
      if (n == 0) return EIO;
      done += static_cast<size_t>(n);
    }
    written += end;
    if (written == failAfter) break;
  }
  return failAfter < SIZE_MAX ? ENOSPC : 0;
}

}  // namespace

TempFileGuard::TempFileGuard(const std::string& path) {
  for (int i = 0; i < kSlots && path.size() + 1 <= kPathMax; ++i) {
    int expected = kFree;
    if (!gSlots[i].state.compare_exchange_strong(expected, kFilling)) continue;
    std::memcpy(gSlots[i].path, path.c_str(), path.size() + 1);
    gSlots[i].state.store(kArmed);
    slot_ = i;
    break;
  }
  signalHook(path);
}

TempFileGuard::~TempFileGuard() {
  if (slot_ >= 0) gSlots[slot_].state.store(kFree);
}

void removeRegisteredTempFiles() noexcept {
  const int saved = errno;
  for (Slot& s : gSlots) {
    if (s.state.load() == kArmed) ::unlink(s.path);
  }
  errno = saved;
}

void installTempFileCleanup() {
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = onTerminatingSignal;
  sigemptyset(&action.sa_mask);
  // Not SA_RESETHAND: a deferred SIGTERM returns, and the next one must find the handler.
  action.sa_flags = SA_NODEFER;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  gSignalHook.read("PENUMBRA_TEST_SIGNAL_AT", "temp-file");
  gDiskFullHook.read("PENUMBRA_TEST_DISK_FULL_AT", "write");
  if (const char* pass = std::getenv("PENUMBRA_TEST_TERM_AFTER_PASS")) gTermAfterPass.store(std::max(0, std::atoi(pass)));
}

TermDeferral::TermDeferral() { gTermDeferrals.fetch_add(1); }
TermDeferral::~TermDeferral() { gTermDeferrals.fetch_sub(1); }

bool terminationRequested() noexcept { return gTermRequested.load(); }

void termHookAfterPass(int passesDone) {
  const int k = gTermAfterPass.load(std::memory_order_relaxed);
  if (k > 0 && passesDone == k) std::raise(SIGTERM);
}

// Same directory (so the rename is atomic on one filesystem), pid + counter (so
// neither two processes nor two threads share a name), the target's extension last
// (a leftover shows what it was). A long name gives up the end of its stem, so
// every name the target may have has a temp name the directory allows.
std::string tempPathFor(const std::string& path) {
  const fs::path target(path);
  static std::atomic<unsigned> counter{0};
  const std::string tag = ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  std::string stem = target.stem().string(), ext = target.extension().string();
  const size_t limit = nameMax(target.parent_path());
  if (tag.size() + ext.size() > limit) ext.clear();
  if (stem.size() + tag.size() + ext.size() > limit) {
    size_t keep = limit - tag.size() - ext.size();
    while (keep > 0 && (static_cast<unsigned char>(stem[keep]) & 0xC0) == 0x80) --keep;  // whole UTF-8 characters
    stem.resize(keep);
  }
  return (target.parent_path() / (stem + tag + ext)).string();
}

void writeFileAtomic(const std::string& path, const void* data, size_t size, const std::string& what) {
  writeFileAtomic(path, std::vector<FilePiece>{{data, size}}, what);
}

void writeFileAtomic(const std::string& path, const std::vector<FilePiece>& pieces, const std::string& what) {
  const fs::path target(path);
  fs::path temp;
  auto fail = [&](int err) {
    std::error_code ec;
    const bool kept = fs::exists(target, ec);
    throw InputError(fmt::format("{}: cannot write {}: {}{}", path, what, std::strerror(err),
                                 kept ? "; the old file is kept" : ""));
  };
  // O_EXCL: the temp name is this write's alone, never a file (or link) already there.
  // A name left by a process killed mid-write (SIGKILL runs no cleanup) under the same
  // pid is passed over for the next counter, never reused or overwritten.
  std::optional<TempFileGuard> guard;
  int fd = -1;
  for (int attempt = 0; fd < 0; ++attempt) {
    temp = tempPathFor(path);
    guard.emplace(temp.string());  // registered before it exists: a SIGINT during the write removes it
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && (errno != EEXIST || attempt + 1 == kTempNameAttempts)) fail(errno);
  }
  size_t size = 0;
  for (const FilePiece& piece : pieces) size += piece.size;
  const size_t failAfter = gDiskFullHook.fires(temp.string()) ? size / 2 : SIZE_MAX;
  int err = writeAll(fd, pieces, failAfter);
  // A network or delayed-allocation file system may report the lost bytes only here.
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err == 0 && ::rename(temp.c_str(), target.c_str()) != 0) err = errno;
  if (err != 0) {
    ::unlink(temp.c_str());
    fail(err);
  }
}

void writeTextFileAtomic(const std::string& path, const std::string& text) {
  writeFileAtomic(path, text.data(), text.size(), "file");
}

std::string outputPathProblem(const std::string& path) {
  if (path.empty()) return "empty path";
  const fs::path target(path);
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const std::string name = target.filename().string();
  if (path.size() >= PATH_MAX)
    return fmt::format("its path is {} bytes, the system's limit is {}", path.size(), PATH_MAX - 1);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return "directory '" + dir.string() + "' does not exist";
  if (::access(dir.c_str(), W_OK) != 0) return "directory '" + dir.string() + "' is not writable";
  if (fs::is_directory(target, ec)) return "it is a directory";
  // Not one free block: the write would fail, so the work before it is not begun.
  // (A file system that reports no blocks at all is taken at its word: unknown.)
  struct statvfs fsInfo;
  if (::statvfs(dir.c_str(), &fsInfo) == 0 && fsInfo.f_blocks > 0 &&
      (::geteuid() == 0 ? fsInfo.f_bfree : fsInfo.f_bavail) == 0) {
    return std::string(std::strerror(ENOSPC)) + " (its file system is full)";
  }
  const size_t limit = nameMax(dir);
  if (name.size() > limit) return fmt::format("its name is {} bytes, the directory allows {}", name.size(), limit);
  const size_t tempPath = path.size() - name.size() + std::min(limit, name.size() + kTempTagMax);
  if (tempPath >= PATH_MAX) {
    return fmt::format("its temp file's path would be {} bytes, the system's limit is {}; use a shorter path",
                       tempPath, PATH_MAX - 1);
  }
  return "";
}

}  // namespace penumbra
