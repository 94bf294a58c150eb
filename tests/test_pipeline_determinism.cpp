// End to end: the same scene renders to the same bytes for any thread count
// (through runRender and through the penumbra binary), a different seed changes
// the jittered image, and the CLI's exit codes and messages follow the contract
// (0 ok, 2 bad input with one line on stderr).
#include "plan/pipeline.h"
#include "plan/batch/batch_jobs.h"
#include "plan/batch/batch_run.h"
#include "cli/progress_meter.h"
#include "plan/sweep/sweep_run.h"
#include "core/error.h"
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// A small open-fronted room: diffuse walls, a mirror ball, a glass ball, one point
// light (so both photon maps are built) and a dim directional light.
const char* kScene = R"({
  "name": "determinism",
  "camera": {"position": [0, 1, 3.5], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov": 50,
             "width": 64, "height": 48, "spp": 4},
  "lights": [
    {"type": "point", "position": [0.3, 1.8, 0.5], "color": [1, 0.95, 0.9], "intensity": 1.5},
    {"type": "directional", "direction": [0.2, -1, -0.3], "intensity": 0.1}
  ],
  "materials": {
    "white": {"ambient": 0.1, "diffuse": 0.75, "p_r": 0.5},
    "red": {"ambient": 0.1, "diffuse": [0.75, 0.2, 0.2], "p_r": 0.5},
    "green": {"ambient": 0.1, "diffuse": [0.2, 0.75, 0.2], "p_r": 0.5},
    "mirror": {"ambient": 0.0, "diffuse": 0.1, "reflective": {"kr": 0.8}},
    "glass": {"ambient": 0.0, "diffuse": 0.0, "transparent": {"ior": 1.5, "tint": [0.95, 1, 0.95]}}
  },
  "objects": [
    {"type": "quad", "corner": [-1, 0, -1], "edge1": [0, 0, 2], "edge2": [2, 0, 0], "material": "white"},
    {"type": "quad", "corner": [-1, 2, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "material": "white"},
    {"type": "quad", "corner": [-1, 0, -1], "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "white"},
    {"type": "quad", "corner": [-1, 0, -1], "edge1": [0, 2, 0], "edge2": [0, 0, 2], "material": "red"},
    {"type": "quad", "corner": [1, 0, -1], "edge1": [0, 0, 2], "edge2": [0, 2, 0], "material": "green"},
    {"type": "sphere", "center": [-0.45, 0.35, -0.3], "radius": 0.35, "material": "mirror"},
    {"type": "sphere", "center": [0.45, 0.35, 0.2], "radius": 0.35, "material": "glass"}
  ],
  "render": {"max_depth": 5, "background": [0.05, 0.05, 0.1], "seed": 7},
  "photons": {"shadow": 30000, "indirect": 20000, "k_shadow": 30, "k_indirect": 30,
              "estimator": "classic", "gate": true, "lookup": "exact"}
})";

class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    path_ = fs::temp_directory_path() / ("penumbra_pipe_" + tag + "_" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name, std::ios::binary) << text;
    return path_ / name;
  }
  const fs::path& path() const { return path_; }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string quote(const std::string& s) { return "'" + s + "'"; }

struct CliResult {
  int exitCode = -1;
  std::string out, err;
};

