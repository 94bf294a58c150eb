// Temp files: the SIGINT/SIGTERM cleanup removes registered temp files and only
// them, then the process still dies of the signal; text writes are all or nothing,
// every legal name can be written, and the up-front path rule names each limit.
#include "core/error.h"
#include "io/temp_file.h"
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace penumbra;

namespace {

class TempFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "penumbra-temp-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir = pattern;
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string make(const std::string& name, const std::string& text) const {
    std::ofstream((dir / name).string(), std::ios::binary) << text;
    return (dir / name).string();
  }
  static std::string read(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path dir;
};

// Forks a child that registers `temp`, installs the cleanup and raises `sig`.
int dieOf(int sig, const std::string& temp, bool registered) {
  const pid_t child = fork();
  if (child == 0) {
    installTempFileCleanup();
    if (registered) {
      TempFileGuard guard(temp);
      std::raise(sig);
    }
    std::raise(sig);
    _exit(0);  // the signal should have ended us
  }
  int status = 0;
  waitpid(child, &status, 0);
  return status;
}

}  // namespace

TEST_F(TempFileTest, SignalRemovesTheRegisteredTempFileAndStillKills) {
  for (int sig : {SIGINT, SIGTERM}) {
    const std::string temp = make("out.tmp123-0.exr", "partial");
    const std::string target = make("out.exr", "old");
    const int status = dieOf(sig, temp, true);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status;
    EXPECT_FALSE(fs::exists(temp));
    EXPECT_EQ(read(target), "old");  // only the temp file goes
  }
}

// While a TermDeferral lives, the first SIGTERM only sets the flag (the temp file
// stays for its owner); a second one, or SIGINT, removes it and kills as before.
TEST_F(TempFileTest, ADeferredSigtermSetsTheFlagAndASecondOneStillKills) {
  for (int second : {SIGTERM, SIGINT}) {
    const std::string temp = make("out.tmp7-0.passes", "partial");
    const pid_t child = fork();
    if (child == 0) {
      installTempFileCleanup();
      TempFileGuard guard(temp);
      const TermDeferral deferring;
      if (terminationRequested()) _exit(3);
      std::raise(SIGTERM);
      if (!terminationRequested() || !fs::exists(temp)) _exit(4);
      std::raise(second);
      _exit(0);  // the second signal should have ended us
    }
    int status = 0;
    waitpid(child, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == second) << "status " << status;
    EXPECT_FALSE(fs::exists(temp));
  }
}

TEST_F(TempFileTest, UnregisteredFilesSurviveTheSignal) {
  const std::string keep = make("keep.tmp1-0.png", "not ours any more");
  const int status = dieOf(SIGINT, keep, false);
  EXPECT_TRUE(WIFSIGNALED(status)) << status;
  EXPECT_TRUE(fs::exists(keep));
  {
    TempFileGuard guard(keep);
  }  // released: a later signal must not remove it
  removeRegisteredTempFiles();
  EXPECT_TRUE(fs::exists(keep));
  TempFileGuard again(keep);
  removeRegisteredTempFiles();
  EXPECT_FALSE(fs::exists(keep));
}

TEST_F(TempFileTest, TextWritesReplaceWholeOrNotAtAll) {
  const std::string path = make("stats.json", "old");
  writeTextFileAtomic(path, "{\"new\": 1}\n");
  EXPECT_EQ(read(path), "{\"new\": 1}\n");
  EXPECT_THROW(writeTextFileAtomic((dir / "missing" / "s.json").string(), "x"), InputError);
  fs::create_directory(dir / "target_is_dir");
  EXPECT_THROW(writeTextFileAtomic((dir / "target_is_dir").string(), "x"), InputError);
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    ++entries;
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  }
  EXPECT_EQ(entries, 2u);
}

// Every name the directory allows can be written: the temp name gives up the end
// of a long stem (a 250-byte target plus ".tmpPID-N" would pass NAME_MAX).
// A process killed by SIGKILL leaves its temp file; a later process of the same pid
// (common in containers) must pass over that name, not fail on it every run.
TEST_F(TempFileTest, ALeftoverTempFileOfTheSamePidIsPassedOverAndKept) {
  const std::string target = (dir / "out.txt").string();
  const std::string probe = tempPathFor(target);  // takes counter c; the next write tries c + 1 first
  const size_t dash = probe.rfind('-'), dot = probe.rfind('.');
  const unsigned next = std::stoul(probe.substr(dash + 1, dot - dash - 1)) + 1;
  std::vector<std::string> leftovers;
  for (unsigned c = next; c < next + 3; ++c) {
    leftovers.push_back(make(fs::path(probe.substr(0, dash + 1) + std::to_string(c) + ".txt").filename().string(),
                             "left by a killed process"));
  }
  writeTextFileAtomic(target, "new");
  EXPECT_EQ(read(target), "new");
  for (const std::string& l : leftovers) EXPECT_EQ(read(l), "left by a killed process") << l;
}

TEST_F(TempFileTest, LongestLegalNamesAreWritten) {
  for (const std::string& name :
       {std::string(250, 'n') + ".json", std::string(255, 'x'), std::string(251, 'e') + ".exr"}) {
    const std::string path = (dir / name).string();
    EXPECT_EQ(outputPathProblem(path), "") << name.size();
    writeTextFileAtomic(path, "whole");
    EXPECT_EQ(read(path), "whole");
  }
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos);
}

// The up-front rule names each limit; a path that passes it is written.
TEST_F(TempFileTest, OutputPathProblemNamesEachLimit) {
  auto problem = [](const fs::path& p) { return outputPathProblem(p.string()); };
  EXPECT_EQ(problem(dir / "fine.json"), "");
  EXPECT_EQ(problem(dir / std::string(256, 'n')), "its name is 256 bytes, the directory allows 255");
  EXPECT_EQ(problem(dir / "missing" / "a.json"), "directory '" + (dir / "missing").string() + "' does not exist");
  EXPECT_EQ(problem(dir), "it is a directory");
  EXPECT_EQ(problem(""), "empty path");
  EXPECT_NE(problem(dir / std::string(5000, 'p')).find("its path is"), std::string::npos);
  // A folder whose path leaves room for a short name but not for its temp file's.
  fs::path deep = dir;
  while (deep.string().size() < 4060) deep /= std::string(std::min<size_t>(200, 4060 - deep.string().size()), 'd');
  fs::create_directories(deep);
  const fs::path target = deep / std::string(4080 - deep.string().size(), 't');
  EXPECT_NE(problem(target).find("its temp file's path would be"), std::string::npos) << problem(target);
}
