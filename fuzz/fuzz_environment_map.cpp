// libFuzzer target for environment maps: bytes -> an .exr (OpenEXR magic) or .hdr
// file that a scene's "environment" names, loaded through parseScene; then the map
// invariants the samplers rely on. The scene fuzzer only names files, so it never
// mutates the headers OpenImageIO and the map reader judge.
#include "core/lights/environment_map.h"
#include "core/error.h"
#include "io/scene_loader.h"
#include "fuzz_scratch.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

using penumbra_fuzz::Scratch;

// What a map may make the loader allocate here: small, so an input claiming a large
// map is refused by the budget rule (the rule under test) rather than by -rss_limit_mb.
constexpr uint64_t kFuzzBudgetBytes = 64ull << 20;

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "fuzz_environment_map: invariant broken: %s\n", what);
  std::abort();
}

// core/lights/environment_map.h: width x height texels, finite and >= 0, CDFs of the documented
// sizes ending at 1.
void checkMap(const penumbra::Scene& scene) {
  const penumbra::Light* sky = penumbra::environmentOf(scene);
  if (!sky) broken("no environment light");
  const penumbra::EnvironmentMap* map = sky->environment.get();
  if (!map) broken("a map scene without a map");
  const size_t w = size_t(map->width), h = size_t(map->height);
  if (map->width < 2 || map->height < 1 || map->texels.size() != w * h) broken("texels != width x height");
  for (const penumbra::Color& c : map->texels) {
    if (!penumbra::isFinite(c) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f) broken("texel not finite and >= 0");
  }
  if (map->marginal.size() != h + 1 || map->conditional.size() != h * (w + 1)) broken("table sizes");
  if (map->marginal.back() != 1.0f) broken("marginal CDF does not end at 1");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Scratch scratch;
  const std::string input(reinterpret_cast<const char*>(data), size);
  const bool exr = input.compare(0, 4, std::string("\x76\x2f\x31\x01", 4)) == 0;
  const std::string map = scratch.write(exr ? "map.exr" : "map.hdr", input);
  const std::string json = R"({"camera": {"width": 4, "height": 4}, "environment": {"map": ")" + map + R"("}})";
  try {
    checkMap(penumbra::parseScene(json, map + ".json", {}, {kFuzzBudgetBytes, "the fuzz budget"}));
  } catch (const penumbra::InputError&) {
    // The documented rejection; anything else escaping is a finding.
  }
  return 0;
}
