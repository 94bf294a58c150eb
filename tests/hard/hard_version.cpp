// `penumbra --version` names the version, the commit and the build type; the file that
// carries them (cmake/build_info.cmake) says "unknown" outside git, marks a checkout
// with changed tracked files "-dirty", and is rewritten only when its text changes.
#include "hard_cli.h"

#include <gtest/gtest.h>
#include <regex>

namespace penumbra::hard {
namespace {

// Runs the generator on `source` and returns the file it wrote.
std::string generate(const fs::path& source, const fs::path& output) {
  const CliResult r = runShell("cmake -DSOURCE_DIR=" + quote(source.string()) + " -DOUTPUT=" + quote(output.string()) +
                               " -DBUILD_TYPE=Debug -P " + quote(PENUMBRA_SOURCE_DIR "/cmake/build_info.cmake"));
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return testing::readFile(output);
}

TEST(Version, NamesTheVersionTheCommitAndTheBuildType) {
  const CliResult r = runCli("--version");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::smatch m;
  const std::regex form(R"(penumbra [0-9]+\.[0-9]+(\.[0-9]+)? \(commit (unknown|([0-9a-f]{7})(-dirty)?), )"
                        R"((Release|Debug|RelWithDebInfo|MinSizeRel)(, sanitize=[a-z,-]+)?(, fuzz)?\)\n)");
  ASSERT_TRUE(std::regex_match(r.out, m, form)) << r.out;
  // Built from this checkout: its HEAD (a binary older than HEAD is rebuilt with the test).
  const CliResult head = runShell("git -C " + quote(PENUMBRA_SOURCE_DIR) + " rev-parse --short=7 HEAD");
  if (head.exitCode == 0) {
    EXPECT_EQ(m[3].str() + "\n", head.out);
  }
}

TEST(Version, TheGeneratedFileSaysUnknownOutsideGitAndDirtyForChangedTrackedFiles) {
  if (runShell("(command -v git && command -v cmake)").exitCode != 0) GTEST_SKIP() << "needs git and cmake";
  const ScratchDir dir;
  fs::create_directories(dir / "src");
  const fs::path out = dir / "build_info.cpp";
  std::string text = generate(dir / "src", out);
  EXPECT_NE(text.find("buildCommit() { return \"unknown\"; }"), std::string::npos) << text;
  EXPECT_NE(text.find("buildType() { return \"Debug\"; }"), std::string::npos) << text;

  const std::string git = "git -C " + quote((dir / "src").string()) + " -c user.name=t -c user.email=t@t ";
  dir.write("src/a.txt", "one\n");
  ASSERT_EQ(runShell(git + "init -q && " + git + "add a.txt && " + git + "commit -qm one").exitCode, 0);
  const std::string hash = runShell(git + "rev-parse --short=7 HEAD").out.substr(0, 7);
  text = generate(dir / "src", out);
  EXPECT_NE(text.find("buildCommit() { return \"" + hash + "\"; }"), std::string::npos) << text;
  // Untracked files (a build folder) leave it clean; nothing changed, nothing written.
  dir.write("src/untracked.txt", "x\n");
  const auto written = fs::last_write_time(out);
  fs::last_write_time(out, written - std::chrono::hours(1));
  const auto marked = fs::last_write_time(out);
  EXPECT_EQ(generate(dir / "src", out), text);
  EXPECT_EQ(fs::last_write_time(out), marked) << "rewritten with the same text";
  dir.write("src/a.txt", "two\n");
  text = generate(dir / "src", out);
  EXPECT_NE(text.find("buildCommit() { return \"" + hash + "-dirty\"; }"), std::string::npos) << text;
}

}  // namespace
}  // namespace penumbra::hard
