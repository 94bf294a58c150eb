// The pixels that see an emitter, through the render: an emitting quad over the left
// half of an orthographic view marks columns 0-15 of 32, and column 16 beside its edge
// (the one-pixel growth); the lighting's figures leave them out, and the bias view is
// 0 there; the same for one thread or two. The bias view needs 4 passes and the whole
// frame.
#include "core/error_estimate.h"
#include "plan/pipeline.h"
#include "support/render_file.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>

using namespace penumbra;

namespace {

// A white floor lit by a point light, and an emitting quad in front of it covering
// x < 0: the left half of the view (x in [-1, 1]).
const char* kHalfEmitter = R"({
  "name": "half_emitter",
  "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "up": [0, 1, 0], "ortho_height": 2,
             "width": 32, "height": 32, "spp": 1},
  "lights": [{"type": "point", "position": [0.5, 0, 2], "color": [1, 1, 1], "intensity": 2}],
  "materials": {"floor": {"diffuse": 0.6}, "lamp": {"emission": 3}},
  "objects": [{"type": "quad", "corner": [-3, -3, 0], "edge1": [6, 0, 0], "edge2": [0, 6, 0], "material": "floor"},
              {"type": "quad", "corner": [-3, -3, 0.5], "edge1": [3, 0, 0], "edge2": [0, 6, 0], "material": "lamp"}],
  "render": {"model": "physical", "seed": 5},
  "photons": {"gate": false, "global": 4000, "caustic": 0, "passes": 4}
})";

using penumbra::testing::renderFile;

TEST(EmitterMask, AnEmitterInViewIsLeftOutOfTheLighting) {
  const penumbra::testing::ScratchDir dir;
  const std::string file = dir.write("half.json", kHalfEmitter).string();
  const RenderResult two = renderFile(file, {}, 2);
  const ErrorEstimate& e = two.stats.error;
  ASSERT_EQ(e.source, ErrorSource::Passes);
  EXPECT_DOUBLE_EQ(e.emitterShare, 17.0 / 32.0);
  ASSERT_TRUE(e.lightingKnown());
  EXPECT_GE(e.lightingBiasRmse, 0.0) << "4 passes: the bias is checked";
  const RenderResult one = renderFile(file, {}, 1);
  EXPECT_EQ(one.stats.error.emitterShare, e.emitterShare);
  EXPECT_EQ(one.stats.error.lightingNoiseRmse, e.lightingNoiseRmse) << "one thread or two";
  // The bias view is 0 wherever the mask is.
  const RenderResult bias = renderFile(file, {}, 2, "bias");
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x <= 16; ++x) EXPECT_EQ(bias.image.pixels[size_t(y) * 32 + x], Color(0.0f)) << x << "," << y;
}

TEST(EmitterMask, TheBiasViewNeedsFourPassesAndTheWholeFrame) {
  const penumbra::testing::ScratchDir dir;
  const std::string file = dir.write("half.json", kHalfEmitter).string();
  EXPECT_THROW(renderFile(file, {"photons.passes=2"}, 2, "bias"), InputError);
  RenderRequest req;
  req.scenePath = file;
  req.aov = "bias";
  req.tile = TileRequest{};
  req.tile->count = 2;
  req.tile->index = 1;
  EXPECT_THROW(runRender(req), InputError) << "a tile's neighbours are another tile's";
}

}  // namespace
