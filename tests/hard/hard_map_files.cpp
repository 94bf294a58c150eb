// Photon map files through the binary (--map-dir): a render writes its stage's file and
// the next loads it, with the image byte-identical to a render without files at any
// thread count; a damaged, truncated or swapped file is never used (emitted again and
// rewritten, with one note saying why); a sweep writes and loads them too.
#include "hard/hard_cli.h"
#include "io/image_io.h"
#include "plan/render_session.h"
#include "support/scoped_env.h"
#include <gtest/gtest.h>
#include <cstring>
#include <fstream>
#include <vector>

namespace penumbra::hard {
namespace {

using testing::readFile;

// Shipped scenes at reduced size: the physical model with two progressive passes
// (pass 1's photons are fresh, only pass 0's are stored) and the classic gate.
struct SceneCase {
  const char* file;
  const char* settings;
};
const SceneCase kPhysical{"cornell_physical.json",
                          "-D camera.width=32 -D camera.height=24 -D photons.global=20000 -D photons.caustic=20000 "
                          "-D photons.passes=2"};
const SceneCase kGated{"fig11_gate_shadows.json", "-D camera.width=32 -D camera.height=24 -D photons.shadow=100000"};

std::string shipped(const char* file) { return std::string(PENUMBRA_SOURCE_DIR) + "/scenes/" + file; }

// An EXR's pixels as bytes (its header carries the time it was written).
std::string pixelsOf(const fs::path& exr) {
  const Image image = readImage(exr.string());
  std::string bytes(image.pixels.size() * sizeof(Color), '\0');
  if (!bytes.empty()) std::memcpy(bytes.data(), image.pixels.data(), bytes.size());
  return bytes;
}

std::vector<fs::path> mapFiles(const fs::path& dir) {
  std::vector<fs::path> files;
  if (!fs::exists(dir)) return files;
  for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
  return files;
}

class MapFiles : public ::testing::Test {
 protected:
  // Renders `c` to OUT (a PNG in the scratch folder) with `args`; returns the run.
  CliResult render(const SceneCase& c, const std::string& out, const std::string& args = "") const {
    return runCli("render " + quote(shipped(c.file)) + " " + c.settings + " -o " + quote((dir_ / out).string()) + " " +
                  args);
  }
  std::string image(const std::string& out) const { return readFile(dir_ / out); }
  std::string maps(const std::string& name = "maps") const { return quote((dir_ / name).string()); }
  fs::path mapDir(const std::string& name = "maps") const { return dir_ / name; }

