// libFuzzer target for density grids: bytes -> a .vdb file a medium's "density" names,
// loaded through parseScene (OpenVDB reads files, not memory); then the lattice's
// invariants. OpenVDB runs in the reader process (core/density_codec.h): what is fuzzed
// here is that whatever it does with the file (fuzz/crashers/fuzz_vdb_reader/: sizes of
// exabytes, strings of gigabytes), this process gets a one-line refusal or a valid grid.
// The voxel budget is small, so a file claiming a large box is refused by the budget
// rule, before the lattice is allocated, and the reader's memory cap is small with it.
#include "core/error.h"
#include "io/scene_loader.h"
#include "fuzz_media_checks.h"
#include "fuzz_scratch.h"

#include <cstdint>
#include <string>

namespace {

using penumbra_fuzz::Scratch;

// The load budget here: a lattice of 4M floats at most.
constexpr uint64_t kFuzzBudgetBytes = 16ull << 20;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Scratch scratch;
  const std::string vdb = scratch.write("grid.vdb", std::string(reinterpret_cast<const char*>(data), size));
  const std::string json = R"({"camera": {"width": 4, "height": 4}, "render": {"model": "physical"},
    "media": [{"name": "smoke", "sigma_s": 1, "density": {"file": ")" + vdb + R"("}}],
    "objects": [{"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "medium": "smoke"}]})";
  try {
    penumbra_fuzz::checkMedia(penumbra::parseScene(json, vdb + ".json", {}, {kFuzzBudgetBytes, "the fuzz budget"}));
  } catch (const penumbra::InputError&) {
    // The documented rejection; anything else escaping is a finding.
  }
  return 0;
}
