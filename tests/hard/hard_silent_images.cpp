// Hard cases, class "silent images": inputs that used to render a wrong image with
// exit 0 and no word. Each is now refused with one line naming the file and JSON
// path (texture transform offset and scale, a film finer than float resolves, an
// unknown alphaMode, a light index that is not an integer) or rendered right (a huge
// texture rotation), and the error estimate is finite wherever the image is, and
// said to be a lower bound where its probes found no error.
#include "hard/hard_cli.h"
#include "hard/hard_gltf_support.h"
#include "hard/hard_support.h"
#include "support/render_file.h"

#include <nlohmann/json.hpp>

#include <cmath>

namespace penumbra::hard_gltf {
namespace {

using hard::quote;
using hard::runCli;

// The triangle of hard_gltf_support.h with a 2x2 texture of one colour as its base
// colour (alpha 1), `transform` its KHR_texture_transform and `mode` its alphaMode.
json texturedTriangle(const ScratchDir& dir, const json& transform, const std::string& mode = "") {
  Image texture(2, 2);
  texture.pixels.assign(4, Color(0.5f, 0.25f, 0.125f));
  writeImage((dir / "base.png").string(), texture);
  json j = triangle();
  j["images"] = {{{"uri", "base.png"}}};
  j["textures"] = {{{"source", 0}}};
  json info = {{"index", 0}};
  if (!transform.is_null()) {
    info["extensions"]["KHR_texture_transform"] = transform;
    j["extensionsUsed"] = {"KHR_texture_transform"};
  }
  j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", info}}}}};
  if (!mode.empty()) j["materials"][0]["alphaMode"] = mode;
  j["meshes"][0]["primitives"][0]["material"] = 0;
  return j;
}

// One line on stderr naming the file and each of `parts`, exit 2, for `penumbra render`.
void expectRenderRefused(const ScratchDir& dir, const fs::path& scene, const std::vector<std::string>& parts) {
  const hard::CliResult r = runCli("render " + quote(scene.string()) + " -o " + quote((dir / "out.png").string()));
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(hard::occurrences(r.err, "\n"), 1u) << r.err;
  EXPECT_NE(r.err.find(scene.filename().string()), std::string::npos) << r.err;
  for (const std::string& p : parts) EXPECT_NE(r.err.find(p), std::string::npos) << "wanted \"" << p << "\" in: " << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.png"));
}

const std::string kTransform = "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform.";

// An offset or scale of 1e39 is a valid JSON double but +inf as a float: the uvs came
// out NaN (a black surface, a MASK one gone). Both are bounded as TEXCOORD_0 is.
TEST(HardSilentImages, TextureTransformOffsetAndScaleBeyondTheUvLimitAreRefused) {
  const ScratchDir dir;
  const std::pair<const char*, const char*> cases[] = {
      {R"({"offset": [1e39, 0]})", "offset"}, {R"({"offset": [0, -2e6]})", "offset"},
      {R"({"scale": [1e39, 1]})", "scale"},   {R"({"scale": [1, -1e7]})", "scale"},
      {R"({"offset": [1, 2, 3]})", "offset"}, {R"({"scale": "big"})", "scale"},
      {R"({"rotation": "half"})", "rotation"}};
  for (const auto& [transform, key] : cases) {
    for (const std::string mode : {"", "MASK"}) {
      expectRefused(dir, texturedTriangle(dir, json::parse(transform), mode), {"model.gltf: " + kTransform + key});
    }
  }
  const json huge = json::parse(R"({"scale": [1e39, 1]})");
  expectRefused(dir, texturedTriangle(dir, huge), {"within +-1e+06"});
  // Within the limit it loads, and through the CLI the refusal is one line, exit 2.
  const json edge = json::parse(R"({"offset": [-1e6, 0.5], "scale": [1e6, -1]})");
  EXPECT_EQ(refusal(dir.write("model.gltf", texturedTriangle(dir, edge).dump())), "");
  expectRenderRefused(dir, dir.write("mask.gltf", texturedTriangle(dir, huge, "MASK").dump()), {kTransform + "scale"});
}

// A rotation is an angle: any finite one places the texture, 1e39 radians included
// (taken modulo 2 pi in double). A one-colour texture looks the same at every angle,
// so the render must equal the untransformed one, pixel for pixel, with no sample dropped.
TEST(HardSilentImages, AHugeTextureRotationRendersAsTheAngleItIs) {
  const ScratchDir dir;
  const std::vector<std::string> small = {"camera.width=48", "camera.height=36"};
  for (const std::string mode : {"", "MASK"}) {
    const fs::path plain = dir.write("plain.gltf", texturedTriangle(dir, nullptr, mode).dump());
    const RenderResult want = testing::renderFile(plain.string(), small, 2);
    ASSERT_GT(hard::maxPixel(want.image), 0.05f) << mode << ": the triangle is lit and seen";
    for (double rotation : {1e39, -3e30, 7.0}) {
      const fs::path turned = dir.write("turned.gltf", texturedTriangle(dir, {{"rotation", rotation}}, mode).dump());
      const RenderResult got = testing::renderFile(turned.string(), small, 2);
      EXPECT_EQ(got.stats.rays.nonfiniteSamples, 0u) << mode << " " << rotation;
      EXPECT_EQ(hard::differingPixels(want.image, got.image, 1e-6f), 0)
          << mode << " rotation " << rotation << ":" << hard::worstPixels(want.image, got.image);
    }
  }
}

// An orthographic film 1e-30 tall puts every pixel's ray on one float position at the
// camera: one surface point over the whole image. The pixel step (height / pixels) must
// be at least 2^-21 of the camera position's largest coordinate (4 float steps).
TEST(HardSilentImages, AnOrthographicFilmFinerThanFloatAtTheCameraIsRefused) {
  const ScratchDir dir;
  auto ortho = [](double mag) {
    json j = triangle();
    j["cameras"] = {{{"type", "orthographic"}, {"orthographic", {{"xmag", mag}, {"ymag", mag}, {"znear", 0.1}, {"zfar", 100}}}}};
    j["nodes"].push_back({{"camera", 0}, {"translation", {0.25, 0.25, 3}}});
    j["scenes"][0]["nodes"].push_back(1);
    return j;
  };
  for (double mag : {1e-30, 1e-7}) expectRefused(dir, ortho(mag), {"model.gltf: cameras[0].orthographic.ymag", "2^-21"});
  // 2 ymag / 640 pixels (xmag = ymag: a square 640 x 640 film) against 2^-21 x 3.
  const double least = std::ldexp(3.0, -21) * 640.0 / 2.0;
  EXPECT_NE(refusal(dir.write("model.gltf", ortho(0.99 * least).dump())), "");
  EXPECT_EQ(refusal(dir.write("model.gltf", ortho(1.01 * least).dump())), "");
  // A sidecar's new width keeps the file's aspect: twice the pixels, half the step,
  // refused at the sidecar's camera.
  dir.write("model.json", R"({"camera": {"width": 1280}})");
  try {
    loadScene((dir / "model.gltf").string());
    ADD_FAILURE() << "a sidecar width of 1280 halves the step below the limit";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("model.json: camera: a pixel (ortho_height / height"), std::string::npos) << e.what();
  }
  fs::remove(dir / "model.json");
  expectRenderRefused(dir, dir.write("ortho.gltf", ortho(1e-30).dump()), {"cameras[0].orthographic.ymag"});

