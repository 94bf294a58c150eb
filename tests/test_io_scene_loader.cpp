// Scene loader: a full scene parses into the expected values, defaults and
// overrides apply, and every malformed scene in tests/data/bad fails with a
// one-line, path-qualified message.
#include "core/error.h"
#include "core/image.h"
#include "io/image_io.h"
#include "io/scene_loader.h"

#include "support/parse_error.h"
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include <unistd.h>

using namespace penumbra;
namespace fs = std::filesystem;

namespace {

const std::string kSourceDir = PENUMBRA_SOURCE_DIR;

using penumbra::testing::errorOf;

// A scratch folder with a scene next to its texture, to check relative paths.
class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() / ("penumbra_io_" + std::to_string(::getpid()));
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name) << text;
    return path_ / name;
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

const char* kFullScene = R"({
  "name": "fig3_shadows",
  "camera": {"position": [0, 1, 6], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov": 40,
             "width": 320, "height": 200, "spp": 4},
  "lights": [
    {"type": "point", "position": [2, 5, 3], "color": [1, 0.9, 0.8], "intensity": 2.5},
    {"type": "directional", "direction": [0, -3, 4], "color": 0.5}
  ],
  "materials": {
    "red": {"ambient": 0.05, "diffuse": [0.8, 0.1, 0.1], "specular": 0.3, "shininess": 64},
    "mirror": {"reflective": {"kr": 0.9}},
    "planet": {"texture": {"file": "planet.png", "blend": "add"}},
    "planet2": {"texture": {"file": "./planet.png"}},
    "checker": {"texture": {"file": "builtin:checker"}}
  },
  "objects": [
    {"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "red"},
    {"type": "quad", "corner": [-5, 0, -5], "edge1": [0, 0, 10], "edge2": [10, 0, 0],
     "material": "checker"},
    {"type": "box", "min": [1, 0, 1], "max": [2, 1, 2], "material": "mirror"},
    {"type": "sphere", "center": [-2, 0.5, 0], "radius": 0.5, "material": "planet2"}
  ],
  "render": {"max_depth": 6, "background": [0.1, 0.2, 0.3], "ambient": 0.2,
             "seed": 18446744073709551615, "min_weight": 0.01, "shadows": false,
             "aov": "normal"},
  "photons": {"shadow": 2e6, "indirect": 100000, "k_shadow": 30, "k_indirect": 80,
              "max_radius": 0.25, "estimator": "density", "sampling": "cosine",
              "max_bounces": 8, "gate": false}
})";

}  // namespace

