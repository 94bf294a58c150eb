// The "environment" key from JSON to pixels: a map read through OpenImageIO, the
// studio or the uniform sky becomes the last light, every bad value is refused in one line naming the file and JSON path
// (exit 2 from the CLI), and the shipped example renders in both models.
#include "core/lights/environment_map.h"
#include "core/lights/studio_environment.h"
#include "io/scene_loader.h"
#include "support/cli_run.h"
#include "support/scratch_dir.h"
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

const std::string kBody =
    R"("objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}])";

std::string sceneWith(const std::string& environment) {
  return "{" + kBody + ", \"environment\": " + environment + "}";
}

void writeExr(const fs::path& path, int w, int h, const std::vector<float>& rgb) {
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(path.string(), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
  out->close();
}

std::string refusal(const std::string& text, const std::string& file) {
  try {
    parseScene(text, file);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(loaded)";
}

TEST(EnvironmentScene, ConstantSkyAndMapBecomeTheLastLight) {
  testing::ScratchDir dir;
  std::vector<float> rgb(8 * 4 * 3, 0.25f);
  rgb[(1 * 8 + 2) * 3 + 1] = 9.0f;
  writeExr(dir / "sky.exr", 8, 4, rgb);
  const std::string file = (dir / "s.json").string();
  const Scene sky = parseScene(sceneWith(R"({"color": [0.5, 0.6, 0.7], "intensity": 2})"), file);
  ASSERT_EQ(sky.lights.size(), 1u);
  EXPECT_EQ(sky.lights.back().type, LightType::Environment);
  EXPECT_EQ(environmentOf(sky), &sky.lights.back());
  EXPECT_FALSE(sky.lights.back().environment);
  EXPECT_FLOAT_EQ(sky.lights.back().radiance().b, 1.4f);

  const std::string withLights = "{" + kBody +
      R"(, "lights": [{"type": "point", "position": [0, 3, 0]}], "environment": {"map": "sky.exr", "rotation": 90}})";
  const Scene mapped = parseScene(withLights, file);
  ASSERT_EQ(mapped.lights.size(), 2u);
  EXPECT_EQ(mapped.lights[0].type, LightType::Point) << "the environment comes after every other light";
  ASSERT_TRUE(mapped.lights[1].environment);
  EXPECT_EQ(mapped.lights[1].environment->width, 8);
  EXPECT_FLOAT_EQ(mapped.lights[1].environment->texels[1 * 8 + 2].g, 9.0f);
  EXPECT_NE(std::find(mapped.inputs.begin(), mapped.inputs.end(), (dir / "sky.exr").string()), mapped.inputs.end())
      << "the map is one of the scene's inputs";
}

TEST(EnvironmentScene, StudioAndUniformAreNamedSkies) {
  // "studio" is the built-in map with its grey background; "uniform" the constant sky of
  // radiance 1, the same light as {}; an object names a preset and turns, scales or
  // re-colours it; "background" sets what camera rays see for any environment.
  const std::string file = "s.json";
  const Scene studio = parseScene(sceneWith(R"("studio")"), file);
  ASSERT_EQ(studio.lights.size(), 1u);
  ASSERT_TRUE(studio.lights[0].environment);
  EXPECT_EQ(studio.lights[0].environment->width, studio::kWidth);
  EXPECT_EQ(studio.render.environmentBackground, Color(studio::kBackground));
  const Scene turned =
      parseScene(sceneWith(R"({"preset": "studio", "rotation": 90, "intensity": 2, "background": 0.5})"), file);
  EXPECT_FLOAT_EQ(turned.lights[0].environment->rotation, 0.5f * 3.14159265f);
  EXPECT_FLOAT_EQ(turned.lights[0].radiance().r, 2.0f);
  EXPECT_EQ(turned.render.environmentBackground, Color(0.5f));
  for (const char* uniform : {R"("uniform")", R"({})", R"({"preset": "uniform"})"}) {
    const Scene u = parseScene(sceneWith(uniform), file);
    ASSERT_EQ(u.lights.size(), 1u) << uniform;
    EXPECT_FALSE(u.lights[0].environment) << uniform;
    EXPECT_EQ(u.lights[0].radiance(), Color(1.0f)) << uniform;
    EXPECT_FALSE(u.render.environmentBackground.has_value()) << uniform;
  }
  EXPECT_EQ(parseScene(sceneWith(R"({"background": [0, 0.1, 0.2]})"), file).render.environmentBackground,
            Color(0.0f, 0.1f, 0.2f));
}

TEST(EnvironmentScene, BadValuesAreRefusedNamingFileAndPath) {
  testing::ScratchDir dir;
  std::vector<float> rgb(4 * 2 * 3, 0.5f);
  rgb[5] = -1.0f;
  writeExr(dir / "negative.exr", 4, 2, rgb);
  rgb[5] = std::nanf("");
  writeExr(dir / "nan.exr", 4, 2, rgb);
  dir.write("sky.png", "not really a png");
  const std::string file = (dir / "s.json").string();
  struct Case {
    std::string environment, where, what;
  };
  const std::vector<Case> cases = {
      {R"({"intensity": -1})", "environment.intensity", "must be >= 0"},
      {R"({"color": [1, 1]})", "environment.color", ""},
      {R"({"intensity": "2"})", "environment.intensity", ""},
      {R"({"map": "missing.exr"})", "environment.map", "environment map " + (dir / "missing.exr").string() + ": does not exist"},
      {R"({"map": "sky.png"})", "environment.map", "an .exr or .hdr file"},
      {R"({"map": "negative.exr"})", "environment.map", "negative value at row 0, column 1"},
      {R"({"map": "nan.exr"})", "environment.map", "non-finite value at row 0, column 1"},
      {R"({"rotation": 30})", "environment.rotation", "give \"map\" too"},
      {R"("studoi")", "environment", "did you mean \"studio\""},
      {R"(3)", "environment", "must be \"studio\", \"uniform\" or an object, got"},
      {R"({"preset": "studio", "map": "sky.png"})", "environment.map", "a map and the studio are two skies"},
      {R"({"preset": "sun"})", "environment.preset", "unknown value \"sun\""},
      {R"({"preset": "studio", "rotation": 400})", "environment.rotation", ""},
      {R"({"background": [1, -1, 0]})", "environment.background", ""},
      {R"({"map": "negative.exr", "background": -1})", "environment.background", ""},  // before the map is read
      {R"({"colour": [1, 1, 1]})", "environment", "colour"},
      {R"([1, 2])", "environment", ""},
  };
  for (const Case& c : cases) {
    const std::string message = refusal(sceneWith(c.environment), file);
    EXPECT_EQ(message.rfind(file + ": " + c.where, 0), 0u) << c.environment << " -> " << message;
    EXPECT_NE(message.find(c.what), std::string::npos) << c.environment << " -> " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(EnvironmentScene, ShippedExampleRendersInBothModels) {
  // scenes/environment_sky.json through the CLI at 32 x 24: exit 0, and the sky seen
  // by the top-left pixel is the sky's radiance (a constant sky: every missed ray sees it),
  // within half-float rounding (1e-3 relative).
  testing::ScratchDir dir;
  const std::string scene = testing::quote(std::string(PENUMBRA_SOURCE_DIR) + "/scenes/environment_sky.json");
  for (const char* model : {"physical", "classic"}) {
    const fs::path out = dir / (std::string(model) + ".exr");
    const testing::CliResult r = testing::runCli(
        "render " + scene + " -q -o " + testing::quote(out.string()) +
        " --set camera.width=32 --set camera.height=24 --set camera.spp=1 --set " +
        testing::quote(std::string("render.model=\"") + model + "\""));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto in = OIIO::ImageInput::open(out.string());
    ASSERT_TRUE(in);
    std::vector<float> px(32 * 24 * in->spec().nchannels);
    ASSERT_TRUE(in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, px.data()));
    const Scene s = loadScene(std::string(PENUMBRA_SOURCE_DIR) + "/scenes/environment_sky.json");
    const Color sky = s.lights.back().radiance();
    // EXR beauty is half float: 2^-11 relative rounding.
    EXPECT_NEAR(px[0], sky.r, 1e-3f * sky.r) << model << ": the top-left pixel sees the sky";
  }
}

}  // namespace
}  // namespace penumbra
