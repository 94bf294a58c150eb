// Start-up pays for no library a command does not use: the image module, and the
// OpenImageIO codecs behind it, load only when an image is decoded or encoded.
#include "core/image_codec.h"
#include "hard_cli.h"

#include <gtest/gtest.h>

namespace penumbra::hard {
namespace {

// The binary at `binary` run with LD_DEBUG=files: the loader names every library it
// opens on stderr ("file=libOpenImageIO.so.2.4 [0];  needed by ...").
CliResult runTraced(const std::string& binary, const std::string& args) {
  return runShell("LD_DEBUG=files " + quote(binary) + " " + args + " </dev/null");
}

class Startup : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "floor.json") << kFloorScene;
  }
  ScratchDir dir_;
  std::string scene() const { return quote((dir_ / "floor.json").string()); }
};

TEST_F(Startup, VersionPlanAndCheckLoadNoImageLibrary) {
  for (const std::string& args : {std::string("--version"), "plan " + scene(), "check " + scene()}) {
    const CliResult r = runTraced(PENUMBRA_BINARY, args);
    EXPECT_EQ(r.exitCode, 0) << args << "\n" << r.err.substr(0, 2000);
    EXPECT_EQ(r.err.find("libOpenImageIO"), std::string::npos) << args;
    EXPECT_EQ(r.err.find(kImageModuleName), std::string::npos) << args;
  }
}

TEST_F(Startup, ABatchRerunWithEverythingUpToDateLoadsNoImageLibrary) {
  for (const std::string format : {"png", "exr"}) {
    const fs::path out = dir_ / format;
    const std::string args = "batch " + scene() + " -q --format " + format + " -o " + quote(out.string());
    const CliResult first = runCli(args);
    ASSERT_EQ(first.exitCode, 0) << first.err;
    const fs::path image = out / ("floor." + format);
    ASSERT_TRUE(fs::exists(image)) << format;
    const auto written = fs::last_write_time(image);
    const CliResult rerun = runTraced(PENUMBRA_BINARY, args);
    EXPECT_EQ(rerun.exitCode, 0) << format;
    EXPECT_EQ(fs::last_write_time(image), written) << format << ": rendered again";
    EXPECT_EQ(rerun.err.find("libOpenImageIO"), std::string::npos) << format;
  }
}

TEST_F(Startup, ARenderLoadsTheModuleBesideTheBinary) {
  // A copy of the binary and module elsewhere: the module beside the binary is the one
  // loaded, so an installed pair needs no build folder.
  const fs::path bin = dir_ / "bin";
  fs::create_directories(bin);
  fs::copy_file(PENUMBRA_BINARY, bin / "penumbra");
  fs::copy_file(fs::path(PENUMBRA_BINARY).parent_path() / kImageModuleName, bin / kImageModuleName);
  const fs::path png = dir_ / "floor.png";
  const CliResult r = runTraced((bin / "penumbra").string(), "render " + scene() + " -q -o " + quote(png.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err.substr(0, 2000);
  EXPECT_TRUE(fs::exists(png));
  EXPECT_NE(r.err.find("file=" + (bin / kImageModuleName).string()), std::string::npos);
  EXPECT_NE(r.err.find("libOpenImageIO"), std::string::npos);
}

}  // namespace
}  // namespace penumbra::hard
