// Bad input is one clear line and exit 2, never an internal error: contradicting
// flags, options named in their own errors, binary or endless stdin, hostile OBJ and
// MTL numbers, side files too big to be what they claim, and huge quads.
#include "hard/hard_cli.h"
#include "io/image_io.h"
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

namespace penumbra {
namespace {

using namespace hard;

void expectBadInput(const CliResult& r, const std::string& says, const std::string& what) {
  EXPECT_EQ(r.exitCode, 2) << what << "\n" << r.err;
  EXPECT_NE(r.err.find(says), std::string::npos) << what << "\n" << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << what << "\n" << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << "\n" << r.err;
}

TEST(HardMessages, ContradictingGateFlagsAreRefusedByEveryCommand) {
  ScratchDir dir;
  const std::string scene = quote(dir.write("s.json", kFloorScene).string());
  const std::string out = quote((dir / "o").string());
  const std::pair<std::string, std::string> flags[] = {{"--no-gate --gate on", "--no-gate contradicts --gate on"},
                                                       {"--enable gate --no-gate", "contradicts --enable gate"},
                                                       {"--disable gate --gate on", "contradicts --disable gate"}};
  for (const auto& [f, says] : flags) {
    expectBadInput(runCli("render " + scene + " -q -o " + out + ".png " + f), says, "render " + f);
    expectBadInput(runCli("plan " + scene + " " + f), says, "plan " + f);
    expectBadInput(runCli("sweep " + scene + " --spp 1 -q -o " + out + " " + f), says, "sweep " + f);
    expectBadInput(runCli("batch " + scene + " -q -o " + out + " " + f), says, "batch " + f);
    expectBadInput(runCli("bench " + scene + " -q --repeat 1 --json " + out + ".json " + f), says, "bench " + f);
  }
  const CliResult plan = runCli("plan " + scene + " --gate off");
  EXPECT_EQ(plan.exitCode, 0) << plan.err;
  EXPECT_NE(plan.out.find("photons.gate is off"), std::string::npos) << plan.out;
}

TEST(HardMessages, EveryCommandRefusesASetValueThatIsNotUtf8) {
  ScratchDir dir;
  const std::string scene = quote(dir.write("s.json", kFloorScene).string());
  const std::string out = quote((dir / "o").string());
  const std::string latin1 = " --set 'name=\"caf\xe9\"'";  // Latin-1, not UTF-8
  for (const std::string& cmd : {"render " + scene + " -q -o " + out + ".png", "plan " + scene, "check " + scene,
                                 "sweep " + scene + " --spp 1 -q -o " + out, "batch " + scene + " -q -o " + out,
                                 "bench " + scene + " -q --repeat 1 --json " + out + ".json"}) {
    expectBadInput(runCli(cmd + latin1), "not valid UTF-8", cmd);
  }
}

TEST(HardMessages, EachOptionsErrorNamesThatOption) {
  ScratchDir dir;
  const std::string scene = quote(dir.write("s.json", kFloorScene).string());
  expectBadInput(runCli("batch " + scene + " -q -o " + quote((dir / "o").string()) + " --map-cache abc"),
                 "--map-cache: expected a size", "--map-cache abc");
  // An option of another command says whose it is.
  const CliResult r = runCli("plan " + scene + " --threads 2");
  expectBadInput(r, "--threads is an option of render, sweep, batch and bench", "plan --threads");
}

TEST(HardMessages, StatsDashGoesToStdout) {
  ScratchDir dir;
  const std::string scene = quote(dir.write("s.json", kFloorScene).string());
  const fs::path cwd = fs::current_path();
  fs::current_path(dir.path());
  const CliResult r = runCli("render " + scene + " -q -o " + quote((dir / "a.png").string()) + " --stats -");
  fs::current_path(cwd);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / "-"));
  EXPECT_NE(r.out.find("\"estimate\""), std::string::npos) << r.out.substr(0, 200);
}

TEST(HardMessages, BinaryStdinIsRefusedAtItsFirstBytesAndNeverEchoedRaw) {
  ScratchDir dir;
  const std::string bin = quote(PENUMBRA_BINARY);
  // 256 MB of NULs: refused at offset 0, long before the stream ends.
  const CliResult nul = runShell("head -c 268435456 /dev/zero | " + bin + " check -");
  expectBadInput(nul, "binary data, not a JSON scene (a NUL byte at offset 0)", "NULs on stdin");
  // Bytes the parser quotes back ("last read: ..."): shown escaped, never raw.
  dir.write("noise.bin", std::string("{\"a\": t\xff\xfe\x9b", 10));
  const CliResult noise = runShell("cat " + quote((dir / "noise.bin").string()) + " | " + bin + " check -");
  EXPECT_EQ(noise.exitCode, 2) << noise.err;
  for (unsigned char c : noise.err) EXPECT_TRUE(c == '\n' || (c >= 0x20 && c < 0x7f)) << int(c) << " in " << noise.err;
  EXPECT_NE(noise.err.find("\\xff"), std::string::npos) << noise.err;
}

TEST(HardMessages, DeeplyNestedSceneJsonIsBadInput) {
  ScratchDir dir;
  const std::string deep = "{\"render\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
  expectBadInput(runCli("check " + quote(dir.write("deep.json", deep).string())), "nested deeper than 64 levels",
                 "deep JSON");
}