TEST(SceneLoader, FullSceneParsesIntoExpectedValues) {
  TempDir dir;
  // A real (tiny) image: textures are decoded at load time.
  writeImage((dir.path() / "planet.png").string(), Image(4, 2));
  fs::path file = dir.write("full.json", kFullScene);
  Scene s = loadScene(file.string());

  EXPECT_EQ(s.name, "fig3_shadows");
  EXPECT_EQ(s.file, file.string());
  EXPECT_EQ(s.camera.position, Vec3(0, 1, 6));
  EXPECT_EQ(s.camera.lookAt, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(s.camera.fovY, 40.0f);
  EXPECT_EQ(s.camera.width, 320);
  EXPECT_EQ(s.camera.height, 200);
  EXPECT_EQ(s.camera.spp, 4);

  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].type, LightType::Point);
  EXPECT_EQ(s.lights[0].position, Vec3(2, 5, 3));
  EXPECT_EQ(s.lights[0].color, Color(1, 0.9f, 0.8f));
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 2.5f);
  EXPECT_EQ(s.lights[1].type, LightType::Directional);
  EXPECT_NEAR(s.lights[1].direction.y, -0.6f, 1e-6f);  // normalised (0,-3,4)/5
  EXPECT_NEAR(s.lights[1].direction.z, 0.8f, 1e-6f);
  EXPECT_EQ(s.lights[1].color, Color(0.5f));
  EXPECT_FLOAT_EQ(s.lights[1].intensity, 1.0f);

  // Materials are ordered by name: checker, mirror, planet, planet2, red.
  ASSERT_EQ(s.materials.size(), 5u);
  std::map<std::string, const Material*> byName;
  for (const Material& m : s.materials) byName[m.name] = &m;
  const Material& red = *byName.at("red");
  EXPECT_EQ(red.ambient, Color(0.05f));
  EXPECT_EQ(red.diffuse, Color(0.8f, 0.1f, 0.1f));
  EXPECT_EQ(red.specular, Color(0.3f));
  EXPECT_FLOAT_EQ(red.shininess, 64.0f);
  EXPECT_EQ(red.texture, -1);
  EXPECT_FLOAT_EQ(byName.at("mirror")->kr, 0.9f);

  // Both spellings of planet.png resolve to one absolute texture; the builtin
  // is kept verbatim for the texture stage.
  ASSERT_EQ(s.textures.size(), 2u);
  const Material& planet = *byName.at("planet");
  EXPECT_EQ(planet.textureBlend, TextureBlend::Add);
  EXPECT_EQ(byName.at("planet2")->texture, planet.texture);
  EXPECT_EQ(byName.at("planet2")->textureBlend, TextureBlend::Multiply);
  EXPECT_EQ(fs::path(s.textures[planet.texture].path), (dir.path() / "planet.png").lexically_normal());
  EXPECT_TRUE(fs::path(s.textures[planet.texture].path).is_absolute());
  EXPECT_EQ(s.textures[byName.at("checker")->texture].path, "builtin:checker");

  ASSERT_EQ(s.spheres.size(), 2u);
  EXPECT_EQ(s.spheres[0].center, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(s.spheres[0].radius, 1.0f);
  EXPECT_EQ(s.materials[s.spheres[0].material].name, "red");
  EXPECT_EQ(s.materials[s.spheres[1].material].name, "planet2");
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].triangles.size(), 2u);
  EXPECT_EQ(s.materials[s.meshes[0].material].name, "checker");
  EXPECT_EQ(s.meshes[1].triangles.size(), 12u);
  EXPECT_EQ(s.materials[s.meshes[1].material].name, "mirror");

  EXPECT_EQ(s.render.maxDepth, 6);
  EXPECT_EQ(s.render.background, Color(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.render.ambient, Color(0.2f));
  EXPECT_EQ(s.render.seed, 18446744073709551615ull);
  EXPECT_FLOAT_EQ(s.render.minWeight, 0.01f);
  EXPECT_FALSE(s.render.shadows);
  EXPECT_EQ(s.render.aov, "normal");

  EXPECT_EQ(s.photons.shadowPhotons, 2'000'000u);
  EXPECT_EQ(s.photons.indirectPhotons, 100'000u);
  EXPECT_EQ(s.photons.kShadow, 30);
  EXPECT_EQ(s.photons.kIndirect, 80);
  EXPECT_FLOAT_EQ(s.photons.maxRadius, 0.25f);
  EXPECT_EQ(s.photons.estimator, IndirectEstimator::Density);
  EXPECT_EQ(s.photons.sampling, HemisphereSampling::Cosine);
  EXPECT_EQ(s.photons.maxBounces, 8);
  EXPECT_EQ(s.photons.gateMode, GateMode::Off);
}

TEST(SceneLoader, EmptySceneGetsDefaults) {
  Scene s = parseScene("{}", "scenes/empty_room.json");
  Scene d;
  EXPECT_EQ(s.name, "empty_room");
  EXPECT_EQ(s.file, "scenes/empty_room.json");
  EXPECT_EQ(s.camera.position, d.camera.position);
  EXPECT_FLOAT_EQ(s.camera.fovY, 45.0f);
  EXPECT_EQ(s.camera.width, 640);
  EXPECT_EQ(s.camera.height, 480);
  EXPECT_EQ(s.render.maxDepth, 4);
  EXPECT_EQ(s.render.seed, 1u);
  EXPECT_TRUE(s.render.shadows);
  EXPECT_EQ(s.render.aov, "beauty");
  EXPECT_EQ(s.photons.shadowPhotons, 5'000'000u);
  EXPECT_EQ(s.photons.estimator, IndirectEstimator::Classic);
  EXPECT_EQ(s.photons.gateMode, GateMode::Auto);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "default");
  EXPECT_EQ(s.materials[0].diffuse, Material().diffuse);
  EXPECT_TRUE(s.lights.empty());
  EXPECT_TRUE(s.spheres.empty());
}

