// A progress bar on stderr, shown only on a terminal and only once a render
// has taken over a second (short renders stay quiet).
#pragma once
#include "core/stats.h"
#include <cstdio>
#include <mutex>
#include <unistd.h>

namespace penumbra {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO)) {}
  ~ProgressBar() { finish(); }

  // Redraws when the phase changes or the percentage grows; phases are labelled
  // so the photon pass, which has no fraction of its own, still shows activity.
  void update(const char* phase, double fraction) {
    if (!enabled_ || clock_.seconds() < 1.0) return;
    int percent = static_cast<int>(fraction * 100.0);
    std::lock_guard<std::mutex> lock(mutex_);
    if (phase == phase_ && percent <= shown_) return;
    phase_ = phase;
    shown_ = percent;
    const int width = 40;
    int filled = percent * width / 100;
    std::fprintf(stderr, "\r%-8s [%.*s%*s] %3d%%", phase, filled, "########################################",
                 width - filled, "", percent);
    std::fflush(stderr);
    drawn_ = true;
  }
  void finish() {
    if (drawn_) std::fputc('\n', stderr);
    drawn_ = false;
  }

 private:
  bool enabled_;
  Stopwatch clock_;
  const char* phase_ = nullptr;  // phases are string literals: compared by address
  int shown_ = -1;
  std::mutex mutex_;
  bool drawn_ = false;
};

}  // namespace penumbra
