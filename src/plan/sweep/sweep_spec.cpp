// Value lists, knob-to-key mapping and the grid's expansion.
#include "plan/sweep/sweep_spec.h"
#include "core/error.h"
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <fmt/format.h>

namespace penumbra {
namespace {

bool asNumber(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(out);
}

// Highest value's index: numerically when every value is a number, else the last.
size_t highestValue(const std::vector<std::string>& values) {
  size_t best = values.size() - 1;
  double top = 0.0;
  for (size_t i = 0; i < values.size(); ++i) {
    double v = 0.0;
    if (!asNumber(values[i], v)) return values.size() - 1;
    if (i == 0 || v > top) { top = v; best = i; }
  }
  return best;
}

std::string slugOf(const std::string& id) {
  std::string slug;
  for (char c : id) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-') slug += c;
    else if (c == '=') slug += '-';
    else if (c == ' ') slug += '_';
    else slug += '~';
  }
  return slug;
}

}  // namespace

std::vector<std::string> splitValues(const std::string& list, const std::string& option) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t comma = list.find(',', start);
    const std::string item = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (item.empty()) throw InputError(option + ": empty value in '" + list + "'");
    out.push_back(item);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

std::string overrideValue(const std::string& value) {
  double v = 0.0;
  if (asNumber(value, v) && v == std::floor(v) && std::fabs(v) < 9.007199254740992e15 &&
      value.find_first_of(".eE") != std::string::npos) {
    return fmt::format("{:.0f}", v);
  }
  return value;
}

SweepKnob namedKnob(const std::string& name, const std::string& list, const TransportModel& model, bool media) {
  SweepKnob knob;
  knob.name = name;
  knob.values = splitValues(list, "--" + name);
  if (name == "photons" || name == "k") {
    // Every map that carries the model's light: photons.global and photons.caustic, ...
    // (and photons.volume where the scene has a medium: elsewhere no such map is built).
    for (MapKind k : model.lightMaps()) {
      if (k == MapKind::Volume && !media) continue;
      knob.keys.push_back(fmt::format("photons.{}{}", name == "k" ? "k_" : "", mapName(k)));
    }
  } else if (name == "depth") {
    knob.keys = {"render.max_depth"};
  } else if (name == "spp") {
    knob.keys = {"camera.spp"};
  } else {
    throw InputError("sweep: unknown knob '" + name + "'");
  }
  return knob;
}

SweepKnob keyKnob(const std::string& arg) {
  const size_t eq = arg.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError("--vary: expected KEY=v1,v2,..., got '" + arg + "'");
  }
  SweepKnob knob;
  knob.name = arg.substr(0, eq);
  knob.keys = {knob.name};
  knob.values = splitValues(arg.substr(eq + 1), "--vary " + knob.name);
  return knob;
}

SweepKnob threadsKnob(const std::string& list) {
  SweepKnob knob;
  knob.name = kThreadsKnob;
  knob.values = splitValues(list, "--threads");
  for (const std::string& v : knob.values) {
    char* end = nullptr;
    const long n = std::strtol(v.c_str(), &end, 10);
    if (*end != '\0' || n < 1 || n > 1024) {
      throw InputError("--threads: '" + v + "' is not a thread count in 1..1024");
    }
  }
  return knob;
}

int runThreads(const SweepSpec& spec, const SweepRun& run) {
  for (size_t k = 0; k < spec.knobs.size() && k < run.values.size(); ++k) {
    if (spec.knobs[k].name == kThreadsKnob) return std::atoi(run.values[k].c_str());
  }
  return 0;
}

std::vector<int> threadCounts(const SweepSpec& spec) {
  std::vector<int> counts;
  for (const SweepKnob& k : spec.knobs) {
    if (k.name != kThreadsKnob) continue;
    for (const std::string& v : k.values) counts.push_back(std::atoi(v.c_str()));
  }
  std::sort(counts.begin(), counts.end(), std::greater<int>());
  counts.erase(std::unique(counts.begin(), counts.end()), counts.end());
  return counts;
}

SweepSpec expandGrid(std::vector<SweepKnob> knobs, const std::vector<std::string>& baseOverrides,
                     size_t maxRuns) {
  if (knobs.empty()) throw InputError("sweep: nothing to vary (give --photons, --k, --depth, --spp or --vary)");
  size_t total = 1;
  for (size_t i = 0; i < knobs.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      for (const std::string& key : knobs[i].keys) {
        for (const std::string& other : knobs[j].keys) {
          if (key == other) throw InputError("sweep: " + key + " is varied twice (" + knobs[j].name + ", " + knobs[i].name + ")");
        }
      }
    }
    total *= knobs[i].values.size();
    if (total > maxRuns) throw InputError(fmt::format("sweep: more than {} runs", maxRuns));
  }
  SweepSpec spec;
  std::vector<size_t> top;
  for (const SweepKnob& k : knobs) top.push_back(highestValue(k.values));
  std::vector<size_t> at(knobs.size(), 0);
  for (size_t r = 0; r < total; ++r) {
    SweepRun run;
    run.overrides = baseOverrides;
    bool highest = true;
    for (size_t k = 0; k < knobs.size(); ++k) {
      const std::string& v = knobs[k].values[at[k]];
      run.values.push_back(v);
      run.id += (k ? " " : "") + knobs[k].name + "=" + v;
      for (const std::string& key : knobs[k].keys) run.overrides.push_back(key + "=" + overrideValue(v));
      highest = highest && at[k] == top[k];
    }
    run.slug = slugOf(run.id);
    if (highest) spec.highest = r;
    spec.runs.push_back(std::move(run));
    for (size_t k = knobs.size(); k-- > 0;) {  // the last knob varies fastest
      if (++at[k] < knobs[k].values.size()) break;
      at[k] = 0;
    }
  }
  spec.knobs = std::move(knobs);
  return spec;
}

}  // namespace penumbra
