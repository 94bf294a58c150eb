// The progress of one render's long phases (photons, maps, lookups, render) on
// stderr: one line redrawn in place on a terminal, a few plain lines in a log.
#pragma once
#include "plan/command_support.h"
#include <condition_variable>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace penumbra {

struct ProgressDisplay {
  // A terminal redraws one line in place (\r, erase line) at every poll; a log gets
  // plain lines: when a phase turns `quietSeconds` old, as it passes 25, 50 and 75%,
  // and when it ends (100%).
  bool terminal = false;
  // A phase shows nothing until it has run this long, so short renders stay silent.
  double quietSeconds = 0.5;
  std::FILE* out = stderr;
  // Seconds on any steady clock; empty: std::chrono::steady_clock. Tests inject one.
  std::function<double()> clock;
};

// Where and when progress shows for a command: a terminal or a log, after the
// default quiet time or PENUMBRA_PROGRESS_AFTER seconds (tests set 0).
ProgressDisplay progressDisplay();

// The workers only add to the current phase's counter (core/progress.h). Drawing
// happens on the thread calling poll() (the ticker: 10 times a second) or at a
// phase's start and end (the pipeline's thread), never on a worker; the mutex is
// shared by those two threads only, so no worker ever waits for the terminal.
class ProgressMeter final : public ProgressPhases {
 public:
  explicit ProgressMeter(ProgressDisplay display);
  ~ProgressMeter();  // stops the ticker and closes the line
  ProgressMeter(const ProgressMeter&) = delete;
  ProgressMeter& operator=(const ProgressMeter&) = delete;

  // Starts a phase (ending the previous one): its counter, reset to `expected` units
  // (0: the workers announce theirs). Call only while no worker counts.
  ProgressCounter* begin(const std::string& phase, uint64_t expected = 0) override;
  void end() override;  // the phase is over: its 100% line, if it ran long enough to show
  // A many-render command's place (sweep, batch: "sweep 3/12 | run-id"), shown before
  // the phase, or alone between phases on a terminal; set by the scheduling thread.
  void setContext(std::string context);
  void poll();    // draws the current phase if it is old enough (and, in a log, due)
  void finish();  // ends the phase and the terminal's line
  // Polls on a thread of its own (kTickInterval) until finish() or destruction.
  void startTicker();

  // Every phase ended so far and its counter then, shown or not (tests: the
  // counters reach their totals).
  struct EndedPhase {
    std::string phase;
    uint64_t done = 0, total = 0;
  };
  const std::vector<EndedPhase>& ended() const { return ended_; }

 private:
  double now() const;
  void draw(double fraction, double elapsed);  // mutex_ held

  ProgressDisplay display_;
  std::mutex mutex_;
  ProgressCounter counter_;
  std::string phase_;  // empty: between phases
  std::string context_;
  double start_ = 0.0;
  int quarter_ = -1;       // a log: the last quarter of this phase printed (-1: none)
  bool lineOpen_ = false;  // a terminal: a line is drawn with no newline after it
  std::string shown_;      // a terminal: the line on screen
  std::vector<EndedPhase> ended_;
  std::thread ticker_;
  std::condition_variable wake_;
  bool stop_ = false;
};

// A many-render command's progress (sweep, batch): on a terminal each item's line
// heads the meter's phase line; in a log, one line per finished item ("| done |").
// Lines arrive on the command's own thread.
class ItemProgress {
 public:
  ItemProgress();
  ~ItemProgress() { finish(); }
  ProgressPhases* phases() { return &meter_; }
  void line(const std::string& line);
  void finish() { meter_.finish(); }

 private:
  bool terminal_;
  ProgressMeter meter_;
  std::string last_;
};

}  // namespace penumbra
