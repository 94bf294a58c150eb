// Validation of what the scene text and its files hold: duplicate JSON keys,
// OBJ fields that are not finite floats, and textures that do not decode, each
// refused at load with the file, the JSON path and the problem on one line.
#include "core/error.h"
#include "core/image.h"
#include "io/image_io.h"
#include "io/scene_loader.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

using namespace penumbra;
namespace fs = std::filesystem;

namespace {

// A scratch folder: the scene "v.json" is parsed as if it sat here, so the
// OBJ and image files written next to it resolve.
class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() / ("penumbra_validation_" + std::to_string(::getpid()));
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name, std::ios::binary) << text;
    return (path_ / name).string();
  }
  std::string scene() const { return (path_ / "v.json").string(); }

 private:
  fs::path path_;
};

std::string errorOf(const std::string& json, const std::string& file,
                    const std::vector<std::string>& overrides = {}) {
  try {
    parseScene(json, file, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expectRefused(const std::string& message, const std::string& prefix, const std::string& problem) {
  ASSERT_FALSE(message.empty()) << "loaded without error";
  EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
  EXPECT_NE(message.find(problem), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

std::string meshScene() {
  return R"({"objects": [{"type": "mesh", "file": "m.obj"}]})";
}

std::string textureScene(const std::string& file) {
  return R"({"materials": {"m": {"texture": {"file": ")" + file +
         R"("}}}, "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";
}

const char* kTriangle = "f 1 2 3\n";

}  // namespace

TEST(DuplicateKeys, AreRefusedWithTheirPath) {
  expectRefused(errorOf(R"({"camera": {"fov": 40, "width": 8, "fov": 50}})", "v.json"),
                "v.json: camera.fov: ", "duplicate key");
  expectRefused(errorOf(R"({"camera": {}, "camera": {}})", "v.json"), "v.json: camera: ",
                "duplicate key");
  // Inside an array, after nested containers: the index is counted right.
  expectRefused(errorOf(R"({"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1},
                                         {"type": "sphere", "center": [1, 0, 0], "radius": 1, "radius": 2}]})",
                        "v.json"),
                "v.json: objects[1].radius: ", "duplicate key");
  // The same key in different objects is not a duplicate.
  EXPECT_EQ(errorOf(R"({"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1},
                                    {"type": "sphere", "center": [3, 0, 0], "radius": 1}]})",
                    "v.json"),
            "");
  // Nor is a key repeated at another depth.
  EXPECT_EQ(errorOf(R"({"materials": {"m": {"transparent": {"tint": 1}, "tint": 0}}})", "v.json")
                .find("duplicate"),
            std::string::npos);
}

TEST(DuplicateKeys, InAnOverrideValueAreRefused) {
  const std::string message =
      errorOf("{}", "v.json", {R"(camera={"fov": 40, "fov": 50})"});
  expectRefused(message, "--set \"camera=", "fov: duplicate key in the value");
}

TEST(ObjValidation, NonFiniteFieldsNameTheObjFileAndLine) {
  TempDir dir;
  struct Case {
    std::string line, problem;
  };
  const std::vector<Case> cases = {
      {"v nan 0 0", ":2: vertex field \"nan\" is not a finite"},
      {"v 0 inf 0", ":2: vertex field \"inf\""},
      {"v 0 0 1e39", ":2: vertex field \"1e39\""},  // finite in double, not in float
      {"v 0 0 abc", ":2: vertex field \"abc\""},
      {"vn nan 0 1", ":2: normal field \"nan\""},
      {"vt inf 0", ":2: texture coordinate field \"inf\""},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.line);
    const std::string obj = dir.write("m.obj", "v 0 0 0\n" + c.line + "\nv 1 0 0\nv 0 1 0\n" +
                                                   "v 0 0 1\nvn 0 0 1\nvt 0 0\nf 3 4 5\n");
    expectRefused(errorOf(meshScene(), dir.scene()), dir.scene() + ": objects[0].file: OBJ file " + obj,
                  c.problem);
  }
}

TEST(ObjValidation, FiniteFieldsStillLoad) {
  TempDir dir;
  // Tiny values, signs, exponents, trailing comments and CRLF line ends are numbers.
  dir.write("m.obj", "v 1e-50 0 0 # tiny\r\nv +1.5 0 0\nv 0 .5e1 -0\nvn 0 0 1\nvt 0.5 1\n" +
                         std::string(kTriangle));
  Scene s = parseScene(meshScene(), dir.scene());
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_FLOAT_EQ(s.meshes[0].positions[2].y, 5.0f);
}

TEST(TextureValidation, TruncatedOrUnreadableImagesFailAtLoad) {
  TempDir dir;
  Image noise(64, 64);
  uint32_t state = 12345;
  for (Color& c : noise.pixels) {
    for (int k = 0; k < 3; ++k) {
      state = state * 1664525u + 1013904223u;
      c[k] = static_cast<float>(state >> 8) / 16777216.0f;
    }
  }
  const std::string good = (fs::path(dir.scene()).parent_path() / "good.png").string();
  writeImage(good, noise);
  EXPECT_NO_THROW(parseScene(textureScene("good.png"), dir.scene()));

  // The header survives, the pixel data stops halfway.
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 2000u);
  dir.write("cut.png", bytes.substr(0, bytes.size() / 2));
  expectRefused(errorOf(textureScene("cut.png"), dir.scene()),
                dir.scene() + ": materials.m.texture.file: texture ", "is truncated or corrupt");

  dir.write("text.png", "not an image at all\n");
  expectRefused(errorOf(textureScene("text.png"), dir.scene()),
                dir.scene() + ": materials.m.texture.file: cannot read texture ", "text.png");
}

TEST(TextureValidation, NonFiniteTexelsFailAtLoad) {
  TempDir dir;
  // Written through OIIO directly: writeImage replaces NaN with 0.
  std::vector<float> texels(8 * 4 * 3, 0.5f);
  texels[(2 * 8 + 3) * 3] = std::nanf("");
  const std::string path = (fs::path(dir.scene()).parent_path() / "nan.exr").string();
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(path, OIIO::ImageSpec(8, 4, 3, OIIO::TypeDesc::FLOAT)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, texels.data()));
  out->close();
  expectRefused(errorOf(textureScene("nan.exr"), dir.scene()),
                dir.scene() + ": materials.m.texture.file: texture ", "non-finite value in row 2");
}

TEST(TextureValidation, BuiltinNamesAndWidthsAreCheckedAtLoad) {
  expectRefused(errorOf(textureScene("builtin:chequer"), "v.json"),
                "v.json: materials.m.texture.file: ", "unknown builtin texture \"chequer\"");
  expectRefused(errorOf(textureScene("builtin:checker@1"), "v.json"),
                "v.json: materials.m.texture.file: ", "width must be an integer in [2, 16384]");
  Scene s = parseScene(textureScene("builtin:checker@64"), "v.json");
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].path, "builtin:checker@64");
}