// Runs the penumbra binary with `args` (already shell-quoted), capturing output.
CliResult runCli(const TempDir& dir, const std::string& args) {
  fs::path out = dir.path() / "cli.stdout", err = dir.path() / "cli.stderr";
  std::string cmd = quote(PENUMBRA_BINARY) + " " + args + " >" + quote(out.string()) + " 2>" +
                    quote(err.string()) + " </dev/null";
  int status = std::system(cmd.c_str());
  CliResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readFile(out);
  r.err = readFile(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

size_t lineCount(const std::string& s) { return static_cast<size_t>(std::count(s.begin(), s.end(), '\n')); }

RenderResult render(const fs::path& scene, int threads, std::vector<std::string> overrides = {}) {
  RenderRequest req;
  req.scenePath = scene.string();
  req.session.threads = threads;
  req.overrides = std::move(overrides);
  return runRender(req);
}

bool samePixels(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

TEST(Determinism, RunRenderIsIdenticalForOneAndTwoThreads) {
  TempDir dir("threads");
  fs::path scene = dir.write("scene.json", kScene);
  RenderResult one = render(scene, 1);
  RenderResult two = render(scene, 2);
  ASSERT_EQ(one.image.width, 64);
  ASSERT_EQ(one.image.height, 48);
  // Photon maps were really on, and the gate and the gather were used.
  EXPECT_EQ(one.stats.emitted[MapKind::Shadow], 30000u);
  EXPECT_EQ(one.stats.emitted[MapKind::Indirect], 20000u);
  EXPECT_GT(one.stats.stored[MapKind::Shadow], 0u);
  EXPECT_GT(one.stats.stored[MapKind::Indirect], 0u);
  EXPECT_GT(one.stats.rays.gateQueries, 0u);
  EXPECT_GT(one.stats.rays.gatherQueries, 0u);
  EXPECT_EQ(one.stats.rays.camera, 64u * 48u * 4u);
  EXPECT_EQ(one.stats.threads, 1);
  EXPECT_EQ(two.stats.threads, 2);
  // Same photons, same rays, same bytes.
  EXPECT_EQ(one.stats.stored[MapKind::Shadow], two.stats.stored[MapKind::Shadow]);
  EXPECT_EQ(one.stats.stored[MapKind::Indirect], two.stats.stored[MapKind::Indirect]);
  EXPECT_EQ(one.stats.rays.shadow, two.stats.rays.shadow);
  EXPECT_EQ(one.stats.rays.reflection, two.stats.rays.reflection);
  EXPECT_EQ(one.stats.rays.refraction, two.stats.rays.refraction);
  EXPECT_TRUE(samePixels(one.image, two.image));
  // Not a degenerate image: finite, and with real variation.
  float lo = kInf, hi = -kInf;
  for (const Color& c : one.image.pixels) {
    ASSERT_TRUE(isFinite(c));
    lo = std::min(lo, luminance(c));
    hi = std::max(hi, luminance(c));
  }
  EXPECT_GT(hi - lo, 0.1f);
}

// A meter that draws every phase (no quiet time) into a scratch file, with its ticker
// polling while the workers count: what penumbra sweep and batch run on a terminal.
struct MeterToFile {
  explicit MeterToFile(const fs::path& path) : file(std::fopen(path.string().c_str(), "w")) {
    ProgressDisplay d;
    d.terminal = true;
    d.quietSeconds = 0.0;
    d.out = file;
    meter.emplace(d);
    meter->startTicker();
  }
  ~MeterToFile() {
    meter.reset();
    std::fclose(file);
  }
  std::FILE* file;
  std::optional<ProgressMeter> meter;
};

// Sweep and batch on two threads with their progress on (make test-tsan runs these):
// the lines come from the scheduling thread and the meter's ticker, never a worker.
TEST(Determinism, SweepWithProgressOnTwoThreads) {
  TempDir dir("sweep_progress");
  const fs::path scene = dir.write("scene.json", kScene);
  MeterToFile progress(dir.path() / "progress.txt");
  SweepRequest req;
  req.scenePath = scene.string();
  req.outDir = (dir.path() / "sweep").string();
  req.spec = expandGrid({keyKnob("photons.k_indirect=10,30")}, {"camera.spp=1"});
  req.session.threads = 2;
  size_t lines = 0;
  req.progress = [&](const SweepProgress& p) {
    progress.meter->setContext(p.run + " " + p.phase);
    ++lines;
  };
  req.session.progress = &*progress.meter;
  const SweepOutcome out = runSweep(req);
  progress.meter->finish();
  EXPECT_EQ(out.rows.size(), 2u);
  EXPECT_GT(lines, 0u);
  EXPECT_FALSE(progress.meter->ended().empty());
}

TEST(Determinism, BatchWithProgressOnTwoThreads) {
  TempDir dir("batch_progress");
  const fs::path scene = dir.write("scene.json", kScene);
  MeterToFile progress(dir.path() / "progress.txt");
  BatchRequest req;
  req.jobs = jobsForScenes({scene.string()}, dir.path().string(), {"beauty", "depth"}, ".exr");
  req.session.threads = 2;
  req.force = true;
  req.progress = [&](const BatchProgress& p) { progress.meter->setContext(p.job + " " + p.phase); };
  req.session.progress = &*progress.meter;
  const BatchOutcome out = runBatch(req);
  progress.meter->finish();
  EXPECT_EQ(out.rendered, 1u);
  EXPECT_EQ(out.failed, 0u);
  EXPECT_FALSE(progress.meter->ended().empty());
}

TEST(Determinism, SeedChangesTheJitteredImage) {
  TempDir dir("seed");
  fs::path scene = dir.write("scene.json", kScene);
  RenderResult a = render(scene, 2);
  RenderResult b = render(scene, 2, {"render.seed=8"});
  RenderResult a2 = render(scene, 2, {"render.seed=7"});
  EXPECT_TRUE(samePixels(a.image, a2.image));
  ASSERT_EQ(a.image.pixels.size(), b.image.pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.image.pixels.size(); ++i) differing += a.image.pixels[i] != b.image.pixels[i];
  // Jitter moves every sample; edges and the photon-map estimates change widely.
  EXPECT_GT(differing, a.image.pixels.size() / 10);
  // With one centred sample and no photons the seed plays no part at all.
  RenderResult c = render(scene, 2, {"camera.spp=1", "photons.shadow=0", "photons.indirect=0"});
  RenderResult d = render(scene, 2, {"camera.spp=1", "photons.shadow=0", "photons.indirect=0", "render.seed=8"});
  EXPECT_TRUE(samePixels(c.image, d.image));
}

TEST(Determinism, CliPngIsByteIdenticalForOneAndTwoThreads) {
  TempDir dir("cli");
  fs::path scene = dir.write("scene.json", kScene);
  fs::path png1 = dir.path() / "one.png", png2 = dir.path() / "two.png";
  CliResult r1 = runCli(dir, "render " + quote(scene.string()) + " -o " + quote(png1.string()) + " --threads 1 -q");
  CliResult r2 = runCli(dir, "render " + quote(scene.string()) + " -o " + quote(png2.string()) + " --threads 2 -q");
  ASSERT_EQ(r1.exitCode, 0) << r1.err;
  ASSERT_EQ(r2.exitCode, 0) << r2.err;
  EXPECT_EQ(r1.err, "");  // -q: nothing on stderr
  std::string a = readFile(png1), b = readFile(png2);
  ASSERT_GT(a.size(), 100u);
  EXPECT_EQ(a.substr(1, 3), "PNG");
  EXPECT_TRUE(a == b) << "PNG files differ between 1 and 2 threads";
  // No temporary files left next to the outputs.
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"one.png", "scene.json", "two.png"}));
}

