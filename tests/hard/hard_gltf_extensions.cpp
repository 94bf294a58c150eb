// glTF extensions said out loud: a required one penumbra cannot read is refused by
// name (JSON path, why, what penumbra reads), optional ones it leaves unread are named
// once in a note and in --stats, and a file that is not glTF at all says what it
// starts with. Every check is an exact substring or count: no tolerance applies.
#include "hard/hard_cli.h"
#include "hard/hard_gltf_support.h"
#include "support/gltf_build.h"

#include <algorithm>

namespace penumbra::hard_gltf {
namespace {

using hard::occurrences;
using hard::quote;
using hard::runCli;

// The model penumbra reads (a box), with `used` in extensionsUsed, written by tinygltf.
fs::path boxWithExtensions(const ScratchDir& dir, const std::string& name, const std::vector<std::string>& used) {
  tinygltf::Model m = testing::emptyGltf();
  const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  testing::addSceneNode(m, testing::addBoxMesh(m, lo, hi));
  m.extensionsUsed = used;
  const fs::path file = dir.path() / name;
  EXPECT_TRUE(testing::writeGltfFile(m, file.string(), name.size() > 4 && name.substr(name.size() - 4) == ".glb"));
  return file;
}

TEST(HardGltfExtensions, ARequiredExtensionPenumbraCannotReadIsRefusedByName) {
  const ScratchDir dir;
  const std::string reads = "it reads KHR_lights_punctual, KHR_materials_emissive_strength, KHR_materials_ior, "
                            "KHR_materials_transmission, KHR_materials_volume, KHR_texture_transform";
  const std::pair<const char*, const char*> cases[] = {
      {"KHR_draco_mesh_compression", "(Draco-compressed meshes; penumbra reads uncompressed accessors)"},
      {"EXT_meshopt_compression", "(meshopt-compressed buffers; penumbra reads uncompressed buffers)"},
      {"KHR_texture_basisu", "(KTX2 / Basis Universal textures; penumbra reads PNG and JPEG)"},
      {"ACME_sparkles", "requires ACME_sparkles, which penumbra does not support"}};
  for (const auto& [ext, why] : cases) {
    json j = triangle();
    // As in a Draco file: the compressed accessor has no bufferView, which tinygltf
    // would report first ("invalid bufferView") were the extension not checked before.
    j["accessors"][0].erase("bufferView");
    j["extensionsUsed"] = {"KHR_lights_punctual", ext};
    j["extensionsRequired"] = {"KHR_lights_punctual", ext};
    expectRefused(dir, j, {"model.gltf: extensionsRequired[1]: requires " + std::string(ext), why, reads});
  }
}

TEST(HardGltfExtensions, EveryCommandRefusesTheRequiredExtensionWithExitTwo) {
  const ScratchDir dir;
  json j = triangle();
  j["extensionsUsed"] = j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  const fs::path file = dir.write("draco.gltf", j.dump());
  const fs::path jobs = dir.write("jobs.json", R"({"jobs": [{"scene": "draco.gltf", "output": "o.png"}]})");
  for (const std::string& args : {"render " + quote(file.string()) + " -o " + quote((dir / "o.png").string()),
                                  "check " + quote(file.string()), "plan " + quote(file.string()),
                                  "batch " + quote(jobs.string()),
                                  "sweep " + quote(file.string()) + " --spp 1,2 -o " + quote((dir / "sw").string())}) {
    const hard::CliResult r = runCli(args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.err;
    EXPECT_EQ(occurrences(r.err, "\n"), 1u) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("extensionsRequired[0]: requires KHR_draco_mesh_compression"), std::string::npos) << r.err;
  }
}

TEST(HardGltfExtensions, ExtensionsPenumbraReadsMayBeRequired) {
  const ScratchDir dir;
  for (const char* ext : {"KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_ior",
                          "KHR_materials_transmission", "KHR_materials_volume", "KHR_texture_transform"}) {
    json j = triangle();
    j["extensionsUsed"] = j["extensionsRequired"] = {ext};
    EXPECT_EQ(refusal(dir.write("model.gltf", j.dump())), "") << ext;
  }
}

TEST(HardGltfExtensions, OptionalExtensionsLeftUnreadAreNamedOnceInOneNote) {
  const ScratchDir dir;
  const fs::path file = boxWithExtensions(
      dir, "model.glb",
      {"KHR_materials_clearcoat", "KHR_lights_punctual", "KHR_materials_sheen", "KHR_materials_clearcoat"});
  const Scene s = loadScene(file.string());
  EXPECT_EQ(s.load.ignoredExtensions, (std::vector<std::string>{"KHR_materials_clearcoat", "KHR_materials_sheen"}));
  const std::string line = file.string() + ": ignores KHR_materials_clearcoat, KHR_materials_sheen (optional)";
  EXPECT_EQ(std::count(s.load.notes.begin(), s.load.notes.end(), line), 1) << s.load.notes.size();
  for (const std::string& n : s.load.notes) EXPECT_TRUE(n == line || n.find("ignores") == std::string::npos) << n;

  // One model placed twice by a JSON scene: still one note.
  dir.write("two.json", R"({"lights": [{"type": "point", "position": [0, 3, 0]}],
    "objects": [{"type": "mesh", "file": "model.glb"}, {"type": "mesh", "file": "model.glb", "translate": [3, 0, 0]}]})");
  const Scene two = loadScene((dir / "two.json").string());
  size_t notes = 0;
  for (const std::string& n : two.load.notes) notes += n.find("ignores KHR_materials_clearcoat") != std::string::npos;
  EXPECT_EQ(notes, 1u);

