// The registry is a fixed array of slots with atomic states, no allocation and no
// locks, because the signal handler reads it: it may run between any two
// instructions of the thread that is filling a slot.
#include "io/temp_file.h"
#include "core/error.h"
#include <fcntl.h>
#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

constexpr int kSlots = 16;
constexpr size_t kPathMax = 4096;
enum : int { kFree = 0, kFilling = 1, kArmed = 2 };

struct Slot {
  std::atomic<int> state{kFree};
  char path[kPathMax];
};
Slot gSlots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the handler needs lock-free atomics");

// Test-only hook: PENUMBRA_TEST_SIGNAL_AT=temp-file[:PREFIX[:N]] in the environment
// when the cleanup is installed makes the Nth (default first) registered temp file
// whose name starts with PREFIX (default any) exist at once and then raises SIGINT,
// as if Ctrl-C arrived mid-write. Tests interrupt a write at a known point this way
// instead of polling for the file. Read once; unset, a guard costs one relaxed load.
struct SignalHook {
  std::atomic<bool> armed{false};
  std::string prefix;
  int nth = 1;
  std::atomic<int> seen{0};
};
SignalHook gHook;

void readSignalHook() {
  const char* env = std::getenv("PENUMBRA_TEST_SIGNAL_AT");
  if (!env) return;
  const std::string spec(env), phase = "temp-file";
  if (spec.compare(0, phase.size(), phase) != 0) return;
  std::string rest = spec.substr(phase.size());
  if (!rest.empty() && rest[0] != ':') return;
  if (!rest.empty()) rest.erase(0, 1);
  const size_t colon = rest.rfind(':');
  if (colon != std::string::npos) {
    gHook.nth = std::atoi(rest.c_str() + colon + 1);
    rest.erase(colon);
  }
  gHook.prefix = rest;
  gHook.armed.store(gHook.nth > 0);
}

void signalHook(const std::string& path) {
  if (!gHook.armed.load(std::memory_order_relaxed)) return;
  if (fs::path(path).filename().string().compare(0, gHook.prefix.size(), gHook.prefix) != 0) return;
  if (gHook.seen.fetch_add(1) + 1 != gHook.nth) return;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT, 0644);
  if (fd >= 0) ::close(fd);
  std::raise(SIGINT);
}

extern "C" void onTerminatingSignal(int sig) {
  removeRegisteredTempFiles();
  // SA_RESETHAND restored the default action; SA_NODEFER lets this raise take it now.
  std::raise(sig);
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
  action.sa_flags = SA_RESETHAND | SA_NODEFER;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  readSignalHook();
}

void writeTextFileAtomic(const std::string& path, const std::string& text) {
  const fs::path target(path);
  const fs::path temp = target.parent_path() /
                        (target.filename().string() + ".tmp" + std::to_string(::getpid()));
  TempFileGuard guard(temp.string());
  std::FILE* f = std::fopen(temp.c_str(), "wb");
  if (!f) throw InputError(path + ": cannot write file: " + std::strerror(errno));
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const bool closed = std::fclose(f) == 0;
  std::error_code ec;
  if (!written || !closed) {
    fs::remove(temp, ec);
    throw InputError(path + ": cannot write file");
  }
  fs::rename(temp, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw InputError(path + ": cannot write file: " + ec.message());
  }
}

}  // namespace penumbra
