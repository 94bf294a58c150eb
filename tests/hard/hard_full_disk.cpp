// A full disk, through the binary: every command and output format exits with its
// failure code, keeps the old file byte for byte and leaves no temp file; a full disk
// is refused before the work; an image cut short is never up to date.
#include "hard/hard_cli.h"
#include "support/scoped_env.h"
#include "io/image_io.h"
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/mount.h>
#include <unistd.h>
#include <fstream>
#include <map>
#include <optional>
#include <vector>

namespace penumbra::hard {
namespace {

using testing::readFile;

// How a test fills the disk: a small tmpfs with a filler file taking its every
// block (root only, where mount works), or the binary's deterministic hook
// (PENUMBRA_TEST_DISK_FULL_AT: ENOSPC after half the bytes of a named write), which
// runs everywhere, so the suite never passes by skipping.
enum class Fill { Tmpfs, Hook };

class FullDisk {
 public:
  static constexpr uintmax_t kBlock = 4096;  // tmpfs counts whole pages

  explicit FullDisk(Fill how) : how_(how), dir_(scratch_ / "disk") {
    fs::create_directory(dir_);
    if (how_ == Fill::Tmpfs) mounted_ = ::mount("tmpfs", dir_.c_str(), "tmpfs", 0, "size=2m") == 0;
  }
  ~FullDisk() {
    free();
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  FullDisk(const FullDisk&) = delete;
  FullDisk& operator=(const FullDisk&) = delete;

  bool ready() const { return how_ == Fill::Hook || mounted_; }
  // The folder that fills up; `off()` is a folder beside it that never does.
  const fs::path& dir() const { return dir_; }
  const testing::ScratchDir& off() const { return scratch_; }

  // From here every write into dir() fails: the filler takes every free block but
  // `spare` bytes' worth, or the hook fails each temp file whose name starts with
  // `prefix` ("" any).
  void fill(const std::string& prefix, uintmax_t spare = 0) {
    if (how_ == Fill::Hook) {
      env_.emplace("PENUMBRA_TEST_DISK_FULL_AT", "write:" + prefix + ":*");
      return;
    }
    const int fd = ::open((dir_ / "filler").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ASSERT_GE(fd, 0);
    const std::vector<char> block(kBlock, 'x');
    while (::write(fd, block.data(), block.size()) > 0) {
    }
    EXPECT_EQ(errno, ENOSPC);
    ::close(fd);
    const uintmax_t blocks = (spare + kBlock - 1) / kBlock;
    fs::resize_file(dir_ / "filler", fs::file_size(dir_ / "filler") - blocks * kBlock);
  }
  void free() {
    env_.reset();
    std::error_code ec;
    fs::remove(dir_ / "filler", ec);
  }

 private:
  Fill how_;
  testing::ScratchDir scratch_;
  fs::path dir_;
  bool mounted_ = false;
  std::optional<testing::ScopedEnv> env_;
};

// Every regular file under `root` and its bytes: what a failed command must leave.
std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.is_regular_file()) files[fs::relative(e.path(), root).string()] = readFile(e.path());
  }
  return files;
}

// Files under `root` whose name holds ".tmp": what a failed write would leave behind.
int tempFilesUnder(const fs::path& root) {
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(root))
    n += e.path().filename().string().find(".tmp") != std::string::npos;
  return n;
}

class FullDiskTest : public ::testing::TestWithParam<Fill> {
 protected:
  void SetUp() override {
    disk_.emplace(GetParam());
    if (!disk_->ready()) GTEST_SKIP() << "cannot mount a tmpfs here (needs root); the Hook cases cover the same writes";
    scene_ = disk_->off().write("floor.json", kFloorScene).string();
  }
  FullDisk& disk() { return *disk_; }
  std::string render(const std::string& args) const { return "render " + quote(scene_) + " " + args; }

  std::optional<FullDisk> disk_;
  std::string scene_;
};

std::string fillName(const ::testing::TestParamInfo<Fill>& info) {
  return info.param == Fill::Tmpfs ? "Tmpfs" : "Hook";
}

}  // namespace

// The image is encoded in memory and written by a checked loop: a short write is
// an error (OIIO's PNG writer alone reported none), and the old image stays.
TEST_P(FullDiskTest, RenderKeepsTheOldImageInEveryFormat) {
  for (const std::string ext : {"png", "exr"}) {
    const fs::path out = disk().dir() / ("a." + ext);
    ASSERT_EQ(runCli(render("-q -o " + quote(out.string()))).exitCode, 0);
    const auto before = snapshot(disk().dir());
    disk().fill("a.tmp");
    const CliResult r = runCli(render("-q --set camera.width=20 -o " + quote(out.string())));
    disk().free();
    EXPECT_EQ(r.exitCode, 2) << ext << ": " << r.err;
    EXPECT_NE(r.err.find(out.string() + ": cannot write image: No space left on device"), std::string::npos) << r.err;
    EXPECT_EQ(occurrences(r.err, "\n"), 1u) << r.err;
    EXPECT_EQ(snapshot(disk().dir()), before) << ext;
    EXPECT_EQ(tempFilesUnder(disk().dir()), 0) << ext;
  }
}

