// Camera-ray packets change nothing but speed: shipped scenes (classic and physical;
// beauty, depth, normal, indirect, direct and caustic views; textures, mirrors, glass,
// area lights, the gate on and off) render to the same bytes and the same ray counts
// with render.packets true and false.
#include "plan/pipeline.h"
#include <gtest/gtest.h>
#include <cstring>
#include <string>
#include <vector>

namespace penumbra {
namespace {

struct Case {
  const char* scene;
  const char* aov;  // empty: the scene's own view
  std::vector<std::string> overrides;
};

RenderResult render(const Case& c, bool packets) {
  RenderRequest req;
  req.scenePath = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/" + c.scene + ".json";
  req.session.threads = 2;
  req.aov = c.aov;
  // Small and cheap: an odd size leaves partial tiles and partial packets.
  req.overrides = {"camera.width=83", "camera.height=61", "photons.shadow=40000"};
  req.overrides.insert(req.overrides.end(), c.overrides.begin(), c.overrides.end());
  req.overrides.push_back(packets ? "render.packets=true" : "render.packets=false");
  return runRender(req);
}

bool samePixels(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

class PacketsMatchSingleRays : public ::testing::TestWithParam<Case> {};

TEST_P(PacketsMatchSingleRays, SameBytesAndCounts) {
  const Case& c = GetParam();
  RenderResult single = render(c, false);
  RenderResult packet = render(c, true);
  ASSERT_EQ(single.image.width, 83);
  EXPECT_TRUE(samePixels(single.image, packet.image)) << c.scene << " " << c.aov;
  const RayCounts &a = single.stats.rays, &b = packet.stats.rays;
  EXPECT_EQ(a.camera, b.camera);
  EXPECT_EQ(a.shadow, b.shadow);
  EXPECT_EQ(a.shadowRaysAvoided, b.shadowRaysAvoided);
  EXPECT_EQ(a.gateQueries, b.gateQueries);
  EXPECT_EQ(a.gatherQueries, b.gatherQueries);
  EXPECT_EQ(a.nonfiniteSamples, b.nonfiniteSamples);
}

const char* kNoGate = "photons.gate=false";

INSTANTIATE_TEST_SUITE_P(
    Scenes, PacketsMatchSingleRays,
    ::testing::Values(
        Case{"fig01_depth", "", {}},                                   // depth view, teapot
        Case{"fig05_reflective_mesh", "normal", {}},                   // normal view
        Case{"fig02_phong", "", {}},                                   // classic, gate auto
        Case{"fig03_shadows", "", {kNoGate, "camera.spp=3"}},          // shadow packets, jitter
        Case{"fig04_reflection", "", {kNoGate}},                       // mirrors: secondary rays single
        Case{"fig11_gate_shadows", "", {kNoGate}},                     // two point lights
        Case{"fig11_gate_shadows", "", {"photons.gate=true"}},         // the gate decides: no shadow packets
        Case{"fig07_glass_in_box", "", {kNoGate}},                     // classic glass: tinted walks stay single
        Case{"fig13_cornell_indirect", "", {"photons.indirect=20000"}},  // indirect view
        Case{"fig14_cornell", "", {"photons.lookup=precomputed"}},    // gate verdicts from the cache
        Case{"showcase", "", {"camera.spp=1"}},                        // everything at once
        Case{"fig15_globe", "", {"camera.spp=2"}},                     // textured sphere
        Case{"fig16_texture_add", "", {"camera.spp=2", kNoGate}},      // textured, added
        Case{"soft_shadows", "", {"render.light_samples=2", "camera.spp=2"}},  // area lights stay single
        Case{"cornell_physical", "", {"photons.global=20000", "photons.caustic=20000"}},  // physical beauty
        Case{"cornell_physical", "direct", {"photons.global=20000", "photons.caustic=20000"}},                        // physical direct view
        Case{"cornell_physical", "caustic", {"photons.global=20000", "photons.caustic=20000"}},
        Case{"cornell_physical", "depth", {"photons.global=20000", "photons.caustic=20000"}}),
    // Named by scene, view and gate setting (the two fig11 cases differ only there),
    // so ctest lists Scenes/PacketsMatchSingleRays.SameBytesAndCounts/fig11_gate_shadows_gate_on
    // instead of /6 and the Case's raw bytes.
    [](const ::testing::TestParamInfo<Case>& tp) {
      const Case& c = tp.param;
      std::string name = c.scene;
      if (*c.aov) name += std::string("_") + c.aov;
      for (const std::string& o : c.overrides) {
        if (o == kNoGate) name += "_no_gate";
        if (o == "photons.gate=true") name += "_gate_on";
      }
      return name;
    });

}  // namespace
}  // namespace penumbra
