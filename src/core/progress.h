// How much of a long phase is done, counted by the layer doing the work (emission
// batches, map parts, lookup chunks, image tiles) and read by whoever displays it.
#pragma once
#include <atomic>
#include <cstdint>
#include <string>

namespace penumbra {

// Plain data shared by the workers and one reader: workers add once per batch,
// part, chunk or tile (never per photon or pixel), with relaxed atomics, so
// counting costs nothing measurable and takes no lock. Units are the phase's own
// (photons of a batch, photons of a part, cells, tiles): only done / total matters.
struct ProgressCounter {
  std::atomic<uint64_t> done{0};
  std::atomic<uint64_t> total{0};  // 0: not known yet

  void add(uint64_t n) { done.fetch_add(n, std::memory_order_relaxed); }
  void expect(uint64_t n) { total.fetch_add(n, std::memory_order_relaxed); }
  // Called between phases, while no worker counts.
  void reset(uint64_t expected) {
    done.store(0, std::memory_order_relaxed);
    total.store(expected, std::memory_order_relaxed);
  }
  // In [0, 1], or -1 while the total is unknown.
  double fraction() const {
    const uint64_t t = total.load(std::memory_order_relaxed);
    if (t == 0) return -1.0;
    const uint64_t d = done.load(std::memory_order_relaxed);
    return d >= t ? 1.0 : static_cast<double>(d) / static_cast<double>(t);
  }
};

// The lower layers take an optional counter: null (tests, benchmarks) counts nothing.
inline void progressAdd(ProgressCounter* c, uint64_t n) {
  if (c) c->add(n);
}
inline void progressExpect(ProgressCounter* c, uint64_t n) {
  if (c) c->expect(n);
}

// Where a render announces its phases (photons, maps, lookups, render): the CLI's
// progress display implements it. Only the thread running the render calls it,
// between phases; workers only add to the counter it returns, and nothing is ever
// called back on a worker.
class ProgressPhases {
 public:
  // Starts a phase (ending the previous one) with its counter reset to `expected`
  // units (0: the workers announce theirs).
  virtual ProgressCounter* begin(const std::string& phase, uint64_t expected = 0) = 0;
  virtual void end() = 0;

 protected:
  ~ProgressPhases() = default;
};

// The display is optional (tests and benchmarks pass none): null counts nothing.
inline ProgressCounter* beginPhase(ProgressPhases* phases, const std::string& phase, uint64_t expected = 0) {
  return phases ? phases->begin(phase, expected) : nullptr;
}
inline void endPhase(ProgressPhases* phases) {
  if (phases) phases->end();
}

// Ends the current phase when it goes out of scope, thrown through or not, so a
// failed step never leaves its phase drawn under the next one.
class PhaseGuard {
 public:
  explicit PhaseGuard(ProgressPhases* phases) : phases_(phases) {}
  ~PhaseGuard() { endPhase(phases_); }
  PhaseGuard(const PhaseGuard&) = delete;
  PhaseGuard& operator=(const PhaseGuard&) = delete;

 private:
  ProgressPhases* phases_;
};

}  // namespace penumbra