// An OBJ floor with the given extra lines (and MTL text, when given).
std::string objScene(const ScratchDir& dir, const std::string& objExtra, const std::string& mtl = "") {
  dir.write("m.obj", "mtllib m.mtl\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\nvt 0 0\nusemtl a\nf 1 2 3 4\n" + objExtra);
  if (!mtl.empty()) dir.write("m.mtl", mtl);
  return quote(dir.write("s.json", R"({"camera": {"position": [0, 3, 3], "look_at": [0, 0, 0], "width": 16,
    "height": 12}, "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 5}],
    "objects": [{"type": "mesh", "file": "m.obj"}]})").string());
}

TEST(HardMessages, MtlAndObjNumbersOutOfRangeAreRefusedWithTheirLine) {
  const std::pair<std::string, std::string> mtls[] = {{"newmtl a\nd 1.5\n", "m.mtl:2: d \"1.5\""},
                                                      {"newmtl a\nTr -0.2\n", "m.mtl:2: Tr"},
                                                      {"newmtl a\nNs -3\n", "m.mtl:2: Ns"},
                                                      {"newmtl a\nNi 0\n", "m.mtl:2: Ni"},
                                                      {"newmtl a\nNi nan\n", "m.mtl:2: Ni"},
                                                      {"newmtl a\nKd inf 0 0\n", "m.mtl:2: Kd \"inf\""}};
  for (const auto& [mtl, says] : mtls) {
    ScratchDir dir;
    expectBadInput(runCli("check " + objScene(dir, "", mtl)), says, mtl);
  }
  ScratchDir dir;
  expectBadInput(runCli("check " + objScene(dir, "vt 3e38 0\n", "newmtl a\nKd 1 1 1\n")),
                 "texture coordinate 3e38 is beyond", "vt 3e38");
}

TEST(HardMessages, AnMtllibNotFoundIsRefusedSayingWhereItLooked) {
  ScratchDir dir;
  const std::string scene = objScene(dir, "");  // names m.mtl, which is not there
  expectBadInput(runCli("check " + scene), "mtllib 'm.mtl' not found (looked for " + (dir / "m.mtl").string(),
                 "missing MTL");
}

TEST(HardMessages, SideFilesTooBigForWhatTheyClaimAreRefusedBeforeReading) {
  ScratchDir dir;
  const std::string scene = objScene(dir, "", "newmtl a\nKd 1 1 1\n");
  // A 6 GB sparse MTL: its size alone refuses it.
  ASSERT_EQ(::truncate((dir / "m.mtl").c_str(), 6ll << 30), 0);
  expectBadInput(runCli("check " + scene), "is not a material library", "6 GB MTL");
  dir.write("m.mtl", "newmtl a\nKd 1 1 1\n");
  // 40k faces against a 1 MB budget: refused with the load estimate.
  std::string faces;
  for (int i = 0; i < 40000; ++i) faces += "f 1 2 3\n";
  const std::string big = objScene(dir, faces);
  expectBadInput(runCli("render " + big + " -q -o " + quote((dir / "a.png").string()) + " --max-memory 1M"),
                 "to load", "OBJ over --max-memory");
}

// A quad light over a floor, everything scaled by s: the image does not depend on s.
// At s = 1e10 the edges' float cross product squared (1.6e41) overflows, which used
// to refuse the light as "spanning no area" and drop the floor's triangles.
std::string scaledQuadScene(double s) {
  const auto v = [s](double x, double y, double z) { return fmt::format("[{:g}, {:g}, {:g}]", x * s, y * s, z * s); };
  return R"({"camera": {"position": )" + v(0, 3, 3) + R"(, "look_at": [0, 0, 0], "width": 16, "height": 12},
    "lights": [{"type": "quad", "corner": )" + v(-1, 2, -1) + R"(, "edge1": )" + v(2, 0, 0) + R"(, "edge2": )" +
         v(0, 0, 2) + R"(, "radiance": 1}],
    "objects": [{"type": "quad", "corner": )" + v(-200, 0, 200) + R"(, "edge1": )" + v(400, 0, 0) +
         R"(, "edge2": )" + v(0, 0, -400) + R"(}],
    "render": {"model": "physical", "light_samples": 1}, "photons": {"global": 0, "caustic": 0, "shadow": 0}})";
}

TEST(HardMessages, AQuadLightOfHugeEdgesRendersAsItsSmallCopy) {
  ScratchDir dir;
  double mean[2] = {0.0, 0.0};
  const double scales[2] = {1.0, 1e10};
  for (int i = 0; i < 2; ++i) {
    const std::string scene = quote(dir.write("s.json", scaledQuadScene(scales[i])).string());
    const CliResult r = runCli("render " + scene + " -q -o " + quote((dir / "a.exr").string()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image image = readImage((dir / "a.exr").string());
    for (const Color& c : image.pixels) mean[i] += c.g / static_cast<double>(image.pixels.size());
  }
  EXPECT_GT(mean[0], 0.01);
  EXPECT_NEAR(mean[1], mean[0], 1e-4 * mean[0]);
  // At 1e11 the floor's triangles are 4e13 long: Embree would miss most hits, so the
  // scene is refused rather than rendered black.
  const std::string larger = quote(dir.write("s.json", scaledQuadScene(1e11)).string());
  expectBadInput(runCli("check " + larger), "beyond 1e+13", "4e13 triangles");
}

}  // namespace
}  // namespace penumbra