TEST(SceneLoader, ObjectsWithoutMaterialsSectionUseTheDefault) {
  Scene s = parseScene(
      R"({"objects": [{"type": "sphere", "center": [0,0,0], "radius": 2},
                      {"type": "sphere", "center": [0,0,0], "radius": 1, "material": "default"}]})",
      "x.json");
  ASSERT_EQ(s.spheres.size(), 2u);
  EXPECT_EQ(s.spheres[0].material, 0);
  EXPECT_EQ(s.spheres[1].material, 0);
}

TEST(SceneLoader, PhotonProbabilityDefaults) {
  Scene s = parseScene(R"({"materials": {
      "matte": {},
      "mirror": {"reflective": {"kr": 0.7}},
      "glass": {"transparent": {"ior": 1.33, "tint": [1, 0.5, 0]}},
      "coated": {"reflective": {"kr": 0.2}, "transparent": {}},
      "explicit": {"reflective": {"kr": 0.9}, "p_r": 0.3, "p_t": 0.4},
      "bright": {"transparent": {"tint": 3}},
      "edge": {"p_r": 0.5, "p_t": 0.5000001}}})",
                       "x.json");
  std::map<std::string, Material> m;
  for (const Material& mat : s.materials) m[mat.name] = mat;
  EXPECT_FLOAT_EQ(m["matte"].pR, 0.0f);
  EXPECT_FLOAT_EQ(m["matte"].pT, 0.0f);
  EXPECT_FALSE(m["matte"].transparent);
  EXPECT_FLOAT_EQ(m["mirror"].pR, 0.7f);
  EXPECT_FLOAT_EQ(m["mirror"].pT, 0.0f);
  EXPECT_TRUE(m["glass"].transparent);
  EXPECT_FLOAT_EQ(m["glass"].ior, 1.33f);
  EXPECT_EQ(m["glass"].tint, Color(1, 0.5f, 0));
  EXPECT_FLOAT_EQ(m["glass"].pR, 0.0f);
  EXPECT_FLOAT_EQ(m["glass"].pT, 0.5f);  // (1 - 0) * mean(1, 0.5, 0)
  EXPECT_FLOAT_EQ(m["coated"].kr, 0.2f);
  EXPECT_FLOAT_EQ(m["coated"].ior, 1.5f);
  EXPECT_FLOAT_EQ(m["coated"].pR, 0.2f);
  EXPECT_FLOAT_EQ(m["coated"].pT, 0.8f);  // (1 - 0.2) * 1
  EXPECT_FLOAT_EQ(m["explicit"].kr, 0.9f);
  EXPECT_FLOAT_EQ(m["explicit"].pR, 0.3f);
  EXPECT_FLOAT_EQ(m["explicit"].pT, 0.4f);
  EXPECT_FLOAT_EQ(m["bright"].pT, 1.0f);  // a tint above 1 is clamped to 1 - p_r
  EXPECT_FLOAT_EQ(m["edge"].pT, 0.5000001f);  // within the 1e-6 tolerance
}

TEST(SceneLoader, OverridesChangeValues) {
  const char* scene = R"({"objects": [{"type": "sphere", "center": [0,0,0], "radius": 1},
                                      {"type": "sphere", "center": [0,0,0], "radius": 1}]})";
  Scene s = parseScene(scene, "x.json",
                       {"render.max_depth=8", "photons.estimator=density", "objects[1].radius=3",
                        "camera.position=[1, 2, 3]", "name=\"with space\"", "photons.gate=false",
                        "render.max_depth=9"});
  EXPECT_EQ(s.render.maxDepth, 9);  // later overrides win
  EXPECT_EQ(s.photons.estimator, IndirectEstimator::Density);
  EXPECT_FLOAT_EQ(s.spheres[0].radius, 1.0f);
  EXPECT_FLOAT_EQ(s.spheres[1].radius, 3.0f);
  EXPECT_EQ(s.camera.position, Vec3(1, 2, 3));
  EXPECT_EQ(s.name, "with space");
  EXPECT_EQ(s.photons.gateMode, GateMode::Off);
}

