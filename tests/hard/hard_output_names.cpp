// Output names at the system's limits, through the binary: a name the directory
// allows is written (its temp file gives up the end of its stem), a longer one is
// refused in one line before any photon, for images, --stats and batch outputs.
#include "hard/hard_cli.h"
#include "io/image_io.h"
#include "support/scoped_env.h"
#include <gtest/gtest.h>

namespace penumbra::hard {

using testing::readFile;
using testing::ScopedEnv;

// 250-byte names are legal: the temp file gives up the end of its stem to fit,
// and the image and the stats are written (they failed after the whole render).
TEST(OutputNames, LongLegalNamesAreWritten) {
  ScratchDir dir;
  const std::string scene = dir.write("floor.json", kFloorScene).string();
  const fs::path image = dir / (std::string(246, 'i') + ".png"), stats = dir / (std::string(245, 's') + ".json");
  const CliResult r = runCli("render " + quote(scene) + " -q -o " + quote(image.string()) + " --stats " +
                             quote(stats.string()));
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(imageComplete(image.string()));
  EXPECT_NE(readFile(stats).find("\"image\""), std::string::npos);
  EXPECT_EQ(dir.tempFiles(), 0);
}

// A name longer than the directory allows is one line and exit 2 before any work:
// with every phase's progress shown, a render would print more than that line.
TEST(OutputNames, NamesTooLongAreRefusedBeforeAnyPhoton) {
  ScratchDir dir;
  const ScopedEnv everyPhase("PENUMBRA_PROGRESS_AFTER", "0");
  const std::string scene = dir.write("floor.json", kFloorScene).string();
  const std::string image = (dir / (std::string(252, 'i') + ".png")).string();
  const std::string stats = (dir / (std::string(251, 's') + ".json")).string();
  const fs::path jobs = dir.write("jobs.json", "{\"jobs\": [{\"scene\": \"" + scene + "\", \"output\": \"" +
                                                   image + "\"}]}");
  const std::string ok = quote((dir / "ok.png").string());
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"render " + quote(scene) + " -o " + quote(image), image + ": cannot write image: its name is 256 bytes"},
      {"render " + quote(scene) + " -o " + ok + " --stats " + quote(stats),
       "--stats " + stats + ": cannot write: its name is 256 bytes"},
      {"batch " + quote(jobs.string()), image + ": cannot write image: its name is 256 bytes"},
  };
  for (const auto& [args, message] : cases) {
    const CliResult r = runCli(args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_EQ(occurrences(r.err, "\n"), 1u) << "more than the refusal: something ran\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "ok.png"));
  EXPECT_EQ(dir.tempFiles(), 0);
}

}  // namespace penumbra::hard