TEST_P(FullDiskTest, StatsKeepTheOldReport) {
  const fs::path stats = disk().dir() / "s.json";
  std::ofstream(stats) << "{\"the previous stats\": 1}\n";
  const auto before = snapshot(disk().dir());
  disk().fill("s.tmp");
  const CliResult r =
      runCli(render("-q -o " + quote((disk().off() / "img.png").string()) + " --stats " + quote(stats.string())));
  disk().free();
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find(stats.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(occurrences(r.err, "\n"), 1u) << r.err;
  EXPECT_EQ(snapshot(disk().dir()), before);
  EXPECT_EQ(tempFilesUnder(disk().dir()), 0);
}

// A PNG job and a layered EXR job: on a disk full before the batch starts it is refused
// (exit 2) like any unwritable output; when the writes fail, both jobs fail (batch's
// exit 1). Either way their old outputs stay whole, and with room again the rerun
// renders both (an edited job's outputs are stale; nothing cut short has the new stamp).
TEST_P(FullDiskTest, BatchJobsFailKeepTheirOldOutputsAndRenderOnTheRerun) {
  const fs::path jobs = disk().off() / "jobs.json";
  auto writeJobs = [&](int width) {
    std::ofstream(jobs) << "{\"set\": [\"camera.width=" << width << "\"], \"jobs\": ["
                        << "{\"name\": \"p\", \"scene\": \"" << scene_ << "\", \"output\": \""
                        << (disk().dir() / "p.png").string() << "\"},"
                        << "{\"name\": \"l\", \"scene\": \"" << scene_ << "\", \"views\": [\"beauty\", \"depth\"], "
                        << "\"output\": \"" << (disk().dir() / "l.exr").string() << "\"}]}";
  };
  writeJobs(16);
  const std::string batch = "batch " + quote(jobs.string());
  CliResult r = runCli(batch);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_NE(r.err.find("2 jobs: 2 rendered, 0 up to date, 0 failed"), std::string::npos) << r.err;
  const auto before = snapshot(disk().dir());
  writeJobs(20);
  disk().fill("");
  r = runCli(batch);
  disk().free();
  if (GetParam() == Fill::Tmpfs) {
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("No space left on device (its file system is full)"), std::string::npos) << r.err;
  } else {
    EXPECT_EQ(r.exitCode, 3) << r.err;  // some jobs failed: never 1, the internal-error code
    EXPECT_NE(r.err.find("2 jobs: 0 rendered, 0 up to date, 2 failed"), std::string::npos) << r.err;
  }
  EXPECT_EQ(snapshot(disk().dir()), before);
  EXPECT_EQ(tempFilesUnder(disk().dir()), 0);
  r = runCli(batch);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("2 jobs: 2 rendered, 0 up to date, 0 failed"), std::string::npos) << r.err;
}

// A sweep that adds a run: on the full disk it exits 2 with the finished runs'
// images whole and no row for the new run; with room again the rerun renders it.
TEST_P(FullDiskTest, SweepKeepsItsFinishedRunsAndResumes) {
  const fs::path out = disk().dir() / "sweep";
  const std::string sweep = "sweep " + quote(scene_) + " -q -o " + quote(out.string()) + " --spp ";
  ASSERT_EQ(runCli(sweep + "1,2").exitCode, 0);
  const auto before = snapshot(out / "runs");
  disk().fill("spp-3.tmp");  // the hook: the new run's image, after the folder's own files
  CliResult r = runCli(sweep + "1,2,3");
  disk().free();
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(snapshot(out / "runs"), before);
  EXPECT_EQ(readFile(out / "results.csv").find("spp=3"), std::string::npos);
  EXPECT_EQ(tempFilesUnder(out), 0);
  r = runCli(sweep + "1,2,3");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(imageComplete((out / "runs" / "spp-3.exr").string()));
}

INSTANTIATE_TEST_SUITE_P(FullDisk, FullDiskTest, ::testing::Values(Fill::Tmpfs, Fill::Hook), fillName);