TEST(SceneLoader, BadOverridesAreInputErrors) {
  const char* scene = R"({"objects": [{"type": "sphere", "center": [0,0,0], "radius": 1}]})";
  EXPECT_EQ(errorOf(scene, {"render.max_depth"}), "--set \"render.max_depth\": expected KEY=VALUE");
  EXPECT_NE(errorOf(scene, {"=3"}).find("--set \"=3\": empty key"), std::string::npos);
  EXPECT_NE(errorOf(scene, {"render..seed=3"}).find("--set \"render..seed=3\": expected a key"),
            std::string::npos);
  EXPECT_NE(errorOf(scene, {"objects[4].radius=2"}).find("index 4 is out of range (objects has 1"),
            std::string::npos);
  EXPECT_NE(errorOf(scene, {"objects[x].radius=2"}).find("expected [INDEX]"), std::string::npos);
  EXPECT_NE(errorOf(scene, {"render[0]=2"}).find("render is not an array"), std::string::npos);
  EXPECT_NE(errorOf(scene, {"objects[0].radius.x=2"}).find("objects[0].radius is not an object"),
            std::string::npos);
  // Overridden values are validated like the file's own, and say where they came from.
  EXPECT_EQ(errorOf(scene, {"render.max_depth=100"}),
            "x.json: render.max_depth: must be between 0 and 64, got 100 (value from --set)");
  EXPECT_EQ(errorOf(scene, {"photons.estimator=densty"}),
            "x.json: photons.estimator: unknown value \"densty\" (did you mean \"density\"?) "
            "(value from --set)");
  EXPECT_EQ(errorOf(scene, {"camera.fvo=30"}),
            "x.json: camera.fvo: unknown key (did you mean \"fov\"?) (value from --set)");
}