  const std::string scene = R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "ortho_height": 1e-30,
    "width": 64, "height": 48}, "objects": [{"type": "quad", "corner": [-1, -1, 0], "edge1": [2, 0, 0], "edge2": [0, 2, 0]}],
    "lights": [{"type": "point", "position": [0, 0, 2]}]})";
  expectRenderRefused(dir, dir.write("ortho.json", scene), {"camera.ortho_height", "2^-21"});
  // A fine film that float resolves renders: 1e-4 over 48 pixels at 3 is ~9 float steps.
  const fs::path fine = dir.write("fine.json", nlohmann::json::parse(scene).dump());
  const RenderResult r = testing::renderFile(fine.string(), {"camera.ortho_height=1e-4"}, 2);
  EXPECT_GT(hard::meanPixel(r.image), 0.0);
}

json withBogus(const std::string& key) {
  json j = triangle();
  if (key == "alphaMode") {
    j["materials"] = {{{"alphaMode", "bogus"}}};
    j["meshes"][0]["primitives"][0]["material"] = 0;
  } else {
    j["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 1}}};
    j["extensionsUsed"] = {"KHR_lights_punctual"};
    j["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", "0"}}}}}, {"translation", {0, 1, 1}}});
    j["scenes"][0]["nodes"].push_back(1);
  }
  return j;
}

