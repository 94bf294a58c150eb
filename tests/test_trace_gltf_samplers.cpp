// glTF samplers end to end: a glTF file with three quads whose uvs run over u in
// [-1, 0] and v in [1, 2] (as the DamagedHelmet's v does), one texture each over the
// same 4 x 4 PNG with a REPEAT, MIRRORED_REPEAT or CLAMP_TO_EDGE sampler (nearest
// texels), loaded by the scene loader and shot at each texel's centre; the ray's
// --trace-pixel record gives the uv and the base colour the lookup read. The repeat
// quad also carries a constant normal map and metallic-roughness map, whose tilt and
// factors the record must show.
#include "core/color.h"
#include "core/error.h"
#include "io/scene_loader.h"
#include "support/gltf_build.h"
#include "support/render_fixtures.h"
#include "support/scratch_dir.h"
#include "trace/texture_lookup.h"
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
constexpr int kSide = 4;

// Texel (x, y) of grid.png: red 85 x, green 85 y (8-bit sRGB), row 0 at the top.
Color texel(int x, int y) {
  return Color(float(srgbDecode(85.0 * x / 255.0)), float(srgbDecode(85.0 * y / 255.0)), 0.0f);
}

void writePng(const fs::path& path, int side, const std::function<void(int, int, float*)>& rgb) {
  OIIO::ImageBuf buf(OIIO::ImageSpec(side, side, 3, OIIO::TypeDesc::UINT8));
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      float v[3];
      rgb(x, y, v);
      buf.setpixel(x, y, v);
    }
  }
  ASSERT_TRUE(buf.write(path.string())) << buf.geterror();
}

// Quad k spans x in [3k, 3k + 1], y in [0, 1] at z = 0 facing +z; u = x - 3k - 1,
// v = 2 - y (the image's top row at the top).
void addQuad(tinygltf::Model& m, int k, int material) {
  const float x0 = 3.0f * float(k);
  const int mesh = testing::addTriangleMesh(m, {x0, 0, 0, x0 + 1, 0, 0, x0 + 1, 1, 0, x0, 1, 0},
                                            {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1},
                                            {-1, 2, 0, 2, 0, 1, -1, 1}, {0, 1, 2, 0, 2, 3}, material);
  testing::addSceneNode(m, mesh);
}

int addTexture(tinygltf::Model& m, int image, int wrap) {
  tinygltf::Sampler s;
  s.wrapS = s.wrapT = wrap;
  s.magFilter = TINYGLTF_TEXTURE_FILTER_NEAREST;
  s.minFilter = TINYGLTF_TEXTURE_FILTER_NEAREST;
  m.samplers.push_back(s);
  tinygltf::Texture t;
  t.source = image;
  t.sampler = int(m.samplers.size()) - 1;
  m.textures.push_back(t);
  return int(m.textures.size()) - 1;
}

// 8-bit normal-map red 218 with blue 255: the map's normal leans by atan(2 x 218 / 255 - 1).
constexpr float kMapRed = 218.0f / 255.0f;

struct SamplerScene {
  testing::ScratchDir scratch;
  Scene scene;
  tinygltf::Model model;
  SamplerScene() {
    const fs::path& dir = scratch.path();
    writePng(dir / "grid.png", kSide, [](int x, int y, float* v) {
      v[0] = 85.0f * float(x) / 255.0f, v[1] = 85.0f * float(y) / 255.0f, v[2] = 0.0f;
    });
    writePng(dir / "normal.png", 2, [](int, int, float* v) { v[0] = kMapRed, v[1] = 128.0f / 255.0f, v[2] = 1.0f; });
    writePng(dir / "mr.png", 2, [](int, int, float* v) { v[0] = 0.0f, v[1] = 51.0f / 255.0f, v[2] = 1.0f; });
    tinygltf::Model m = testing::emptyGltf();
    for (const char* uri : {"grid.png", "normal.png", "mr.png"}) {
      tinygltf::Image image;
      image.uri = uri;
      m.images.push_back(image);
    }
    const int wraps[3] = {TINYGLTF_TEXTURE_WRAP_REPEAT, TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT,
                          TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE};
    const char* names[3] = {"repeat", "mirror", "clamp"};
    for (int k = 0; k < 3; ++k) {
      tinygltf::Material mat;
      mat.name = names[k];
      mat.pbrMetallicRoughness.baseColorTexture.index = addTexture(m, 0, wraps[k]);
      if (k == 0) {
        mat.normalTexture.index = addTexture(m, 1, TINYGLTF_TEXTURE_WRAP_REPEAT);
        mat.pbrMetallicRoughness.metallicRoughnessTexture.index = addTexture(m, 2, TINYGLTF_TEXTURE_WRAP_REPEAT);
        mat.pbrMetallicRoughness.metallicFactor = 0.5;
        mat.pbrMetallicRoughness.roughnessFactor = 1.0;
      }
      m.materials.push_back(mat);
      addQuad(m, k, k);
    }
    EXPECT_TRUE(testing::writeGltfFile(m, (dir / "quads.gltf").string(), false));
    scene = loadScene((dir / "quads.gltf").string());
    model = m;
  }
};