  // Nothing left unread: no note.
  const Scene plain = loadScene(boxWithExtensions(dir, "plain.gltf", {"KHR_lights_punctual"}).string());
  EXPECT_TRUE(plain.load.ignoredExtensions.empty());
}

TEST(HardGltfExtensions, RenderWarnsOnceOnStderrAndListsThemInStats) {
  const ScratchDir dir;
  const fs::path file = boxWithExtensions(dir, "model.glb", {"KHR_materials_clearcoat", "KHR_materials_sheen"});
  const fs::path stats = dir / "stats.json";
  const hard::CliResult r = runCli("render " + quote(file.string()) + " -o " + quote((dir / "o.png").string()) +
                                   " --stats " + quote(stats.string()) +
                                   " -D camera.width=16 -D camera.height=12 -D camera.spp=1 -D photons.shadow=1000 -D photons.indirect=1000");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "note: " + file.string() + ": ignores KHR_materials_clearcoat, KHR_materials_sheen (optional)\n"), 1u)
      << r.err;
  EXPECT_EQ(occurrences(r.err, "ignores"), 1u) << r.err;
  const json j = json::parse(testing::readFile(stats));
  EXPECT_EQ(j["load"]["ignored_extensions"], json({"KHR_materials_clearcoat", "KHR_materials_sheen"}));
  EXPECT_EQ(j["load"]["defaults_added"], json({"camera", "sky"}));
  EXPECT_EQ(occurrences(j["notes"].dump(), "ignores"), 1u);
}

TEST(HardGltfExtensions, AFileThatIsNotGltfSaysWhatItStartsWith) {
  const ScratchDir dir;
  const std::pair<const char*, std::string> cases[] = {
      {"page.glb", "<!DOCTYPE html>\n<html><body>Download</body></html>"},
      {"image.gltf", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)},
      {"empty.glb", ""}};
  const std::string expected[] = {"page.glb: not a glTF file: starts with '<!DOCTYPE ht'...",
                                  "image.gltf: not a glTF file: starts with '\\x89PNG'...",
                                  "empty.glb: not a glTF file: is empty"};
  for (size_t i = 0; i < 3; ++i) {
    const fs::path file = dir.write(cases[i].first, cases[i].second);
    const std::string what = refusal(file);
    EXPECT_NE(what.find(expected[i]), std::string::npos) << what;
    const hard::CliResult r = runCli("check " + quote(file.string()));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find(expected[i]), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace penumbra::hard_gltf