// A real file system with one block left: the up-front check passes and the kernel
// refuses the write part-way through the file (PNG 6 kB, EXR 18 kB), the case OIIO's
// PNG writer let through.
TEST(FullDisk, ATmpfsRunningOutMidImageKeepsTheOldOne) {
  FullDisk disk(Fill::Tmpfs);
  if (!disk.ready()) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  const std::string scene = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/fig03_shadows.json";
  for (const std::string ext : {"png", "exr"}) {
    const fs::path out = disk.dir() / ("a." + ext);
    const std::string render = "render " + quote(scene) + " -q --set camera.width=160 --set camera.height=120 -o " +
                               quote(out.string());
    ASSERT_EQ(runCli(render).exitCode, 0);
    ASSERT_GT(fs::file_size(out), FullDisk::kBlock);
    const auto before = snapshot(disk.dir());
    disk.fill("", FullDisk::kBlock);
    const CliResult r = runCli(render + " --seed 2");
    disk.free();
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(out.string() + ": cannot write image: No space left on device; the old file is kept"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(snapshot(disk.dir()), before) << ext;
    EXPECT_EQ(tempFilesUnder(disk.dir()), 0) << ext;
  }
}

// The disk fills during a batch (its first job's image takes the last blocks): the
// next job fails before it renders, not after (its own photon count would need a
// second photon map: only one is built), and the batch goes on.
TEST(FullDisk, ABatchJobAfterTheDiskFilledFailsBeforeItsRender) {
  FullDisk disk(Fill::Tmpfs);
  if (!disk.ready()) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  const std::string scene = disk.off().write("floor.json", kFloorScene).string();
  const fs::path a = disk.dir() / "a.exr", b = disk.dir() / "b.png";
  const std::string jobA = "{\"name\": \"a\", \"scene\": \"" + scene + "\", \"output\": \"" + a.string() + "\"}";
  const std::string jobB = "{\"name\": \"b\", \"scene\": \"" + scene +
                           "\", \"set\": [\"photons.indirect=3000\"], \"output\": \"" + b.string() + "\"}";
  const fs::path jobs = disk.off().write(
      "jobs.json", "{\"set\": [\"camera.width=160\", \"camera.height=120\"], \"jobs\": [" + jobA + ", " + jobB + "]}");
  const std::string batch = "batch " + quote(jobs.string());
  ASSERT_EQ(runCli(batch).exitCode, 0);
  const uintmax_t size = fs::file_size(a);  // the same job writes the same bytes again
  fs::remove(a);
  fs::remove(b);
  disk.fill("", size);
  const CliResult r = runCli(batch);
  EXPECT_EQ(r.exitCode, 3) << r.err;
  EXPECT_NE(r.err.find("2 jobs: 1 rendered, 0 up to date, 1 failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("photon maps built 1 "), std::string::npos) << r.err;
  EXPECT_TRUE(imageComplete(a.string()));
  EXPECT_FALSE(fs::exists(b));
  EXPECT_EQ(tempFilesUnder(disk.dir()), 0);
}

// Statistics sent to stdout redirected onto a full device: exit 2, not 0 with half a report.
TEST(FullDisk, StdoutOntoAFullDeviceIsAnError) {
  ASSERT_TRUE(fs::exists("/dev/full"));
  ScratchDir dir;
  const std::string scene = dir.write("floor.json", kFloorScene).string();
  const std::string cmd = quote(PENUMBRA_BINARY) + " render " + quote(scene) + " -q -o " +
                          quote((dir / "a.png").string()) + " --stats - >/dev/full 2>" + quote((dir / "err").string());
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << status;
  EXPECT_EQ(readFile(dir / "err"), "penumbra: cannot write to standard output: No space left on device\n");
}

// A PNG and an EXR cut to half their bytes keep the job's stamp in their header; the
// rerun renders them again rather than call them up to date.
TEST(FullDisk, AnImageCutShortIsNeverUpToDate) {
  ScratchDir dir;
  const std::string scene = dir.write("floor.json", kFloorScene).string();
  // Large enough that the pixels, not the header, are most of each file.
  const fs::path jobs = dir.write("jobs.json", "{\"set\": [\"camera.width=160\", \"camera.height=120\"], "
                                               "\"jobs\": [{\"name\": \"p\", \"scene\": \"" + scene +
                                                   "\", \"output\": \"p.png\"}, {\"name\": \"e\", \"scene\": \"" +
                                                   scene + "\", \"output\": \"e.exr\"}]}");
  const std::string batch = "batch " + quote(jobs.string());
  ASSERT_EQ(runCli(batch).exitCode, 0);
  EXPECT_NE(runCli(batch).err.find("2 jobs: 0 rendered, 2 up to date"), std::string::npos);
  for (const char* name : {"p.png", "e.exr"}) {
    const fs::path file = dir / name;
    const std::string stamp = readImageAttribute(file.string(), "penumbra:job");
    ASSERT_FALSE(stamp.empty()) << name;
    EXPECT_TRUE(imageComplete(file.string())) << name;
    fs::resize_file(file, fs::file_size(file) / 2);
    EXPECT_EQ(readImageAttribute(file.string(), "penumbra:job"), stamp) << name << ": the header survives the cut";
    EXPECT_FALSE(imageComplete(file.string())) << name;
  }
  const CliResult r = runCli(batch);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("2 jobs: 2 rendered, 0 up to date"), std::string::npos) << r.err;
}

// batch -o DIR makes its folder: when it cannot (a full disk, a file in the way),
// one line and exit 2, not an internal error.
TEST(FullDisk, ABatchFolderThatCannotBeMadeIsOneLine) {
  ScratchDir dir;
  const std::string scene = dir.write("floor.json", kFloorScene).string();
  const fs::path folder = dir.write("file", "") / "out";
  const CliResult r = runCli("batch " + quote(scene) + " -q -o " + quote(folder.string()));
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(r.err.rfind("penumbra: " + folder.string() + ": cannot create the output folder (", 0), 0u) << r.err;
  EXPECT_EQ(occurrences(r.err, "\n"), 1u) << r.err;
}

}  // namespace penumbra::hard
