// Resumable progressive jobs, through the binary: SIGTERM after pass k (the
// PENUMBRA_TEST_TERM_AFTER_PASS hook, never a timer) exits with kExitTerminated and
// leaves OUTPUT.passes and nothing else; the same command then writes the bytes an
// uninterrupted run writes (an EXR's bar OIIO's DateTime). A corrupt, truncated or foreign passes file is not used,
// --force discards it, and a frame that is not progressive still dies of the signal.
#include "hard/hard_cli.h"
#include "plan/saved_passes.h"
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <vector>

namespace penumbra::hard {
namespace {

using testing::readFile;

// cornell_physical's 12 passes at a size and photon count that take well under a second.
const std::vector<std::string> kSmall = {"-D", "camera.width=24", "-D", "camera.height=24", "-D",
                                         "photons.global=5000", "-D", "photons.caustic=5000"};
constexpr const char* kHook = "PENUMBRA_TEST_TERM_AFTER_PASS";

// A file's bytes with OIIO's EXR DateTime (the one thing two runs' files differ in) blanked.
std::string bytesOf(const fs::path& p) {
  static const std::regex kDateTime("[0-9]{4}:[0-9]{2}:[0-9]{2} [0-9]{2}:[0-9]{2}:[0-9]{2}");
  return std::regex_replace(readFile(p), kDateTime, "YYYY:MM:DD hh:mm:ss");
}

std::string cornell() { return std::string(PENUMBRA_SOURCE_DIR) + "/scenes/cornell_physical.json"; }

struct Outcome {
  int status = -1;  // as waitpid gives it: an exit code or the signal that killed it
  std::string err;
  int exitCode() const { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }
  bool killedBy(int sig) const { return WIFSIGNALED(status) && WTERMSIG(status) == sig; }
};

// Runs the binary on `args` (no shell, so an exit code is the process's own and a death
// by signal stays one) with the hook set to `termAfter` (0: unset).
Outcome run(std::vector<std::string> args, int termAfter = 0) {
  const testing::ScratchDir io;
  const std::string errPath = (io / "stderr").string();
  std::vector<std::string> envText;
  for (char** e = environ; *e; ++e) {
    if (std::strncmp(*e, kHook, std::strlen(kHook)) != 0) envText.emplace_back(*e);
  }
  if (termAfter > 0) envText.push_back(std::string(kHook) + "=" + std::to_string(termAfter));
  std::vector<char*> env, argv = {const_cast<char*>(PENUMBRA_BINARY)};
  for (std::string& e : envText) env.push_back(e.data());
  env.push_back(nullptr);
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  Outcome r;
  const pid_t child = fork();
  if (child < 0) return r;
  if (child == 0) {
    const int err = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int null = ::open("/dev/null", O_RDWR);
    if (err >= 0) ::dup2(err, 2);
    if (null >= 0) {
      ::dup2(null, 0);
      ::dup2(null, 1);
    }
    ::execve(PENUMBRA_BINARY, argv.data(), env.data());
    _exit(127);
  }
  waitpid(child, &r.status, 0);
  r.err = readFile(errPath);
  return r;
}

std::vector<std::string> render(const fs::path& out, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"render", cornell(), "-o", out.string()};
  args.insert(args.end(), kSmall.begin(), kSmall.end());
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

// Every entry of `dir` by name.
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class Resume : public ::testing::Test {
 protected:
  // The uninterrupted render's bytes, once per output extension.
  static std::string reference(const std::string& ext) {
    static std::map<std::string, std::string> bytes;
    if (!bytes.count(ext)) {
      const ScratchDir dir;
      const Outcome r = run(render(dir / ("ref" + ext), {"-t", "2"}));
      EXPECT_EQ(r.exitCode(), 0) << r.err;
      bytes[ext] = bytesOf(dir / ("ref" + ext));
    }
    return bytes[ext];
  }
  // Interrupts the render of `out` after pass k: exit 143, its passes file and nothing else.
  void interrupt(const fs::path& out, int k, std::vector<std::string> extra = {}) {
    const Outcome r = run(render(out, extra), k);
    ASSERT_EQ(r.exitCode(), kExitTerminated) << r.err;
    EXPECT_EQ(occurrences(r.err, "SIGTERM: saved " + std::to_string(k) + " of 12 passes to " + out.string() + ".passes"),
              1u)
        << r.err;
    EXPECT_EQ(listing(out.parent_path()), std::vector<std::string>{out.filename().string() + ".passes"});
  }
  void resumeWithout(const std::string& why);
  ScratchDir dir;
};

TEST_F(Resume, AfterAnyPassTheResumedImageIsTheUninterruptedOnesBytes) {
  const std::pair<std::string, int> runs[] = {{".exr", 1}, {".exr", 6}, {".exr", 11}, {".png", 6}};
  for (const auto& [ext, k] : runs) {
    SCOPED_TRACE(ext + " after pass " + std::to_string(k));
    const fs::path out = dir / ("frame" + ext);
    interrupt(out, k, {"-t", "2"});
    // Another thread count: passes are seeded by their index.
    const Outcome r = run(render(out, {"-t", "1"}));
    ASSERT_EQ(r.exitCode(), 0) << r.err;
    EXPECT_EQ(occurrences(r.err, out.string() + ".passes: resumed at pass " + std::to_string(k + 1) + " of 12"), 1u)
        << r.err;
    EXPECT_TRUE(bytesOf(out) == reference(ext)) << "the resumed image differs";
    EXPECT_EQ(listing(dir.path()), std::vector<std::string>{out.filename().string()});  // the passes file is gone
    fs::remove(out);
  }
}

// Coverage is summed over the passes as the colour is: a transparent frame (wide enough
// to see past the box) resumed after a pass writes the uninterrupted one's RGBA.
TEST_F(Resume, ATransparentFrameResumesToTheSameRgba) {
  const std::vector<std::string> clear = {"-D", "render.transparent_background=true", "-D", "camera.fov=90"};
  for (const char* ext : {".exr", ".png"}) {
    SCOPED_TRACE(ext);
    const ScratchDir refDir;  // apart: interrupt() expects its folder to hold the passes file alone
    const fs::path ref = refDir / (std::string("ref") + ext), out = dir / (std::string("frame") + ext);
    ASSERT_EQ(run(render(ref, clear)).exitCode(), 0);
    interrupt(out, 4, clear);
    const Outcome r = run(render(out, clear));
    ASSERT_EQ(r.exitCode(), 0) << r.err;
    EXPECT_EQ(occurrences(r.err, "resumed at pass 5 of 12"), 1u) << r.err;
    EXPECT_TRUE(bytesOf(out) == bytesOf(ref)) << "the resumed image differs";
    fs::remove(out);
  }
}

// Where a pass's maps and lookups come from differs by model: the classic model's
// passes read pass 0's maps and precomputed lookups, the gate's shadow photons (and
// their KD-trees) are pass 0's in both; a resumed frame builds them itself.
TEST_F(Resume, PassZerosMapsAndLookupsAreRebuiltAlike) {
  const std::string scenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";
  const std::vector<std::vector<std::string>> jobs = {
      {scenes + "fig14_cornell.json", "-D", "photons.passes=4", "-D", "photons.lookup=precomputed", "-D",
       "photons.gate=on", "-D", "photons.shadow=5000", "-D", "photons.indirect=5000"},
      {cornell(), "-D", "photons.passes=4", "-D", "photons.gate=on", "-D", "photons.shadow=5000"},
  };
  for (const std::vector<std::string>& job : jobs) {
    SCOPED_TRACE(job.front());
    auto args = [&](const fs::path& out) {
      std::vector<std::string> a = {"render", job.front(), "-o", out.string()};
      a.insert(a.end(), kSmall.begin(), kSmall.end());
      a.insert(a.end(), job.begin() + 1, job.end());
      return a;
    };
    ASSERT_EQ(run(args(dir / "whole.png")).exitCode(), 0);
    ASSERT_EQ(run(args(dir / "part.png"), 2).exitCode(), kExitTerminated);
    const Outcome r = run(args(dir / "part.png"));
    ASSERT_EQ(r.exitCode(), 0) << r.err;
    EXPECT_EQ(occurrences(r.err, "resumed at pass 3 of 4"), 1u) << r.err;
    EXPECT_TRUE(readFile(dir / "part.png") == readFile(dir / "whole.png"));
  }
}

TEST_F(Resume, InterruptedTwiceStillEndsWithTheSameBytes) {
  const fs::path out = dir / "frame.exr";
  interrupt(out, 3);
  const Outcome second = run(render(out), 8);  // resumes at 4, stops after 8
  ASSERT_EQ(second.exitCode(), kExitTerminated) << second.err;
  EXPECT_EQ(occurrences(second.err, "saved 8 of 12 passes"), 1u) << second.err;
  const Outcome last = run(render(out));
  ASSERT_EQ(last.exitCode(), 0) << last.err;
  EXPECT_EQ(occurrences(last.err, "resumed at pass 9 of 12"), 1u) << last.err;
  EXPECT_TRUE(bytesOf(out) == reference(".exr"));
}

// A damaged or foreign file: one note naming why, pass 1, the uninterrupted bytes,
// and the file gone once the job is done.
void Resume::resumeWithout(const std::string& why) {
  const fs::path out = dir / "frame.exr", passes = dir / "frame.exr.passes";
  const Outcome r = run(render(out));
  ASSERT_EQ(r.exitCode(), 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "frame.exr.passes: saved passes not used ("), 1u) << r.err;
  EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
  EXPECT_EQ(occurrences(r.err, "resumed"), 0u) << r.err;
  EXPECT_TRUE(bytesOf(out) == reference(".exr"));
  EXPECT_FALSE(fs::exists(passes));
  fs::remove(out);
}

TEST_F(Resume, ACorruptOrTruncatedPassesFileIsNotUsed) {
  interrupt(dir / "frame.exr", 5);
  const std::string saved = readFile(dir / "frame.exr.passes");
  std::string flipped = saved;
  flipped[flipped.size() / 2] ^= 0x10;
  const std::pair<const char*, std::string> damaged[] = {
      {"corrupt", flipped},
      {"truncated", saved.substr(0, saved.size() - 1)},
      {"truncated", saved.substr(0, 10)},
      {"not a passes file", "P6 24 24 255\n"},
  };
  for (const auto& [why, bytes] : damaged) {
    SCOPED_TRACE(std::string(why) + ", " + std::to_string(bytes.size()) + " bytes");
    dir.write("frame.exr.passes", bytes);
    resumeWithout(why);
  }
}

// Settings outside the photon key (the size, a gather's k) belong to the job too.
TEST_F(Resume, PassesOfAnotherSettingAreNotUsed) {
  for (const char* other : {"camera.width=20", "photons.k_global=60", "render.transparent_background=true"}) {
    SCOPED_TRACE(other);
    interrupt(dir / "frame.exr", 5, {"-D", other});
    resumeWithout("saved by another job or setting");
  }
}

TEST_F(Resume, ForceDiscardsTheSavedPasses) {
  const fs::path out = dir / "frame.exr";
  interrupt(out, 7);
  // Had it resumed at pass 8, the hook at pass 2 would never fire.
  const Outcome forced = run(render(out, {"--force"}), 2);
  ASSERT_EQ(forced.exitCode(), kExitTerminated) << forced.err;
  EXPECT_EQ(occurrences(forced.err, "saved 2 of 12 passes"), 1u) << forced.err;
  const Outcome r = run(render(out, {"--force"}));
  ASSERT_EQ(r.exitCode(), 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "frame.exr.passes: saved passes discarded (--force)"), 1u) << r.err;
  EXPECT_EQ(occurrences(r.err, "resumed"), 0u) << r.err;
  EXPECT_TRUE(bytesOf(out) == reference(".exr"));
  EXPECT_EQ(listing(dir.path()), std::vector<std::string>{"frame.exr"});
}

