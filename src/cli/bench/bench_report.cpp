// The bench's table and JSON, both from the samples in the order they ran.
#include "cli/bench/bench_report.h"
#include "plan/cpu_report.h"
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <functional>

namespace penumbra {
namespace {

using Pick = std::function<double(const BenchSample&)>;

MinMedian statAt(const std::vector<BenchSample>& samples, int threads, const Pick& pick) {
  std::vector<double> values;
  for (const BenchSample& s : samples) {
    if (s.threads == threads) values.push_back(pick(s));
  }
  return minMedian(values);
}

Pick stage(double Timings::*field) {
  return [field](const BenchSample& s) { return s.time.*field; };
}

double cpuShare(const BenchSample& s) { return s.cpu.share; }

// Speed-ups are against the fewest threads given.
int baseOf(const BenchOutcome& o) { return *std::min_element(o.threads.begin(), o.threads.end()); }

double speedup(double base, double t) { return t > 0.0 ? base / t : 0.0; }

std::string threadsLabel(int t) { return fmt::format("{} thread{}", t, t == 1 ? "" : "s"); }

std::string tableHeader(const BenchOutcome& o) {
  const int base = baseOf(o);
  std::string top = fmt::format("{:<12}", "seconds"), under = fmt::format("{:<12}", "stage");
  for (int t : o.threads) {
    top += fmt::format("{:>18}", threadsLabel(t));
    under += fmt::format("{:>9}{:>9}", "min", "median");
  }
  for (int t : o.threads) {
    if (t == base) continue;
    top += fmt::format("{:>20}", fmt::format("speed-up {}/{}", t, base));
    under += fmt::format("{:>10}{:>10}", "min", "median");
  }
  return top + "\n" + under + "\n";
}

std::string tableRow(const BenchOutcome& o, const std::string& label, const std::vector<BenchSample>& samples,
                     const Pick& pick, bool ratios) {
  const int base = baseOf(o);
  const char* format = ratios ? "{:>9.3f}{:>9.3f}" : "{:>9.2f}{:>9.2f}";
  std::string row = fmt::format("{:<12}", label);
  for (int t : o.threads) {
    const MinMedian m = statAt(samples, t, pick);
    row += fmt::format(format, m.min, m.median);
  }
  const MinMedian b = statAt(samples, base, pick);
  for (int t : o.threads) {
    if (t == base || !ratios) continue;
    const MinMedian m = statAt(samples, t, pick);
    row += fmt::format("{:>9.2f}x{:>9.2f}x", speedup(b.min, m.min), speedup(b.median, m.median));
  }
  return row + "\n";
}

// A stage no sample spent time in (no photons, exact lookups, no image) is left out.
bool timed(const std::vector<BenchSample>& samples, double Timings::*field) {
  return std::any_of(samples.begin(), samples.end(), [&](const BenchSample& s) { return s.time.*field > 0.0; });
}

nlohmann::json statsJson(const BenchOutcome& o, const std::vector<BenchSample>& samples, const Pick& pick,
                         bool ratios) {
  nlohmann::json j;
  const int base = baseOf(o);
  const MinMedian b = statAt(samples, base, pick);
  for (int t : o.threads) {
    const MinMedian m = statAt(samples, t, pick);
    j[std::to_string(t)] = {{"min", m.min}, {"median", m.median}};
    if (ratios && t != base) {
      j["speedup"][fmt::format("{}/{}", t, base)] = {{"min", speedup(b.min, m.min)},
                                                      {"median", speedup(b.median, m.median)}};
    }
  }
  return j;
}

nlohmann::json samplesJson(const std::vector<BenchSample>& samples, bool stages) {
  nlohmann::json runs = nlohmann::json::array();
  for (const BenchSample& s : samples) {
    nlohmann::json r = {{"threads", s.threads}, {"round", s.round}};
    if (stages) {
      for (const TimingField& f : kTimingFields) r["time_s"][f.name] = s.time.*f.field;
    } else {
      r["seconds"] = s.time.total;
    }
    addCpuFields(r, s.cpu);
    runs.push_back(std::move(r));
  }
  return runs;
}

}  // namespace

MinMedian minMedian(std::vector<double> v) {
  if (v.empty()) return {};
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return {v.front(), n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2])};
}

std::string benchTable(const BenchOutcome& o) {
  const int base = baseOf(o);
  std::string threads;
  for (int t : o.threads) threads += (threads.empty() ? "" : ",") + std::to_string(t);
  std::string out = fmt::format("penumbra bench: {} scene{}, threads {} interleaved, {} round{}{}\n",
                                o.scenes.size(), o.scenes.size() == 1 ? "" : "s", threads, o.repeat,
                                o.repeat == 1 ? "" : "s",
                                o.whole.loadAverage >= 0.0 ? fmt::format(", load {:.2f} at start", o.whole.loadAverage) : "");
  const MinMedian controlBase = statAt(o.control, base, stage(&Timings::total));
  for (const SceneBench& s : o.scenes) {
    out += fmt::format("\n{} ({}): {}\n", s.name, s.path, s.settings) + tableHeader(o);
    for (const TimingField& f : kTimingFields) {
      if (timed(s.samples, f.field)) out += tableRow(o, f.name, s.samples, stage(f.field), true);
    }
    out += tableRow(o, "cpu share", s.samples, cpuShare, false);
    out += tableRow(o, "control", o.control, stage(&Timings::total), true);
    const MinMedian totalBase = statAt(s.samples, base, stage(&Timings::total));
    for (int t : o.threads) {
      if (t == base) continue;
      const double scene = speedup(totalBase.min, statAt(s.samples, t, stage(&Timings::total)).min);
      const double control = speedup(controlBase.min, statAt(o.control, t, stage(&Timings::total)).min);
      out += fmt::format("speed-up {}/{} of the total: {:.2f}x, beside the control's {:.2f}x (compute only, the "
                         "same run: what the machine could give)\n",
                         t, base, scene, control);
    }
  }
  return out;
}

std::string benchJson(const BenchOutcome& o) {
  nlohmann::json j;
  j["threads"] = o.threads;
  j["repeat"] = o.repeat;
  j["overrides"] = o.overrides;
  j["whole"] = {{"wall_s", o.whole.wallSeconds}};
  addCpuFields(j["whole"], o.whole);
  j["scenes"] = nlohmann::json::array();
  for (const SceneBench& s : o.scenes) {
    nlohmann::json scene = {{"scene", s.path}, {"name", s.name}, {"settings", s.settings}};
    for (const TimingField& f : kTimingFields) scene["stages_s"][f.name] = statsJson(o, s.samples, stage(f.field), true);
    scene["cpu_share"] = statsJson(o, s.samples, cpuShare, false);
    scene["runs"] = samplesJson(s.samples, true);
    j["scenes"].push_back(std::move(scene));
  }
  j["control"] = {{"what", "256 chunks of register-only arithmetic, parallel over the same threads"},
                  {"seconds", statsJson(o, o.control, stage(&Timings::total), true)},
                  {"cpu_share", statsJson(o, o.control, cpuShare, false)},
                  {"runs", samplesJson(o.control, false)}};
  j["notes"] = o.notes;
  return j.dump(2) + "\n";
}

}  // namespace penumbra
