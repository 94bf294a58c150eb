// The registry is a fixed array of slots with atomic states, no allocation and no
// locks, because the signal handler reads it: it may run between any two
// instructions of the thread that is filling a slot.
#include "io/temp_file.h"
#include "core/error.h"
#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
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

extern "C" void onTerminatingSignal(int sig) {
  removeRegisteredTempFiles();
  // SA_RESETHAND restored the default action; SA_NODEFER lets this raise take it now.
  std::raise(sig);
}

}  // namespace

TempFileGuard::TempFileGuard(const std::string& path) {
  if (path.size() + 1 > kPathMax) return;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!gSlots[i].state.compare_exchange_strong(expected, kFilling)) continue;
    std::memcpy(gSlots[i].path, path.c_str(), path.size() + 1);
    gSlots[i].state.store(kArmed);
    slot_ = i;
    return;
  }
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
