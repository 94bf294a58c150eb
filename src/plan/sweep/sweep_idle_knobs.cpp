// Idle knobs: runs grouped by every other knob's value, their images compared pixel
// for pixel (read back from the sweep folder), and a reason named where one is known.
#include "plan/sweep/sweep_idle_knobs.h"
#include "io/image_io.h"
#include <algorithm>
#include <cstring>
#include <map>

namespace penumbra {

namespace {

// Keys only the shadow gate reads: they change nothing while the gate is off.
bool gateOnly(const SweepKnob& knob) {
  return std::all_of(knob.keys.begin(), knob.keys.end(), [](const std::string& k) {
    return k == "photons.shadow" || k == "photons.k_shadow" || k == "photons.lookup_cell";
  });
}

bool samePixels(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

}  // namespace

std::vector<std::string> idleKnobNotes(const SweepSpec& spec, const std::vector<SweepRow>& rows,
                                       const std::filesystem::path& dir) {
  std::vector<std::string> notes;
  for (size_t k = 0; k < spec.knobs.size(); ++k) {
    // Thread counts render identical images by design (deterministic).
    if (spec.knobs[k].values.size() < 2 || spec.knobs[k].name == kThreadsKnob) continue;
    std::map<std::vector<std::string>, std::vector<size_t>> groups;
    for (size_t i = 0; i < rows.size(); ++i) {
      if (rows[i].values.size() != spec.knobs.size() || rows[i].image.empty()) continue;
      std::vector<std::string> others = rows[i].values;
      others.erase(others.begin() + static_cast<std::ptrdiff_t>(k));
      groups[others].push_back(i);
    }
    bool compared = false, idle = true;
    for (const auto& [others, members] : groups) {
      if (members.size() < 2 || !idle) continue;
      compared = true;
      const Image first = readImage((dir / rows[members[0]].image).string());
      for (size_t m = 1; m < members.size() && idle; ++m) {
        idle = samePixels(first, readImage((dir / rows[members[m]].image).string()));
      }
    }
    if (!compared || !idle) continue;
    const bool gated = std::any_of(rows.begin(), rows.end(), [](const SweepRow& r) { return r.gate; });
    const std::string why = gateOnly(spec.knobs[k]) && !gated
                                ? "the gate was off in every run and only the gate reads it: --set photons.gate=on"
                                : "the plan may have turned off what it sets: penumbra plan SCENE says why";
    notes.push_back("knob " + spec.knobs[k].name + " changed nothing: its runs rendered identical images (" +
                    why + ")");
  }
  return notes;
}

}  // namespace penumbra