TEST(Cli, BadInputExitsWithTwoAndOneLine) {
  TempDir dir("errors");
  fs::path scene = dir.write("scene.json", kScene);
  fs::path malformed = dir.write("broken.json", "{\n  \"camera\": {\"fov\": 40,,}\n}\n");
  fs::path out = dir.path() / "out.png";
  struct Case {
    std::string name, args;
  };
  const std::vector<Case> cases = {
      {"missing scene", "render " + quote((dir.path() / "nope.json").string()) + " -o " + quote(out.string())},
      {"malformed JSON", "render " + quote(malformed.string()) + " -o " + quote(out.string())},
      {"unsupported extension", "render " + quote(scene.string()) + " -o " + quote((dir.path() / "out.bmp").string())},
      {"no output", "render " + quote(scene.string())},
      {"bad trace pixel", "render " + quote(scene.string()) + " --trace-pixel abc"},
      {"trace pixel with junk", "render " + quote(scene.string()) + " --trace-pixel 1,2,3"},
      {"trace pixel outside", "render " + quote(scene.string()) + " --trace-pixel 64,0"},
      {"negative trace pixel", "render " + quote(scene.string()) + " --trace-pixel=-1,5"},
      {"unknown aov", "render " + quote(scene.string()) + " -o " + quote(out.string()) + " --aov shiny"},
  };
  std::vector<CliResult> results;
  for (const Case& c : cases) {
    results.push_back(runCli(dir, c.args));
    const CliResult& r = results.back();
    EXPECT_EQ(r.exitCode, 2) << c.name << ": " << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << c.name << ": " << r.err;
    EXPECT_EQ(r.err.rfind("penumbra: ", 0), 0u) << c.name << ": " << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << c.name;
  }
  // The messages say what is wrong and where.
  EXPECT_NE(results[0].err.find("nope.json"), std::string::npos);
  EXPECT_NE(results[1].err.find("broken.json:2:"), std::string::npos);
  EXPECT_NE(results[2].err.find(".bmp"), std::string::npos);
  EXPECT_NE(results[6].err.find("64,0"), std::string::npos);
  // Nothing was written for any of them (no image, no temporary).
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"broken.json", "scene.json"}));
  // Argument errors from the parser also map to 2.
  EXPECT_EQ(runCli(dir, "render " + quote(scene.string()) + " -o " + quote(out.string()) + " --threads 0").exitCode, 2);
  EXPECT_EQ(runCli(dir, "frobnicate").exitCode, 2);
  EXPECT_EQ(runCli(dir, "").exitCode, 2);
}

