// Drawing a render's phase progress: when a phase is old enough to show, how a
// terminal's line is redrawn, and which plain lines a log gets.
#include "cli/progress_meter.h"
#include "cli/progress_line.h"
#include <unistd.h>
#include <chrono>
#include <cstdlib>
#include <cmath>

namespace penumbra {

// How often the ticker looks at the counters: often enough that a line follows a
// phase as it moves, rarely enough to cost nothing.
constexpr std::chrono::milliseconds kTickInterval{100};

// Where and when progress shows: PENUMBRA_PROGRESS_AFTER overrides the 0.5 s a
// phase runs before it shows (tests set 0 to see every phase of a small render).
ProgressDisplay progressDisplay() {
  ProgressDisplay d;
  d.terminal = isatty(STDERR_FILENO);
  if (const char* after = std::getenv("PENUMBRA_PROGRESS_AFTER")) {
    char* end = nullptr;
    const double s = std::strtod(after, &end);
    if (end != after && *end == '\0' && s >= 0.0) d.quietSeconds = s;
  }
  return d;
}


ProgressMeter::ProgressMeter(ProgressDisplay display) : display_(std::move(display)) {}

ProgressMeter::~ProgressMeter() { finish(); }

double ProgressMeter::now() const {
  if (display_.clock) return display_.clock();
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

ProgressCounter* ProgressMeter::begin(const std::string& phase, uint64_t expected) {
  end();
  std::lock_guard<std::mutex> lock(mutex_);
  counter_.reset(expected);
  phase_ = phase;
  start_ = now();
  quarter_ = -1;
  return &counter_;
}

void ProgressMeter::end() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (phase_.empty()) return;
  const double elapsed = now() - start_;
  // Judged at the end too, so a phase as long as the threshold shows whether or
  // not a poll fell inside it (and a test's threshold of 0 shows every phase).
  if (elapsed >= display_.quietSeconds) draw(1.0, elapsed);
  ended_.push_back({phase_, counter_.done.load(), counter_.total.load()});
  phase_.clear();
}

ItemProgress::ItemProgress() : terminal_(isatty(STDERR_FILENO)), meter_(progressDisplay()) { meter_.startTicker(); }

void ItemProgress::line(const std::string& line) {
  if (terminal_) meter_.setContext(line);
  else if (line.find("| done |") != std::string::npos && line != last_) std::fprintf(stderr, "%s\n", line.c_str());
  last_ = line;
}

void ProgressMeter::setContext(std::string context) {
  std::lock_guard<std::mutex> lock(mutex_);
  context_ = std::move(context);
  // Between phases a terminal shows the place itself (a job up to date, or failed).
  if (display_.terminal && phase_.empty() && context_ != shown_) {
    std::fprintf(display_.out, "\r\033[K%s", context_.c_str());
    std::fflush(display_.out);
    shown_ = context_;
    lineOpen_ = true;
  }
}

void ProgressMeter::poll() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (phase_.empty()) return;
  const double elapsed = now() - start_;
  if (elapsed < display_.quietSeconds) return;
  const double f = counter_.fraction();
  if (!display_.terminal) {
    // The first line, then one per quarter passed; 100% waits for end().
    const int quarter = f < 0.0 ? 0 : std::min(3, static_cast<int>(f * 4.0));
    if (quarter_ >= 0 && quarter <= quarter_) return;
    quarter_ = quarter;
  }
  draw(f, elapsed);
}

void ProgressMeter::draw(double fraction, double elapsed) {
  std::string line = phaseLine(phase_, fraction, elapsed);
  if (!context_.empty()) line = context_ + " | " + line;
  if (display_.terminal) {
    if (lineOpen_ && line == shown_) return;  // nothing moved since the last redraw
    std::fprintf(display_.out, "\r\033[K%s", line.c_str());
    shown_ = std::move(line);
    lineOpen_ = true;
  } else {
    std::fprintf(display_.out, "%s\n", line.c_str());
  }
  std::fflush(display_.out);
}

void ProgressMeter::finish() {
  if (ticker_.joinable()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    ticker_.join();
  }
  end();
  std::lock_guard<std::mutex> lock(mutex_);
  if (lineOpen_) {
    std::fputc('\n', display_.out);
    std::fflush(display_.out);
  }
  lineOpen_ = false;
}

void ProgressMeter::startTicker() {
  ticker_ = std::thread([this] {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
      wake_.wait_for(lock, kTickInterval);
      if (stop_) break;
      lock.unlock();
      poll();
      lock.lock();
    }
  });
}

}  // namespace penumbra
