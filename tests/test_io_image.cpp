// Image I/O: exact sRGB encoding, half-precision EXR round trips, metadata, that
// failed or successful writes leave no temp files and no partial targets, that a
// file cut short is not whole, and the error metrics of one image against another.
#include "core/error.h"
#include "io/image_compare.h"
#include "io/image_io.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <Imath/half.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <set>
#include <stdexcept>

namespace fs = std::filesystem;
using namespace penumbra;

namespace {

// A fresh, empty directory per test, removed afterwards.
class ImageIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "penumbra-image-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir = pattern;
  }
  void TearDown() override { fs::remove_all(dir); }
  std::set<std::string> listing() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename());
    return names;
  }
  std::string file(const std::string& name) const { return (dir / name).string(); }
  fs::path dir;
};

double srgbDecode(double e) { return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4); }

std::vector<uint8_t> readBytes(const std::string& path, int& channels) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  channels = spec.nchannels;
  std::vector<uint8_t> bytes(spec.image_pixels() * channels);
  EXPECT_TRUE(in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, bytes.data()));
  return bytes;
}

Image rowImage(const std::vector<float>& values) {
  Image image(static_cast<int>(values.size()), 1);
  for (size_t i = 0; i < values.size(); ++i) image.pixels[i] = Color(values[i]);
  return image;
}

}  // namespace