// After the last pass there is nothing to save: the image is written and the render is done.
TEST_F(Resume, ASigtermAsTheLastPassEndsStillWritesTheImage) {
  const fs::path out = dir / "frame.exr";
  const Outcome r = run(render(out), 12);
  ASSERT_EQ(r.exitCode(), 0) << r.err;
  EXPECT_TRUE(bytesOf(out) == reference(".exr"));
  EXPECT_EQ(listing(dir.path()), std::vector<std::string>{"frame.exr"});
}

// A frame of one pass, or a SIGTERM while nothing progressive runs, keeps the old way:
// temp files removed, death by the signal, nothing saved.
TEST_F(Resume, AFrameThatIsNotProgressiveStillDiesOfTheSignal) {
  const fs::path out = dir / "one.exr";
  const Outcome r = run(render(out, {"-D", "photons.passes=1"}), 1);
  EXPECT_TRUE(r.killedBy(SIGTERM)) << r.status << " " << r.err;
  EXPECT_TRUE(listing(dir.path()).empty());
}

TEST_F(Resume, ABatchJobResumesAndItsPassesFileGoesWhenItIsDone) {
  std::string set;
  for (size_t i = 1; i < kSmall.size(); i += 2) set += (set.empty() ? "\"" : ", \"") + kSmall[i] + "\"";
  const fs::path jobs = dir.write("jobs.json", R"({"set": [)" + set + R"(], "jobs": [
    {"name": "physical", "scene": ")" + cornell() + R"(", "output": "physical.exr"},
    {"name": "depth", "scene": ")" + cornell() + R"(", "views": ["depth"], "output": "depth.exr"}]})");
  auto batch = [&](std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"batch", jobs.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  const Outcome whole = run(batch({"-t", "1"}));
  ASSERT_EQ(whole.exitCode(), 0) << whole.err;
  const std::string physical = bytesOf(dir / "physical.exr"), depth = bytesOf(dir / "depth.exr");
  fs::remove(dir / "physical.exr");
  fs::remove(dir / "depth.exr");

  const Outcome stopped = run(batch({"-t", "1"}), 6);
  ASSERT_EQ(stopped.exitCode(), kExitTerminated) << stopped.err;
  EXPECT_EQ(occurrences(stopped.err, "saved 6 of 12 passes to " + (dir / "physical.exr.passes").string()), 1u)
      << stopped.err;
  // The batch stopped there: the next job was not begun.
  EXPECT_EQ(listing(dir.path()), (std::vector<std::string>{"jobs.json", "physical.exr.passes"}));

  // --force starts the job over (the hook at pass 2 fires only from pass 1).
  const Outcome forced = run(batch({"--force"}), 2);
  ASSERT_EQ(forced.exitCode(), kExitTerminated) << forced.err;
  EXPECT_EQ(occurrences(forced.err, "saved 2 of 12 passes"), 1u) << forced.err;

  const Outcome resumed = run(batch({"-t", "2"}));
  ASSERT_EQ(resumed.exitCode(), 0) << resumed.err;
  EXPECT_EQ(occurrences(resumed.err, "physical.exr.passes: resumed at pass 3 of 12"), 1u) << resumed.err;
  EXPECT_TRUE(bytesOf(dir / "physical.exr") == physical) << "the resumed job's image differs";
  EXPECT_TRUE(bytesOf(dir / "depth.exr") == depth);
  EXPECT_EQ(listing(dir.path()), (std::vector<std::string>{"depth.exr", "jobs.json", "physical.exr"}));

  // SIGTERM as the last pass ends: that job is whole and written, the next is not begun.
  fs::remove(dir / "physical.exr");
  fs::remove(dir / "depth.exr");
  const Outcome late = run(batch({"-t", "1"}), 12);
  ASSERT_EQ(late.exitCode(), kExitTerminated) << late.err;
  EXPECT_EQ(occurrences(late.err, "SIGTERM: stopped before job 'depth'"), 1u) << late.err;
  EXPECT_TRUE(bytesOf(dir / "physical.exr") == physical);
  EXPECT_EQ(listing(dir.path()), (std::vector<std::string>{"jobs.json", "physical.exr"}));
  const Outcome rest = run(batch({"-t", "1"}));
  ASSERT_EQ(rest.exitCode(), 0) << rest.err;
  EXPECT_NE(rest.err.find("1 rendered, 1 up to date"), std::string::npos) << rest.err;
  EXPECT_TRUE(bytesOf(dir / "depth.exr") == depth);
}

}  // namespace
}  // namespace penumbra::hard