TEST(Cli, HelpExitsWithZero) {
  TempDir dir("help");
  CliResult top = runCli(dir, "--help");
  EXPECT_EQ(top.exitCode, 0);
  EXPECT_NE(top.out.find("render"), std::string::npos);
  CliResult sub = runCli(dir, "render --help");
  EXPECT_EQ(sub.exitCode, 0);
  EXPECT_NE(sub.out.find("--trace-pixel"), std::string::npos);
}

TEST(Cli, TracePixelWritesParsableRayTree) {
  TempDir dir("trace");
  fs::path scene = dir.write("scene.json", kScene);
  fs::path json = dir.path() / "tree.json";
  CliResult r = runCli(dir, "render " + quote(scene.string()) + " --trace-pixel 40,30 -o " +
                                quote(json.string()) + " -q");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  nlohmann::json tree = nlohmann::json::parse(readFile(json));  // throws if malformed
  EXPECT_EQ(tree["pixel"], nlohmann::json({40, 30}));
  ASSERT_TRUE(tree["rays"].is_array());
  ASSERT_GE(tree["rays"].size(), 1u);
  const auto& first = tree["rays"][0];
  EXPECT_EQ(first["kind"], "camera");
  EXPECT_EQ(first["parent"], -1);
  EXPECT_EQ(first["depth"], 0);
  EXPECT_EQ(first["origin"], nlohmann::json({0.0, 1.0, 3.5}));
  EXPECT_TRUE(first["hit"].get<bool>());  // pixel 40,30 looks into the room
  for (size_t i = 1; i < tree["rays"].size(); ++i) {
    int parent = tree["rays"][i]["parent"];
    EXPECT_GE(parent, 0);
    EXPECT_LT(parent, static_cast<int>(i));
    EXPECT_NE(tree["rays"][i]["kind"], "camera");
  }
  // Without -o the tree goes to stdout, and it is the same tree.
  CliResult s = runCli(dir, "render " + quote(scene.string()) + " --trace-pixel 40,30 -q");
  ASSERT_EQ(s.exitCode, 0) << s.err;
  EXPECT_EQ(nlohmann::json::parse(s.out), tree);
  // The in-process pipeline records the same first ray.
  RenderRequest req;
  req.scenePath = scene.string();
  req.session.threads = 1;
  req.tracePixel = std::make_pair(40, 30);
  RenderResult result = runRender(req);
  ASSERT_EQ(result.rayTree.size(), tree["rays"].size());
  EXPECT_EQ(result.rayTree[0].kind, "camera");
  EXPECT_TRUE(result.image.pixels.empty());  // no image for a trace request
}

TEST(Pipeline, InputErrorsThrowInputError) {
  TempDir dir("throws");
  fs::path scene = dir.write("scene.json", kScene);
  RenderRequest req;
  req.scenePath = (dir.path() / "missing.json").string();
  EXPECT_THROW(runRender(req), InputError);
  req.scenePath = scene.string();
  req.aov = "nope";
  EXPECT_THROW(runRender(req), InputError);
  req.aov = "beauty";
  req.tracePixel = std::make_pair(64, 48);
  EXPECT_THROW(runRender(req), InputError);
}

}  // namespace
}  // namespace penumbra