TEST(HardSilentImages, AnAlphaModeOutsideTheSpecIsRefused) {
  const ScratchDir dir;
  expectRefused(dir, withBogus("alphaMode"), {"model.gltf: materials[0].alphaMode", "\"OPAQUE\", \"MASK\" or \"BLEND\"", "\"bogus\""});
  expectRenderRefused(dir, dir.write("bogus.gltf", withBogus("alphaMode").dump()), {"materials[0].alphaMode"});
  for (const std::string mode : {"OPAQUE", "MASK", "BLEND"}) {
    json j = withBogus("alphaMode");
    j["materials"][0]["alphaMode"] = mode;
    EXPECT_EQ(refusal(dir.write("model.gltf", j.dump())), "") << mode;
  }
}

// A node's light must be an integer index of a light, checked with the nodes before
// any accessor is read: a texture coordinate beyond +-1e6 (refused while the meshes
// are read) is not reached first.
TEST(HardSilentImages, ANodesLightIndexMustBeAnIntegerOfALightAndIsCheckedFirst) {
  const ScratchDir dir;
  const std::string key = "model.gltf: nodes[1].extensions.KHR_lights_punctual.light";
  expectRefused(dir, withBogus("light"), {key, "must be the integer index of a light"});
  for (const json& index : {json(1), json(-1), json(0.5), json(nullptr), json::array({0})}) {
    json j = withBogus("light");
    j["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = index;
    SCOPED_TRACE(index.dump());
    expectRefused(dir, j, {"model.gltf: nodes[1].extensions.KHR_lights_punctual"});  // null: no "light" at all
  }
  json late = withBogus("light");
  late["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 3;
  // Every uv of the triangle at 2e6, beyond TEXCOORD_0's limit.
  late["buffers"][0]["uri"] = dataUri(kVertexData.substr(0, 72) + bytesOf<float>({2e6f, 0, 2e6f, 0, 2e6f, 0}) +
                                      std::string("\0\1\2\0", 4));
  expectRefused(dir, late, {key, "light 3 does not exist"});
  expectRenderRefused(dir, dir.write("light.gltf", withBogus("light").dump()), {"nodes[1].extensions.KHR_lights_punctual.light"});
  json fine = withBogus("light");
  fine["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 0;
  EXPECT_EQ(refusal(dir.write("model.gltf", fine.dump())), "");
}

// A floor half shaded by a board 0.3 above it, under a sky of radiance `sky`,
// physical, one light sample, 4 samples per pixel: the samples' spread is the error
// estimate (ErrorSource::Samples), ~0.04 RMSE under a sky of 1.
std::string skyFloor(double sky) {
  return R"({"camera": {"position": [0, 2, 3], "look_at": [0, 0, 0], "width": 24, "height": 16, "spp": 4},
    "environment": {"intensity": )" + hard::num(sky) + R"(},
    "objects": [{"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]},
                {"type": "quad", "corner": [-0.5, 0.3, -0.5], "edge1": [0, 0, 1], "edge2": [1, 0, 0]}],
    "render": {"model": "physical", "light_samples": 1}, "photons": {"global": 0, "caustic": 0, "shadow": 0}})";
}

// Under a 1e20 sky the squared difference of a pixel's even and odd means (~1e40)
// overflowed float: "~inf". Every sample scales by 1e20, so the estimate must too.
TEST(HardSilentImages, TheSampleSpreadUnderABrightSkyIsFiniteAndScalesWithIt) {
  const RenderResult one = hard::renderJson(skyFloor(1.0), {}, "sky1");
  const RenderResult bright = hard::renderJson(skyFloor(1e20), {}, "sky20");
  ASSERT_EQ(one.stats.error.source, ErrorSource::Samples);
  ASSERT_EQ(bright.stats.error.source, ErrorSource::Samples);
  ASSERT_GT(one.stats.error.noiseRmse, 1e-3) << "the sky's samples spread";
  ASSERT_TRUE(std::isfinite(hard::maxPixel(bright.image)));
  EXPECT_TRUE(std::isfinite(bright.stats.error.noiseRmse)) << describeError(bright.stats.error);
  EXPECT_NEAR(bright.stats.error.noiseRmse / one.stats.error.noiseRmse, 1e20, 1e20 * 1e-4);
  // The error view is the same spread per pixel: finite, scaled alike.
  const RenderResult view = hard::renderJson(skyFloor(1e20), {"render.aov=error"}, "sky20e");
  const RenderResult viewOne = hard::renderJson(skyFloor(1.0), {"render.aov=error"}, "sky1e");
  ASSERT_TRUE(std::isfinite(hard::maxPixel(view.image)));
  EXPECT_NEAR(hard::maxPixel(view.image) / hard::maxPixel(viewOne.image), 1e20, 1e20 * 1e-4);
}

// A floor seen through a film 16384 x 1: the probes (512 of 16384 pixels) find no
// error where the error view (every pixel probed) finds some. Their 0 is a lower
// bound and says so everywhere the figure is shown.
TEST(HardSilentImages, ProbesThatFoundNoErrorReportALowerBound) {
  const ScratchDir dir;
  std::string scene = hard::kFloorScene;
  const std::string size = "\"width\": 16, \"height\": 12";
  scene.replace(scene.find(size), size.size(), "\"width\": 16384, \"height\": 1");
  const fs::path file = dir.write("strip.json", scene);
  const RenderResult r = testing::renderFile(file.string(), {}, 2);
  ASSERT_EQ(r.stats.error.source, ErrorSource::Probes);
  ASSERT_EQ(r.stats.error.noiseRmse, 0.0);
  EXPECT_TRUE(r.stats.error.lowerBound);
  const RenderResult every = testing::renderFile(file.string(), {}, 2, "error");
  EXPECT_GT(every.stats.error.noiseRmse, 1e-3) << "every pixel probed finds error the sample missed";
  EXPECT_FALSE(every.stats.error.lowerBound);

  const fs::path out = dir / "strip.exr", stats = dir / "stats.json";
  const hard::CliResult cli = runCli("render " + quote(file.string()) + " -t 2 -o " + quote(out.string()) + " --stats " +
                                     quote(stats.string()));
  ASSERT_EQ(cli.exitCode, 0) << cli.err;
  const std::string said = "error: at least 0 RMSE";
  EXPECT_NE(cli.err.find(said), std::string::npos) << cli.err;
  EXPECT_EQ(cli.err.find("~0 RMSE"), std::string::npos) << cli.err;
  const json report = json::parse(testing::readFile(stats));
  EXPECT_EQ(report["error"]["lower_bound"], true);
  EXPECT_EQ(report["error"]["noise_rmse"], 0.0);
  EXPECT_EQ(report["error"]["text"].get<std::string>().rfind("at least 0 RMSE", 0), 0u) << report["error"];
  EXPECT_EQ(readImageAttribute(out.string(), "penumbra:error.lower_bound"), "1");
  EXPECT_EQ(readImageAttribute(out.string(), "penumbra:error").rfind("at least 0 RMSE", 0), 0u);

  // A figure the probes did find is an estimate, "~", not a bound.
  const fs::path small = dir.write("floor.json", hard::kFloorScene);
  const hard::CliResult found = runCli("render " + quote(small.string()) + " -t 2 -o " + quote(out.string()) + " --stats " +
                                       quote(stats.string()));
  ASSERT_EQ(found.exitCode, 0) << found.err;
  EXPECT_EQ(json::parse(testing::readFile(stats))["error"]["lower_bound"], false);
  EXPECT_NE(found.err.find("error: ~"), std::string::npos) << found.err;
  EXPECT_EQ(readImageAttribute(out.string(), "penumbra:error.lower_bound"), "");
}

}  // namespace
}  // namespace penumbra::hard_gltf
