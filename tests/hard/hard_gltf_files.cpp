// Hard cases, class "glTF" (files): buffer and image URIs that leave the model's
// folder (../, absolute, percent-encoded, symlinks), directories, sparse giants
// and non-images are refused before anything is read whole; data: URIs still load.
#include "hard/hard_gltf_support.h"

#include <unistd.h>

using namespace penumbra;
using namespace penumbra::hard_gltf;

namespace {

// The triangle with its vertex data in an external buffer file `uri` (written as
// `bin` unless empty) and the folder `model/` holding the .gltf.
json externalTriangle(const std::string& uri) {
  json j = triangle();
  j["buffers"][0]["uri"] = uri;
  return j;
}

const std::string kBin = kVertexData + std::string("\0\1\2\0", 4);

// A minimal valid PNG signature and header; OpenImageIO is never reached here.
const std::string kPngMagic = std::string("\x89PNG\r\n\x1a\n", 8);

}  // namespace

TEST(HardGltfFiles, AnExternalBufferLoadsAndIsListed) {
  const ScratchDir dir;
  fs::create_directories(dir / "model");
  dir.write("model/tri.bin", kBin);
  dir.write("model/model.gltf", externalTriangle("tri.bin").dump());
  const LoadedModel m = loadModel((dir / "model/model.gltf").string());
  ASSERT_EQ(m.files.size(), 2u);
  EXPECT_EQ(fs::path(m.files[1]).filename(), "tri.bin");
  // Percent-encoding inside the folder is fine.
  dir.write("model/a b.bin", kBin);
  dir.write("model/model.gltf", externalTriangle("a%20b.bin").dump());
  EXPECT_EQ(refusal(dir / "model/model.gltf"), "");
}

// A downloaded model could pull any file of the machine into its render.
TEST(HardGltfFiles, UrisStayInsideTheModelsFolder) {
  const ScratchDir dir;
  fs::create_directories(dir / "model");
  dir.write("secret.bin", kBin);
  for (const std::string& uri : {std::string("../secret.bin"), std::string("%2e%2e/secret.bin"),
                                std::string("%2E%2E%2Fsecret.bin"), (dir / "secret.bin").string(),
                                std::string("file:///etc/passwd"), std::string("sub/../../secret.bin")}) {
    const fs::path file = dir.write("model/model.gltf", externalTriangle(uri).dump());
    const std::string what = refusal(file);
    EXPECT_NE(what.find("buffers[0].uri"), std::string::npos) << uri << ": " << what;
    EXPECT_NE(what.find(uri), std::string::npos) << uri << ": " << what;
  }
  // A symlink inside the folder that points out of it.
  fs::create_symlink(dir / "secret.bin", dir / "model/link.bin");
  const std::string what = refusal(dir.write("model/model.gltf", externalTriangle("link.bin").dump()));
  EXPECT_NE(what.find("outside the model's folder"), std::string::npos) << what;
  // Images too.
  dir.write("secret.png", kPngMagic + std::string(64, '\0'));
  json j = triangle();
  j["images"] = {{{"uri", "../secret.png"}}};
  const std::string image = refusal(dir.write("model/model.gltf", j.dump()));
  EXPECT_NE(image.find("images[0].uri"), std::string::npos) << image;
}

// Each external file is stat'ed first: a directory, a sparse giant behind a small
// byteLength and an oversized "image" were read whole before being judged.
TEST(HardGltfFiles, ExternalFilesAreJudgedBeforeTheyAreRead) {
  const ScratchDir dir;
  fs::create_directories(dir / "model/folder.bin");
  std::string what = refusal(dir.write("model/model.gltf", externalTriangle("folder.bin").dump()));
  EXPECT_NE(what.find("buffers[0].uri"), std::string::npos) << what;
  EXPECT_NE(what.find("not a regular file"), std::string::npos) << what;

  what = refusal(dir.write("model/model.gltf", externalTriangle("missing.bin").dump()));
  EXPECT_NE(what.find("does not exist"), std::string::npos) << what;

  const auto start = std::chrono::steady_clock::now();
  dir.write("model/huge.bin", kBin);
  fs::resize_file(dir / "model/huge.bin", 4ull << 30);  // sparse: no disk used
  what = refusal(dir.write("model/model.gltf", externalTriangle("huge.bin").dump()));
  EXPECT_NE(what.find("far more than byteLength 100"), std::string::npos) << what;

  dir.write("model/short.bin", kBin.substr(0, 50));
  what = refusal(dir.write("model/model.gltf", externalTriangle("short.bin").dump()));
  EXPECT_NE(what.find("fewer than byteLength 100"), std::string::npos) << what;

  dir.write("model/big.png", kPngMagic);
  fs::resize_file(dir / "model/big.png", 1ull << 30);
  json j = triangle();
  j["images"] = {{{"uri", "big.png"}}};
  what = refusal(dir.write("model/model.gltf", j.dump()));
  EXPECT_NE(what.find("images[0].uri"), std::string::npos) << what;
  EXPECT_NE(what.find("more than the"), std::string::npos) << what;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);

  // One image file named twice would be read twice: refused, as is a total beyond the budget.
  dir.write("model/small.png", kPngMagic + std::string(5000, '\0'));
  j["images"] = {{{"uri", "small.png"}}, {{"uri", "small.png"}}};
  what = refusal(dir.write("model/model.gltf", j.dump()));
  EXPECT_NE(what.find("images[1].uri: names the same file as images[0]"), std::string::npos) << what;
  dir.write("model/small2.png", kPngMagic + std::string(5000, '\0'));
  j["images"] = {{{"uri", "small.png"}}, {{"uri", "small2.png"}}};
  what = refusal(dir.write("model/model.gltf", j.dump()), LoadLimits{8000, "--max-memory"});
  EXPECT_NE(what.find("images[1].uri: buffers and images add up to 10116 bytes but --max-memory is 8000"),
            std::string::npos) << what;

  // Not a PNG or JPEG: refused by its magic number, never handed to the decoder.
  dir.write("model/text.png", "this is not an image");
  j["images"] = {{{"uri", "text.png"}}};
  what = refusal(dir.write("model/model.gltf", j.dump()));
  EXPECT_NE(what.find("not a PNG or JPEG"), std::string::npos) << what;
  j["images"] = {{{"uri", "data:image/png;base64," + base64("GIF89a not a png")}}};
  what = refusal(dir.write("model/model.gltf", j.dump()));
  EXPECT_NE(what.find("not a PNG or JPEG"), std::string::npos) << what;
}
