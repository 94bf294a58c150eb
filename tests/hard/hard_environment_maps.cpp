// Environment maps that lie: an 8-bit PNG named .exr, headers claiming more pixels
// than the file holds or rows wider than any decoder buffer, and an 8k map under a
// memory budget. Refused with one line before anything large is allocated (the
// process's peak RSS, from wait4, is the assertion), and counted in the estimate.
#include "core/lights/environment_map.h"
#include "hard/hard_cli.h"
#include "hard/hard_support.h"
#include "io/scene_loader.h"
#include "plan/job_admission.h"
#include "plan/render_plan.h"

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>

namespace penumbra {
namespace {

using namespace hard;

// A scene lit only by the environment map `map` (relative to the scene file), a
// 16 x 12 film at 1 spp: the cost of a render is the map's load.
std::string skyScene(const std::string& map) {
  const std::string environment = map.empty() ? R"({"color": [0.5, 0.6, 0.7]})" : R"({"map": ")" + map + R"("})";
  return R"({"camera": {"position": [0, 1, 3], "look_at": [0, 0, 0], "width": 16, "height": 12, "spp": 1},
  "environment": )" +
         environment + R"(,
  "objects": [{"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]}],
  "photons": {"shadow": 0, "indirect": 1000}})";
}

struct MeasuredRun {
  int exitCode = -1;
  std::string err;
  long peakKb = 0;  // the child's peak resident set (ru_maxrss)
};

// `penumbra render SCENE -q -o OUT EXTRA...` in a child of its own, its peak RSS from
// wait4 (that child only, unlike RUSAGE_CHILDREN); stdout to /dev/null.
MeasuredRun renderMeasured(const ScratchDir& dir, const std::string& scene, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {PENUMBRA_BINARY,           "render", (dir / scene).string(), "-q", "-o",
                                   (dir / "out.png").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string errPath = (dir / "stderr.txt").string();
  const pid_t child = fork();
  if (child == 0) {
    const int err = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int null = ::open("/dev/null", O_WRONLY);
    if (err >= 0) ::dup2(err, 2);
    if (null >= 0) ::dup2(null, 1);
    ::execv(PENUMBRA_BINARY, argv.data());
    _exit(127);
  }
  MeasuredRun r;
  int status = 0;
  struct rusage usage {};
  if (child > 0 && wait4(child, &status, 0, &usage) == child) {
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.peakKb = usage.ru_maxrss;
  }
  r.err = testing::readFile(errPath);
  return r;
}

void expectOneLineRefusal(const MeasuredRun& r, const std::string& scene, const std::string& what) {
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find(scene + ": environment.map: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
  EXPECT_EQ(occurrences(r.err, "\n"), 1u) << r.err;
}

void writeMap(const fs::path& path, const char* format, int width, int height, OIIO::TypeDesc type, float value) {
  auto out = OIIO::ImageOutput::create(format);
  ASSERT_TRUE(out) << format;
  OIIO::ImageSpec spec(width, height, 3, type);
  if (std::string(format) == "openexr") spec.attribute("compression", "zip");
  ASSERT_TRUE(out->open(path.string(), spec)) << out->geterror();
  const std::vector<float> row(size_t(width) * 3, value);
  for (int y = 0; y < height; ++y) ASSERT_TRUE(out->write_scanline(y, 0, OIIO::TypeDesc::FLOAT, row.data()));
  ASSERT_TRUE(out->close());
}

std::string le32(uint32_t v) { return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; }
std::string exrAttribute(const std::string& name, const std::string& type, const std::string& value) {
  return name + '\0' + type + '\0' + le32(uint32_t(value.size())) + value;
}

// The header of a scanline OpenEXR file of `width` x `height` half RGB pixels, its
// offset table and the first chunk's 8-byte prefix: no pixel data at all. compression:
// 0 none, 2 zips (one row a chunk), 3 zip (16 rows).
std::string exrClaiming(uint32_t width, uint32_t height, char compression) {
  std::string channels;
  for (const char* c : {"B", "G", "R"})
    channels += std::string(c) + '\0' + le32(1) + std::string(4, '\0') + le32(1) + le32(1);
  channels += '\0';
  const std::string box = le32(0) + le32(0) + le32(width - 1) + le32(height - 1);
  const float one = 1.0f;
  std::string oneBytes(4, '\0');
  std::memcpy(oneBytes.data(), &one, 4);
  std::string exr = std::string("\x76\x2f\x31\x01", 4) + le32(2) + exrAttribute("channels", "chlist", channels) +
                    exrAttribute("compression", "compression", std::string(1, compression)) +
                    exrAttribute("dataWindow", "box2i", box) + exrAttribute("displayWindow", "box2i", box) +
                    exrAttribute("lineOrder", "lineOrder", std::string(1, '\0')) +
                    exrAttribute("pixelAspectRatio", "float", oneBytes) +
                    exrAttribute("screenWindowCenter", "v2f", std::string(8, '\0')) +
                    exrAttribute("screenWindowWidth", "float", oneBytes) + '\0';
  const uint32_t rowsPerChunk = compression == 3 ? 16 : 1;
  const uint32_t chunks = (height + rowsPerChunk - 1) / rowsPerChunk;
  const uint64_t first = exr.size() + 8ull * chunks;
  exr += le32(uint32_t(first)) + le32(uint32_t(first >> 32)) + std::string(8 * (chunks - 1), '\0');
  return exr + le32(0) + le32(width * 6 * std::min(rowsPerChunk, height));
}

// A Radiance HDR header of `width` x `height` and `pixels` flat RGBE pixels after it.
std::string hdrClaiming(int width, int height, int pixels) {
  return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n" +
         std::string(size_t(pixels) * 4, '\x80');
}

// The reference for a refusal's peak: the render of a real 16 x 8 map, the same
// process but the map.
MeasuredRun smallMapRender(const ScratchDir& dir) {
  writeMap(dir / "small.exr", "openexr", 16, 8, OIIO::TypeDesc::HALF, 0.5f);
  dir.write("small.json", skyScene("small.exr"));
  return renderMeasured(dir, "small.json");
}

// What OIIO found decides, not the name: 8-bit display values are not radiance
// (today's loader read them as linear and rendered).
TEST(HardEnvironmentMaps, APngNamedExrIsRefusedAsNotHighDynamicRange) {
  ScratchDir dir;
  writeMap(dir / "sky.exr", "png", 8, 4, OIIO::TypeDesc::UINT8, 0.5f);
  dir.write("s.json", skyScene("sky.exr"));
  const MeasuredRun r = renderMeasured(dir, "s.json");
  expectOneLineRefusal(r, (dir / "s.json").string(), (dir / "sky.exr").string() + " is a png image of uint8 values");
}

// A header claiming 8192 x 4096 over a few bytes: the last row is read first,
// through a buffer of one row, so the refusal comes before the 512 MB the map would
// take: the peak is within 64 MB of a 16 x 8 map's render.
TEST(HardEnvironmentMaps, AHeaderThatLiesAboutItsSizeIsRefusedBeforeAllocating) {
  ScratchDir dir;
  const MeasuredRun reference = smallMapRender(dir);
  ASSERT_EQ(reference.exitCode, 0) << reference.err;
  dir.write("liar.hdr", hdrClaiming(8192, 4096, 64));
  dir.write("liar.exr", exrClaiming(8192, 4096, 3));
  for (const std::string map : {"liar.hdr", "liar.exr"}) {
    const std::string scene = dir.write(map + ".json", skyScene(map)).string();
    const MeasuredRun r = renderMeasured(dir, map + ".json");
    expectOneLineRefusal(r, scene, (dir / map).string() + " is truncated or corrupt: its header says 8192x4096");
    std::printf("%s: peak %ld KB (a 16 x 8 map's render: %ld KB)\n", map.c_str(), r.peakKb, reference.peakKb);
    EXPECT_LT(r.peakKb, reference.peakKb + 64 * 1024) << map;
  }
}

// OpenEXR 3.1 allocates what an attribute claims before reading it: 13 bytes of
// header claiming a 1.9 GB string made it allocate 2 GB (found by fuzz_environment_map),
// under any file name, as OIIO asks every reader when the name's refuses. The sizes
// are checked against the file first, for textures too (io/image_header openImage).
TEST(HardEnvironmentMaps, AnExrAttributeClaimingGigabytesIsRefusedUnallocated) {
  ScratchDir dir;
  const MeasuredRun reference = smallMapRender(dir);
  ASSERT_EQ(reference.exitCode, 0) << reference.err;
  dir.write("claim.exr", std::string("\x76\x2f\x31\x01", 4) + le32(2) + "comment" + '\0' + "string" + '\0' +
                             le32(1946157119) + "abc");
  const std::string scene = dir.write("claim.json", skyScene("claim.exr")).string();
  const MeasuredRun r = renderMeasured(dir, "claim.json");
  expectOneLineRefusal(r, scene,
                       (dir / "claim.exr").string() +
                           " is corrupt: an attribute of its OpenEXR header claims 1946157119 bytes");
  std::printf("claim.exr: peak %ld KB (a 16 x 8 map's render: %ld KB)\n", r.peakKb, reference.peakKb);
  EXPECT_LT(r.peakKb, reference.peakKb + 64 * 1024);
}

// A row wider than any decoder buffer: 33554432 x 1 is within the pixel count, but
// OpenEXR and the bands would allocate the row whole (today: std::bad_alloc, exit 1).
TEST(HardEnvironmentMaps, RowsWiderThanABufferAreRefusedByTheHeader) {
  ScratchDir dir;
  dir.write("none.exr", exrClaiming(33554432, 1, 0));
  dir.write("zips.exr", exrClaiming(33554432, 1, 2));
  dir.write("wide.hdr", hdrClaiming(33554432, 1, 4));
  for (const std::string map : {"none.exr", "zips.exr", "wide.hdr"}) {
    const std::string scene = dir.write(map + ".json", skyScene(map)).string();
    const MeasuredRun r = renderMeasured(dir, map + ".json");
    expectOneLineRefusal(r, scene, (dir / map).string() + " is 33554432x1 pixels: wider than the 16384");
  }
  // OpenEXR itself refuses a zip file of that width when it opens it (its chunk of 16
  // rows would pass 2 GB): one line naming the file, from the decoder.
  dir.write("zip.exr", exrClaiming(33554432, 1, 3));
  const std::string scene = dir.write("zip.json", skyScene("zip.exr")).string();
  expectOneLineRefusal(renderMeasured(dir, "zip.json"), scene, "cannot read " + (dir / "zip.exr").string());
}

// Textures share the header rule with a wider row: a 21600-wide lat-long earth (the
// common Blue Marble size) loads as a texture; a 33554432-wide strip is refused.
TEST(HardEnvironmentMaps, ATextureKeepsItsWiderRowBound) {
  ScratchDir dir;
  writeMap(dir / "earth.png", "png", 21600, 2, OIIO::TypeDesc::UINT8, 0.5f);
  dir.write("strip.exr", exrClaiming(33554432, 1, 0));
  for (const std::string texture : {"earth.png", "strip.exr"}) {
    dir.write(texture + ".json", R"({"camera": {"position": [0, 0, 3], "width": 8, "height": 6},
      "lights": [{"type": "point", "position": [0, 2, 2], "intensity": 5}],
      "materials": {"earth": {"diffuse": 0.8, "texture": {"file": ")" + texture + R"("}}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "earth"}]})");
    const CliResult r = runCli("check " + quote((dir / (texture + ".json")).string()));
    if (texture == "earth.png") {
      EXPECT_EQ(r.exitCode, 0) << r.err;
    } else {
      EXPECT_EQ(r.exitCode, 2) << r.err;
      EXPECT_NE(r.err.find("wider than the 65536"), std::string::npos) << r.err;
    }
  }
}

// The map and its sampling tables are scene memory in the estimate that admission
// and --stats use: exactly environmentMapBytes more than a constant sky.
TEST(HardEnvironmentMaps, TheEstimateCountsTheMap) {
  ScratchDir dir;
  writeMap(dir / "sky.exr", "openexr", 256, 128, OIIO::TypeDesc::HALF, 0.5f);
  const auto estimateOf = [&](const std::string& map) {
    const Scene scene = loadScene(dir.write("s.json", skyScene(map)).string());
    const RenderPlan plan = makePlan(scene, parseAov(scene.render.aov));
    return admitJob(scene, plan, 2, false, 0).estimate;
  };
  const ResourceEstimate constant = estimateOf(""), mapped = estimateOf("sky.exr");
  EXPECT_DOUBLE_EQ(environmentMapBytes(256, 128), 256.0 * 128 * 12 + (128.0 * 257 + 129) * 4);
  EXPECT_DOUBLE_EQ(mapped.sceneBytes - constant.sceneBytes, environmentMapBytes(256, 128));
  EXPECT_DOUBLE_EQ(mapped.totalBytes() - constant.totalBytes(), environmentMapBytes(256, 128));
}

// An 8192 x 4096 map needs 512 MB with its tables, beside the process's 140 MB: under
// --max-memory 600M it is refused at load, before decoding (today it loaded, peaking
// at 924 MB with the whole-image float buffer, and rendered). The peak stays within
// the budget either way.
TEST(HardEnvironmentMaps, An8kMapStaysWithinTheMemoryBudget) {
  ScratchDir dir;
  writeMap(dir / "sky8k.exr", "openexr", 8192, 4096, OIIO::TypeDesc::HALF, 0.5f);
  const std::string scene = dir.write("s.json", skyScene("sky8k.exr")).string();
  const MeasuredRun r = renderMeasured(dir, "s.json", {"--max-memory", "600M"});
  std::printf("8192x4096 under --max-memory 600M: exit %d, peak %ld KB\n", r.exitCode, r.peakKb);
  EXPECT_LE(r.peakKb, 600 * 1024) << r.err;
  expectOneLineRefusal(r, scene, "needs 512.0 MiB decoded with its sampling tables");
  EXPECT_NE(r.err.find("--max-memory"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace penumbra