TEST_F(ImageIoTest, PngEncodesTheStandardSrgbCurveRoundedToNearest) {
  const float inf = kInf;
  // 0.0031308 sits at the curve's linear/power boundary: 12.92 * it = 0.04045 -> 10.3 -> 10.
  // +Inf is brighter than white, not black; -Inf is black.
  Image image = rowImage({0.0f, 0.5f, 1.0f, 0.0031308f, 0.001f, 0.2f, 2.0f, -1.0f, -inf, inf});
  writeImage(file("ramp.png"), image);
  int channels = 0;
  std::vector<uint8_t> bytes = readBytes(file("ramp.png"), channels);
  ASSERT_EQ(channels, 3);
  const uint8_t expected[] = {0, 188, 255, 10, 3, 124, 255, 0, 0, 255};
  for (size_t i = 0; i < std::size(expected); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(bytes[i * 3 + c], expected[i]) << "pixel " << i;
}

TEST_F(ImageIoTest, PngRoundTripsEvery8BitCode) {
  // Each code's exact linear value must encode back to the same code, and
  // readImage must linearise it with the same curve.
  Image image(256, 1);
  for (int k = 0; k < 256; ++k) image.pixels[k] = Color(static_cast<float>(srgbDecode(k / 255.0)));
  writeImage(file("codes.png"), image);
  int channels = 0;
  std::vector<uint8_t> bytes = readBytes(file("codes.png"), channels);
  for (int k = 0; k < 256; ++k) EXPECT_EQ(bytes[k * 3], k);
  Image back = readImage(file("codes.png"));
  ASSERT_EQ(back.width, 256);
  for (int k = 0; k < 256; ++k) EXPECT_NEAR(back.pixels[k].g, image.pixels[k].g, 1e-6f) << k;
}

TEST_F(ImageIoTest, ExrRoundTripIsExactToHalfPrecision) {
  Image image(3, 2);
  const float values[] = {0.0f, 0.1f, 0.5f, 1.0f, 3.14159f, 1234.5f, 0.25f, 1e-3f, 42.0f};
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = Color(values[i % 9], values[(i + 3) % 9], values[(i + 6) % 9]);
  writeImage(file("linear.exr"), image);
  Image back = readImage(file("linear.exr"));
  ASSERT_EQ(back.width, 3);
  ASSERT_EQ(back.height, 2);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(back.pixels[i][c], static_cast<float>(Imath::half(image.pixels[i][c])));
}

TEST_F(ImageIoTest, InfinitiesAndOverflowClampToTheHalfRange) {
  // +Inf and values past half range are the brightest half, not black and not +Inf;
  // radiance is never negative, so -Inf and negatives write 0.
  Image image = rowImage({kInf, -kInf, 1e9f, 65504.0f, -3.0f, 70000.0f});
  writeImage(file("bright.exr"), image);
  Image back = readImage(file("bright.exr"));
  const float expected[] = {65504.0f, 0.0f, 65504.0f, 65504.0f, 0.0f, 65504.0f};
  for (size_t i = 0; i < std::size(expected); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(back.pixels[i][c], expected[i]) << "pixel " << i;
}

TEST_F(ImageIoTest, NanIsAnInternalErrorAndWritesNothing) {
  // The render drops non-finite samples: a NaN reaching the writer is a bug, thrown
  // before any temp file exists, and an old output stays as it was.
  for (const char* name : {"old.png", "old.exr"}) {
    writeImage(file(name), rowImage({0.25f, 0.5f}));
    const auto before = fs::file_size(file(name));
    const auto stamp = fs::last_write_time(file(name));
    Image image = rowImage({0.5f, 1.0f, 0.0f});
    image.pixels[2].g = std::numeric_limits<float>::quiet_NaN();
    try {
      writeImage(file(name), image);
      ADD_FAILURE() << name << ": a NaN was written";
    } catch (const InputError&) {
      ADD_FAILURE() << name << ": a NaN is not the user's error";
    } catch (const std::logic_error& e) {
      EXPECT_NE(std::string(e.what()).find("pixel (2, 0)"), std::string::npos) << e.what();
    }
    EXPECT_EQ(fs::file_size(file(name)), before);
    EXPECT_EQ(fs::last_write_time(file(name)), stamp);
  }
  EXPECT_EQ(listing(), (std::set<std::string>{"old.png", "old.exr"}));
}

TEST_F(ImageIoTest, ExtensionIsCaseInsensitive) {
  writeImage(file("upper.PNG"), rowImage({0.5f}));
  writeImage(file("upper.Exr"), rowImage({0.5f}));
  EXPECT_EQ(listing(), (std::set<std::string>{"upper.PNG", "upper.Exr"}));
}

TEST_F(ImageIoTest, UnsupportedExtensionThrowsAndWritesNothing) {
  try {
    writeImage(file("out.xyz"), rowImage({0.5f}));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              file("out.xyz") + ": unsupported image extension '.xyz' (use .png or .exr)");
  }
  EXPECT_THROW(writeImage(file("noext"), rowImage({0.5f})), InputError);
  EXPECT_TRUE(listing().empty());
}

TEST_F(ImageIoTest, SuccessLeavesOnlyTheTarget) {
  writeImage(file("a.png"), rowImage({0.5f}));
  writeImage(file("a.png"), rowImage({1.0f}));  // replacing an existing file
  writeImage(file("b.exr"), rowImage({0.5f}));
  EXPECT_EQ(listing(), (std::set<std::string>{"a.png", "b.exr"}));
  EXPECT_FLOAT_EQ(readImage(file("a.png")).pixels[0].r, 1.0f);
}

TEST_F(ImageIoTest, MissingDirectoryFailsCleanly) {
  std::string target = (dir / "missing" / "out.png").string();
  try {
    writeImage(target, rowImage({0.5f}));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(target + ": cannot write image: ", 0), 0u) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
  EXPECT_TRUE(listing().empty());
}

TEST_F(ImageIoTest, FailedRenameRemovesTheTempFile) {
  // The temp file is written fine, but a directory occupies the target name.
  fs::create_directory(dir / "taken.png");
  EXPECT_THROW(writeImage(file("taken.png"), rowImage({0.5f})), InputError);
  EXPECT_EQ(listing(), (std::set<std::string>{"taken.png"}));
  EXPECT_TRUE(fs::is_directory(dir / "taken.png"));
}

TEST_F(ImageIoTest, MetadataIsReadableBack) {
  const ImageMetadata metadata{{"penumbra:scene", "scenes/cornell.json"},
                               {"penumbra:photons", "5000000"}};
  for (const std::string name : {"meta.png", "meta.exr"}) {
    writeImage(file(name), rowImage({0.5f}), metadata);
    auto in = OIIO::ImageInput::open(file(name));
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.get_string_attribute("Software"), "penumbra") << name;
    EXPECT_EQ(spec.get_string_attribute("penumbra:scene"), "scenes/cornell.json") << name;
    EXPECT_EQ(spec.get_string_attribute("penumbra:photons"), "5000000") << name;
  }
}