class GltfSamplers : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = new SamplerScene();
    std::vector<std::string> paths;
    std::vector<bool> data;
    std::vector<std::optional<TextureSampling>> samplers;
    for (const Texture& t : model_->scene.textures) {
      paths.push_back(t.path);
      data.push_back(t.data);
      samplers.push_back(t.sampler);
    }
    lookup_ = new TextureLookup(paths, data, samplers);
  }
  static void TearDownTestSuite() {
    delete lookup_;
    delete model_;
  }
  // The record of a camera-like ray straight down -z onto (x, y).
  static RayRecord shoot(float x, float y) {
    Rig rig(model_->scene);
    rig.ctx.textures = lookup_;
    RayTree tree;
    rig.shade(Ray{Vec3(x, y, 5.0f), Vec3(0.0f, 0.0f, -1.0f)}, &tree);
    EXPECT_FALSE(tree.empty());
    return tree.empty() ? RayRecord{} : tree[0];
  }
  static const Material& material(const std::string& name) {
    for (const Material& m : model_->scene.materials) {
      if (m.name == "quads.gltf:" + name) return m;
    }
    ADD_FAILURE() << "no material " << name;
    return model_->scene.materials[0];
  }
  static inline SamplerScene* model_ = nullptr;
  static inline TextureLookup* lookup_ = nullptr;
};

TEST_F(GltfSamplers, TheLoaderKeepsEachTexturesSampler) {
  const Scene& s = model_->scene;
  const TextureWrap want[3] = {TextureWrap::Repeat, TextureWrap::MirroredRepeat, TextureWrap::ClampToEdge};
  const char* names[3] = {"repeat", "mirror", "clamp"};
  for (int k = 0; k < 3; ++k) {
    const Material& m = material(names[k]);
    ASSERT_GE(m.texture, 0) << names[k];
    const std::optional<TextureSampling>& how = s.textures[size_t(m.texture)].sampler;
    ASSERT_TRUE(how.has_value()) << names[k];
    EXPECT_EQ(how->wrapS, want[k]) << names[k];
    EXPECT_EQ(how->wrapT, want[k]) << names[k];
    EXPECT_EQ(how->texels, TexelFilter::Nearest);
    EXPECT_EQ(how->mips, MipFilter::None);
  }
}

// u in [-1, 0], v in [1, 2]: repeat reads texel (c, r), mirrored repeat (3 - c, 3 - r),
// clamp the bottom-left texel (0, 3) everywhere.
TEST_F(GltfSamplers, EachQuadReadsTheTexelItsSamplerGives) {
  const char* names[3] = {"repeat", "mirror", "clamp"};
  for (int k = 0; k < 3; ++k) {
    const Color factor = material(names[k]).diffuse;
    for (int c = 0; c < kSide; ++c) {
      for (int r = 0; r < kSide; ++r) {
        const float fu = (float(c) + 0.5f) / kSide, fv = (float(r) + 0.5f) / kSide;
        const RayRecord rec = shoot(3.0f * float(k) + fu, 1.0f - fv);
        const std::string where = std::string(names[k]) + " texel " + std::to_string(c) + "," + std::to_string(r);
        ASSERT_TRUE(rec.hit && rec.shaded && rec.hasUv) << where;
        EXPECT_NEAR(rec.uv.x, fu - 1.0f, 1e-5f) << where;
        EXPECT_NEAR(rec.uv.y, fv + 1.0f, 1e-5f) << where;
        const Color want = k == 0 ? texel(c, r) : k == 1 ? texel(kSide - 1 - c, kSide - 1 - r) : texel(0, kSide - 1);
        for (int ch = 0; ch < 2; ++ch) EXPECT_NEAR(rec.baseColor[ch], factor[ch] * want[ch], 2e-3f) << where;
      }
    }
  }
}

// The record shows the evaluated material: metallic 0.5 x 1 (blue), roughness
// 1 x 0.2 (green), and the normal map's tilt, atan(2 x 218 / 255 - 1) from the
// interpolated normal (+z here), with the shading normal still facing the ray.
TEST_F(GltfSamplers, TheTraceRecordShowsTheEvaluatedMaterialAndTheMapsTilt) {
  const RayRecord rec = shoot(0.4f, 0.6f);
  ASSERT_TRUE(rec.shaded);
  EXPECT_TRUE(rec.metalRough);
  EXPECT_NEAR(rec.metallic, 0.5f, 3e-3f);
  EXPECT_NEAR(rec.roughness, 0.2f, 3e-3f);
  EXPECT_NEAR(rec.interpolatedNormal.z, 1.0f, 1e-5f);
  EXPECT_NEAR(rec.geometricNormal.z, 1.0f, 1e-5f);
  const float lean = 2.0f * kMapRed - 1.0f;
  EXPECT_NEAR(normalTiltDegrees(rec), glm::degrees(std::atan(lean)), 0.3f);
  EXPECT_NEAR(rec.shadingNormal.z, 1.0f / std::sqrt(1.0f + lean * lean), 5e-3f);
  // The clamp quad has no normal map: no tilt.
  EXPECT_NEAR(normalTiltDegrees(shoot(6.5f, 0.5f)), 0.0f, 1e-3f);
}

// A wrap value the spec does not have, or a sampler that does not exist, is refused
// naming the JSON path.
TEST_F(GltfSamplers, ASamplerOutsideTheSpecIsRefusedNamingItsPath) {
  auto refusal = [](const tinygltf::Model& m) -> std::string {
    const fs::path file = model_->scratch.path() / "bad.gltf";
    EXPECT_TRUE(testing::writeGltfFile(m, file.string(), false));
    try {
      loadScene(file.string());
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  tinygltf::Model m = model_->model;
  m.samplers[1].wrapT = 10496;
  EXPECT_NE(refusal(m).find("samplers[1].wrapT: 10496 is not 10497 (REPEAT)"), std::string::npos) << refusal(m);
  m = model_->model;
  m.textures[2].sampler = 9;
  EXPECT_NE(refusal(m).find("textures[2].sampler: 9 does not exist"), std::string::npos) << refusal(m);
}

}  // namespace
}  // namespace penumbra
