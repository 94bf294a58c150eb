// Start-up pays for no library a command does not use: the image module, and the
// OpenImageIO codecs behind it, load only when an image is decoded; writing a PNG or
// EXR loads only the encoder module (libpng, OpenEXR).
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

TEST_F(Startup, ARenderWritingPngOrExrLoadsNoImageLibrary) {
  for (const std::string format : {"png", "exr"}) {
    const fs::path image = dir_ / ("floor." + format);
    const CliResult r = runTraced(PENUMBRA_BINARY, "render " + scene() + " -q -o " + quote(image.string()));
    ASSERT_EQ(r.exitCode, 0) << r.err.substr(0, 2000);
    EXPECT_TRUE(fs::exists(image)) << format;
    EXPECT_NE(r.err.find(kImageEncoderModuleName), std::string::npos) << format;
    EXPECT_EQ(r.err.find("libOpenImageIO"), std::string::npos) << format;
    EXPECT_EQ(r.err.find(kImageModuleName), std::string::npos) << format;
  }
}

TEST_F(Startup, ARenderLoadsTheModulesBesideTheBinary) {
  // A copy of the binary and modules elsewhere: the modules beside the binary are the
  // ones loaded, so an installed set needs no build folder. The second scene reads the
  // first one's image as a texture, which loads the image module.
  const fs::path bin = dir_ / "bin";
  fs::create_directories(bin);
  fs::copy_file(PENUMBRA_BINARY, bin / "penumbra");
  for (const char* module : {kImageModuleName, kImageEncoderModuleName})
    fs::copy_file(fs::path(PENUMBRA_BINARY).parent_path() / module, bin / module);
  const fs::path png = dir_ / "floor.png";
  const CliResult r = runTraced((bin / "penumbra").string(), "render " + scene() + " -q -o " + quote(png.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err.substr(0, 2000);
  EXPECT_TRUE(fs::exists(png));
  EXPECT_NE(r.err.find("file=" + (bin / kImageEncoderModuleName).string()), std::string::npos);

  std::string textured = kFloorScene;
  textured.replace(textured.find("\"objects\""), 0,
                   R"("materials": {"m": {"diffuse": 0.7, "texture": {"file": "floor.png"}}}, )");
  textured.replace(textured.find("]}]"), 3, R"(], "material": "m"}])");
  std::ofstream(dir_ / "textured.json") << textured;
  // The image module silences its library's stderr while it decodes, so the loader's
  // trace goes to a file (LD_DEBUG_OUTPUT appends the process id).
  const fs::path trace = dir_ / "ld";
  const CliResult t = runShell("LD_DEBUG=files LD_DEBUG_OUTPUT=" + quote(trace.string()) + " " +
                               quote((bin / "penumbra").string()) + " render " +
                               quote((dir_ / "textured.json").string()) + " -q -o " + quote((dir_ / "t.png").string()));
  ASSERT_EQ(t.exitCode, 0) << t.err;
  std::string loaded;
  for (const auto& entry : fs::directory_iterator(trace.parent_path())) {
    if (entry.path().filename().string().rfind("ld.", 0) != 0) continue;
    std::ifstream in(entry.path());
    loaded.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  EXPECT_NE(loaded.find("file=" + (bin / kImageModuleName).string()), std::string::npos);
  EXPECT_NE(loaded.find("libOpenImageIO"), std::string::npos);
}

}  // namespace
}  // namespace penumbra::hard