TEST_F(ImageIoTest, ReadReplicatesGreyAndDropsAlpha) {
  auto writeRaw = [&](const std::string& name, int channels, const std::vector<uint8_t>& bytes) {
    auto out = OIIO::ImageOutput::create(file(name));
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(1, 1, channels, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // store these bytes as they are
    ASSERT_TRUE(out->open(file(name), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, bytes.data()));
    out->close();
  };
  writeRaw("grey.png", 1, {188});
  writeRaw("rgba.png", 4, {255, 188, 0, 7});
  Image grey = readImage(file("grey.png"));
  EXPECT_NEAR(grey.pixels[0].r, 0.5f, 5e-3f);  // 188 is 0.5 to within 8-bit steps
  EXPECT_EQ(grey.pixels[0].r, grey.pixels[0].g);
  EXPECT_EQ(grey.pixels[0].r, grey.pixels[0].b);
  Image rgba = readImage(file("rgba.png"));
  EXPECT_FLOAT_EQ(rgba.pixels[0].r, 1.0f);
  EXPECT_NEAR(rgba.pixels[0].g, 0.5f, 5e-3f);  // colour is not premultiplied by alpha
  EXPECT_FLOAT_EQ(rgba.pixels[0].b, 0.0f);
}

TEST_F(ImageIoTest, ReadingAMissingOrBrokenFileThrows) {
  EXPECT_THROW(readImage(file("nope.png")), InputError);
  std::FILE* f = std::fopen(file("broken.png").c_str(), "w");
  std::fputs("not a png", f);
  std::fclose(f);
  EXPECT_THROW(readImage(file("broken.png")), InputError);
}

// The up-to-date test's rule: a file missing any of its last bytes is not whole.
TEST_F(ImageIoTest, ImageCompleteNeedsEveryByte) {
  Image image(64, 48);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = Color(float(i % 97) / 97.0f, 0.5f, float(i % 13) / 13.0f);
  for (const std::string ext : {".png", ".exr"}) {
    const std::string whole = file("whole" + ext);
    writeImage(whole, image, {{"penumbra:job", "0123456789abcdef"}});
    EXPECT_TRUE(imageComplete(whole)) << ext;
    const auto size = fs::file_size(whole);
    for (const auto cut : {size - 1, size / 2}) {
      const std::string part = file("part" + ext);
      fs::copy_file(whole, part, fs::copy_options::overwrite_existing);
      fs::resize_file(part, cut);
      EXPECT_FALSE(imageComplete(part)) << ext << " cut to " << cut << " of " << size << " bytes";
    }
    EXPECT_FALSE(imageComplete(file("missing" + ext)));
  }
}

TEST(ImageCompare, KnownDifferences) {
  Image ref(10, 10), img(10, 10);
  for (Color& c : ref.pixels) c = Color(0.5f);
  img = ref;
  img.at(3, 4) = Color(1.5f);  // one pixel off by 1 in every channel
  const ImageError e = compareImages(img, ref);
  EXPECT_NEAR(e.rmse, std::sqrt(1.0 / 100.0), 1e-6);
  EXPECT_NEAR(e.relMse, 1.0 / (0.25 + 0.01) / 100.0, 1e-5);
  EXPECT_NEAR(e.worstRmse, 1.0, 1e-6);  // the worst 1% is that pixel
  EXPECT_NEAR(e.maxError, 1.0, 1e-6);
  EXPECT_NEAR(e.referenceMean, 0.5, 1e-6);
  // PSNR on display values: 1.5 clamps to 1, off by 0.5 in one pixel of 100.
  EXPECT_NEAR(e.psnr, 20.0 * std::log10(1.0 / std::sqrt(0.25 / 100.0)), 1e-3);
  EXPECT_THROW(compareImages(Image(3, 3), ref), InputError);

  // Left out (e.g. a pixel that sees an emitter): the figures are the other pixels'.
  // Pixel (3, 4) off by 1 is left out; (5, 5) off by 0.2 is one of the 99 kept.
  img.at(5, 5) = Color(0.7f);
  EmitterMask leaveOut(img.pixels.size(), 0);
  leaveOut[size_t(4 * img.width + 3)] = 1;
  const ImageError kept = compareImages(img, ref, leaveOut);
  EXPECT_NEAR(kept.rmse, std::sqrt(0.04 / 99.0), 1e-6);
  EXPECT_NEAR(kept.relMse, 0.04 / (0.25 + 0.01) / 99.0, 1e-5);
  EXPECT_NEAR(kept.worstRmse, 0.2, 1e-6);  // the worst one of the 99 (1%, at least one)
  EXPECT_NEAR(kept.psnr, 20.0 * std::log10(1.0 / std::sqrt(0.04 / 99.0)), 1e-3);
}