TEST(SceneLoader, MissingFileAndHostileInputs) {
  try {
    loadScene("no/such/scene.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "no/such/scene.json: cannot open scene file: does not exist");
  }
  EXPECT_THROW(loadScene(kSourceDir + "/tests/data"), InputError);  // a folder

  // Deep nesting and huge arrays where objects are expected: errors, not crashes.
  std::string deep = "{\"render\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
  EXPECT_EQ(errorOf(deep), "x.json: render[0][0][0][0][0][0][0][0][0][0][0][...: nested deeper than 64 levels");
  std::string manyLights = "{\"lights\": [";
  for (int i = 0; i < 100000; ++i) manyLights += "1,";
  manyLights += "1]}";
  EXPECT_EQ(errorOf(manyLights), "x.json: lights: at most 65535 lights, got 100001");
  EXPECT_NE(errorOf("{\"camera\": {\"" + std::string(100000, 'k') + "\": 1}}").find("unknown key"),
            std::string::npos);
  EXPECT_EQ(errorOf("{\"name\": \"a\\nb\", \"x\\ny\": 1}"), "x.json: [\"x?y\"]: unknown key");
}

// Every file in tests/data/bad must fail with a message containing its expected
// substring, start with the file name, and stay on one line.
TEST(SceneLoader, MalformedScenesFailWithPreciseMessages) {
  const std::map<std::string, std::string> expected = {
      {"syntax_error.json", "syntax_error.json:3:15: JSON syntax error: syntax error while parsing object key"},
      {"empty_file.json", "empty_file.json:1:1: JSON syntax error:"},
      {"unknown_key.json", ": camera.fvo: unknown key (did you mean \"fov\"?)"},
      {"unknown_top_key.json", ": cmaera: unknown key (did you mean \"camera\"?)"},
      {"negative_radius.json", ": objects[1].radius: must be > 0, got -1"},
      {"unknown_material.json",
       ": objects[0].material: unknown material \"rde\" (did you mean \"red\"?)"},
      {"missing_material.json", ": objects[0]: missing required key \"material\""},
      {"pr_pt_sum.json", ": materials.glass: p_r + p_t must be <= 1, got 0.6 + 0.5 = 1.1"},
      {"number_overflow.json", "number_overflow.json:2:28: JSON number error: number overflow"},
      {"float_overflow.json", ": objects[0].center[1]: is too large for single precision"},
      {"wrong_type.json", ": camera.fov: must be a number, got \"wide\""},
      {"wrong_bool.json", ": photons.gate: must be true, false, \"on\", \"off\" or \"auto\", got 1"},
      {"missing_required.json", ": objects[0]: missing required key \"radius\" for a sphere"},
      {"missing_light_position.json",
       ": lights[0]: missing required key \"position\" for a point light"},
      {"colour_arity.json",
       ": materials.red.diffuse: must be a colour [r, g, b] or a grey number, got an array of 2"},
      {"negative_colour.json", ": render.background[1]: must be >= 0, got -0.5"},
      {"zero_direction.json", ": lights[0].direction: must be a non-zero vector"},
      {"degenerate_camera.json", ": camera.look_at: look_at equals position"},
      {"up_parallel.json", ": camera.up: up is parallel to the view direction"},
      {"missing_mesh_file.json", ": objects[0].file: cannot open OBJ file "},
      {"mesh_without_triangles.json", "empty.obj contains no triangles"},
      {"non_integer_width.json", ": camera.width: must be an integer, got 640.5"},
      {"bad_enum.json", ": photons.estimator: unknown value \"densty\" (did you mean \"density\"?)"},
      {"unknown_object_type.json",
       ": objects[0].type: unknown value \"sphre\" (did you mean \"sphere\"?)"},
      {"root_array.json", ": (root): a scene must be a JSON object, got an array of 1"},
      {"root_null.json", ": (root): a scene must be a JSON object, got null"},
      {"box_min_max.json", ": objects[0].max: must be greater than min on every axis"},
      {"max_depth_range.json", ": render.max_depth: must be between 0 and 64, got 65"},
      {"negative_seed.json", ": render.seed: must be between 0 and 18446744073709551615, got -1"},
      {"missing_texture.json", ": materials.planet.texture.file: texture file "},
      {"parallel_quad_edges.json", ": objects[0].edge2: edge1 and edge2 must be non-zero and not"},
      {"zero_scale.json", ": objects[0].scale: must be non-zero on every axis"},
      {"fov_range.json", ": camera.fov: must be > 0 and < 180, got 180"},
      {"spp_range.json", ": camera.spp: must be between 1 and 4096, got 0"},
      {"vector_arity.json", ": camera.position: must be an array of 3 numbers [x, y, z]"},
      {"sphere_with_rotate.json", ": objects[0].rotate: unknown key"},
      {"teapot_subdivisions.json", ": objects[0].subdivisions: must be between 1 and 128, got 0"},
      {"null_value.json", ": camera.position: must be an array of 3 numbers [x, y, z], got null"},
      {"photon_count.json", ": photons.shadow: must be between 0 and 1000000000, got 1e+12"},
      {"bad_aov.json", ": render.aov: unknown value \"normals\" (did you mean \"normal\"?)"},
      {"reflective_kr_range.json", ": materials.mirror.reflective.kr: must be between 0 and 1"},
  };
  const fs::path dir = fs::path(kSourceDir) / "tests/data/bad";
  size_t seen = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    auto it = expected.find(name);
    ASSERT_NE(it, expected.end()) << "no expected message for " << name;
    ++seen;
    std::string message;
    try {
      loadScene(entry.path().string());
    } catch (const InputError& e) {
      message = e.what();
    }
    ASSERT_FALSE(message.empty()) << "loaded without error";
    EXPECT_NE(message.find(it->second), std::string::npos) << message;
    EXPECT_EQ(message.rfind(entry.path().string(), 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_EQ(seen, expected.size());
  EXPECT_GE(seen, 15u);
}