  testing::ScratchDir dir_;
};

// The one map file in `dir`, after a render wrote it.
fs::path onlyFile(const fs::path& dir) {
  const std::vector<fs::path> files = mapFiles(dir);
  EXPECT_EQ(files.size(), 1u);
  return files.empty() ? fs::path() : files.front();
}

TEST_F(MapFiles, SecondRenderLoadsTheMapsAndWritesTheSameImage) {
  for (const SceneCase& c : {kPhysical, kGated}) {
    SCOPED_TRACE(c.file);
    fs::remove_all(mapDir());
    ASSERT_EQ(render(c, "ref.png", "-t 2").exitCode, 0);
    const CliResult first = render(c, "first.png", "-t 2 --map-dir " + maps() + " --stats " + quote((dir_ / "s.json").string()));
    ASSERT_EQ(first.exitCode, 0) << first.err;
    EXPECT_NE(first.err.find("note: photon maps: written to --map-dir"), std::string::npos) << first.err;
    EXPECT_EQ(first.err.find("loaded from"), std::string::npos) << first.err;
    const fs::path file = onlyFile(mapDir());
    EXPECT_EQ(file.extension(), ".pmap");
    // The estimate counts the file on disk: at least its photons' records.
    EXPECT_NE(readFile(dir_ / "s.json").find("\"map_file\""), std::string::npos);

    const CliResult second = render(c, "second.png", "-t 2 --map-dir " + maps());
    ASSERT_EQ(second.exitCode, 0) << second.err;
    EXPECT_NE(second.err.find("note: photon maps: loaded from --map-dir"), std::string::npos) << second.err;
    EXPECT_EQ(second.err.find("written to"), std::string::npos) << second.err;
    EXPECT_EQ(mapFiles(mapDir()).size(), 1u);
    EXPECT_EQ(image("first.png"), image("ref.png"));
    EXPECT_EQ(image("second.png"), image("ref.png"));
  }
}

// The file holds the emission, which no thread count changes: written on one thread
// it is byte for byte the file two threads write, and read on two it renders their image.
TEST_F(MapFiles, AFileWrittenOnOneThreadIsReadOnTwo) {
  const SceneCase& c = kPhysical;
  ASSERT_EQ(render(c, "ref.png", "-t 2").exitCode, 0);
  ASSERT_EQ(render(c, "one.png", "-t 1 --map-dir " + maps("one")).exitCode, 0);
  ASSERT_EQ(render(c, "two.png", "-t 2 --map-dir " + maps("two")).exitCode, 0);
  const fs::path one = onlyFile(mapDir("one")), two = onlyFile(mapDir("two"));
  EXPECT_EQ(one.filename(), two.filename());
  EXPECT_EQ(readFile(one), readFile(two));
  const CliResult r = render(c, "loaded.png", "-t 2 --map-dir " + maps("one"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("loaded from"), std::string::npos) << r.err;
  EXPECT_EQ(image("loaded.png"), image("ref.png"));
}

// Each way a file can be wrong: the render names the file and the problem in one
// note, emits again, rewrites the good file and renders the good image.
TEST_F(MapFiles, ADamagedTruncatedOrSwappedFileIsNeverUsed) {
  const SceneCase& c = kGated;
  ASSERT_EQ(render(c, "ref.png", "--map-dir " + maps()).exitCode, 0);
  const fs::path file = onlyFile(mapDir());
  const std::string good = readFile(file);
  // Another key's file: the same scene with another shadow budget.
  ASSERT_EQ(runCli("render " + quote(shipped(c.file)) + " " + c.settings + " -D photons.shadow=50000 -q -o " +
                   quote((dir_ / "other.png").string()) + " --map-dir " + maps("other"))
                .exitCode,
            0);
  const std::string other = readFile(onlyFile(mapDir("other")));
  ASSERT_NE(other, good);

  struct Damage {
    const char* name;
    std::string bytes;
    const char* problem;
  };
  std::string payloadByte = good, headerByte = good;
  payloadByte[good.size() - 7] ^= 0x10;
  headerByte[40] ^= 0x01;
  const std::vector<Damage> damages = {
      {"a payload byte", payloadByte, "photons damaged (their checksum differs)"},
      {"a header byte", headerByte, "header damaged (its checksum differs)"},
      {"truncated", good.substr(0, good.size() / 2), "truncated ("},
      {"empty", "", "truncated: no header"},
      {"another key's file", other, "written for another photon key"},
  };
  for (const Damage& d : damages) {
    SCOPED_TRACE(d.name);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << d.bytes;
    const CliResult r = render(c, "again.png", "--map-dir " + maps());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string note = "note: photon maps: " + file.string() + ": " + d.problem;
    EXPECT_NE(r.err.find(note), std::string::npos) << r.err;
    EXPECT_EQ(occurrences(r.err, "photon maps: " + file.string()), 1u) << r.err;
    EXPECT_EQ(r.err.find("loaded from"), std::string::npos) << r.err;
    EXPECT_EQ(image("again.png"), image("ref.png"));
    EXPECT_EQ(readFile(file), good);
  }
}

// A sweep of one photon budget writes its stage's file, a second sweep loads it, and
// a render of one run's settings loads it too: every image as without files.
TEST_F(MapFiles, ASweepWritesAndLoadsMapFiles) {
  const SceneCase& c = kGated;
  auto sweep = [&](const std::string& out, const std::string& args) {
    return runCli("sweep " + quote(shipped(c.file)) + " " + c.settings + " -q --spp 1,2 --reference-passes 1 " +
                  "--no-gate-compare -o " + quote((dir_ / out).string()) + " " + args);
  };
  ASSERT_EQ(sweep("plain", "").exitCode, 0);
  CliResult r = sweep("first", "--map-dir " + maps());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const fs::path file = onlyFile(mapDir());
  const auto written = fs::last_write_time(file);
  r = sweep("second", "--map-dir " + maps());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(fs::last_write_time(file), written);  // loaded, not written again
  for (const auto& run : fs::directory_iterator(dir_ / "plain" / "runs")) {
    const std::string name = run.path().filename().string();
    EXPECT_EQ(pixelsOf(dir_ / "first" / "runs" / name), pixelsOf(run.path())) << name;
    EXPECT_EQ(pixelsOf(dir_ / "second" / "runs" / name), pixelsOf(run.path())) << name;
  }
  r = render(c, "run.png", "-D camera.spp=2 --map-dir " + maps());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("loaded from"), std::string::npos) << r.err;
  EXPECT_EQ(mapFiles(mapDir()).size(), 1u);
}

// A sweep of several budgets emits once at the largest and cuts the others out of it:
// only the largest budget's stage is what a render builds, so only its file is written.
TEST_F(MapFiles, ASweepOfSeveralBudgetsWritesOnlyTheLargest) {
  const SceneCase& c = kPhysical;
  const CliResult r = runCli("sweep " + quote(shipped(c.file)) + " " + c.settings +
                             " -q --photons 10000,20000 --reference-passes 1 --no-gate-compare -o " +
                             quote((dir_ / "sweep").string()) + " --map-dir " + maps());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const fs::path file = onlyFile(mapDir());
  ASSERT_EQ(render(c, "ref.png").exitCode, 0);  // c's budgets are the sweep's largest
  const CliResult loaded = render(c, "loaded.png", "--map-dir " + maps());
  EXPECT_NE(loaded.err.find("loaded from"), std::string::npos) << loaded.err;
  EXPECT_EQ(image("loaded.png"), image("ref.png"));
  const CliResult smaller = render(c, "small.png", "-D photons.global=10000 -D photons.caustic=10000 --map-dir " + maps());
  EXPECT_NE(smaller.err.find("written to"), std::string::npos) << smaller.err;
  EXPECT_EQ(mapFiles(mapDir()).size(), 2u);
}

// What batch --maps-only runs per job: plan, prepare, storeMaps. It emits and writes
// without building a map, then only checks the file; a later session loads it.
TEST_F(MapFiles, StoreMapsWritesOnceAndALaterSessionLoads) {
  SessionOptions options;
  options.threads = 2;
  options.mapDir = mapDir().string();
  JobRequest request;
  request.scenePath = shipped(kGated.file);
  request.overrides = {"camera.width=32", "camera.height=24", "photons.shadow=100000"};
  uint64_t written = 0;
  {
    RenderSession session(options);
    PlannedJob job = session.plan(request);
    session.prepare(job);
    const MapFileOutcome first = session.storeMaps({&job});
    EXPECT_TRUE(first.written);
    EXPECT_FALSE(first.loaded);
    written = first.bytes;
    const MapFileOutcome again = session.storeMaps({&job});
    EXPECT_TRUE(again.loaded);
    EXPECT_FALSE(again.written);
    EXPECT_EQ(session.mapWrites(), 1u);
    EXPECT_EQ(session.photonBuilds(), 1u);
  }
  const fs::path file = onlyFile(mapDir());
  EXPECT_EQ(fs::file_size(file), written);
  RenderSession session(options);
  PlannedJob job = session.plan(request);
  session.prepare(job);
  const PhotonStage& stage = session.photons(job);
  EXPECT_EQ(session.mapLoads(), 1u);
  EXPECT_EQ(session.mapWrites(), 0u);
  EXPECT_EQ(session.photonBuilds(), 0u);
  EXPECT_EQ(stage.emitted[MapKind::Shadow], 100000u);
}

// The prepass traces the BVH alone: a builtin texture is never made or loaded, so
// --maps-only does not load the image module for it; a frame's assets load it.
TEST_F(MapFiles, StoringMapsLeavesATexturedScenesTexturesUnloaded) {
  SessionOptions options;
  options.threads = 2;
  options.mapDir = mapDir().string();
  JobRequest request;
  request.scenePath = shipped("showcase.json");
  request.overrides = {"camera.width=32", "camera.height=24", "photons.shadow=20000", "photons.indirect=20000"};
  RenderSession session(options);
  PlannedJob job = session.plan(request);
  ASSERT_TRUE(job.plan[Pass::Textures].on);
  session.prepare(job, RenderSession::PrepareFor::Photons);
  EXPECT_TRUE(session.storeMaps({&job}).written);
  EXPECT_EQ(session.geometry(job).textures, nullptr);
  // Costed for a shard, then rendered by it: preparing for frames loads them, before any frame.
  session.prepare(job, RenderSession::PrepareFor::Frames);
  EXPECT_NE(session.geometry(job).textures, nullptr);
}

// A map file that cannot be written (a full disk, through the write hook) fails the
// render with one line, leaves no temp file and no image.
TEST_F(MapFiles, AFullMapDiskFailsTheRenderWithOneLine) {
  const SceneCase& c = kGated;
  ASSERT_EQ(render(c, "ref.png", "--map-dir " + maps()).exitCode, 0);
  const fs::path file = onlyFile(mapDir());
  fs::remove(file);
  CliResult r;
  {
    const testing::ScopedEnv full("PENUMBRA_TEST_DISK_FULL_AT", "write:" + file.stem().string() + ":*");
    r = render(c, "full.png", "--map-dir " + maps());
  }
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find(file.string() + ": cannot write photon map file: No space left on device"), std::string::npos)
      << r.err;
  EXPECT_EQ(occurrences(r.err, "\n"), 1u) << r.err;
  EXPECT_TRUE(mapFiles(mapDir()).empty());
  EXPECT_FALSE(fs::exists(dir_ / "full.png"));
}

// fig03's gate is auto, off for point lights, and it has no indirect map: no photons,
// so nothing to store and no file.
TEST_F(MapFiles, AStageWithoutPhotonsHasNoFile) {
  const SceneCase none{"fig03_shadows.json", "-D camera.width=32 -D camera.height=24"};
  const CliResult r = render(none, "x.png", "--map-dir " + maps());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("photon maps"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_directory(mapDir()));
  EXPECT_TRUE(mapFiles(mapDir()).empty());
}

TEST_F(MapFiles, AMapDirThatCannotBeCreatedIsRefusedBeforeAnyWork) {
  std::ofstream(dir_ / "plain-file") << "x";
  const CliResult r = render(kGated, "x.png", "--map-dir " + quote((dir_ / "plain-file" / "maps").string()));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--map-dir " + (dir_ / "plain-file" / "maps").string() + ": cannot create it"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(occurrences(r.err, "\n"), 1u) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

}  // namespace
}  // namespace penumbra::hard
