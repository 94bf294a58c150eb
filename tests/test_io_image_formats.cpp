// Every format penumbra reads, one file each through the image module: readImage gives
// the values OpenImageIO itself decodes (sRGB-decoded for integer files), the texture
// check accepts the file, and the header reader sees its size and channels.
#include "core/image_codec.h"
#include "io/image_io.h"
#include "io/texture_check.h"
#include "support/scratch_dir.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace penumbra;

namespace {

struct Format {
  const char* ext;
  OIIO::TypeDesc type;  // the values written
};

class ImageFormats : public ::testing::TestWithParam<Format> {};

double srgbDecoded(double e) { return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4); }

TEST_P(ImageFormats, ReadAsOpenImageIODecodesThem) {
  const Format f = GetParam();
  const penumbra::testing::ScratchDir dir;
  const std::string path = (dir / (std::string("rgb.") + f.ext)).string();
  constexpr int w = 5, h = 3;
  std::vector<float> written(size_t(w) * h * 3);
  for (size_t i = 0; i < written.size(); ++i) written[i] = float((i * 37) % 101) / 100.0f;
  {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << OIIO::geterror();
    ASSERT_TRUE(out->open(path, OIIO::ImageSpec(w, h, 3, f.type)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, written.data()));
    ASSERT_TRUE(out->close());
  }
  // What the file holds, as OpenImageIO decodes it (JPEG and RGBE are lossy).
  std::vector<float> stored(written.size());
  {
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << OIIO::geterror();
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, stored.data()));
  }
  const bool integer = f.type == OIIO::TypeDesc::UINT8;

  const Image image = readImage(path);
  ASSERT_EQ(image.width, w);
  ASSERT_EQ(image.height, h);
  for (size_t i = 0; i < stored.size(); ++i) {
    const double expected = integer ? srgbDecoded(stored[i]) : stored[i];
    EXPECT_NEAR(image.pixels[i / 3][int(i % 3)], expected, 1e-6) << f.ext << " value " << i;
  }

  EXPECT_EQ(textureFileProblem(path), "") << f.ext;
  std::string error;
  const auto reader = imageCodec().open(path, error);
  ASSERT_TRUE(reader) << error;
  EXPECT_EQ(reader->info().width, w);
  EXPECT_EQ(reader->info().height, h);
  EXPECT_EQ(reader->info().nchannels, 3);
  std::vector<float> rows(stored.size());
  ASSERT_TRUE(reader->readFloat(0, w, 0, h, 0, 3, rows.data(), kAutoStride, kAutoStride)) << reader->error();
  EXPECT_EQ(rows, stored) << f.ext;
}

INSTANTIATE_TEST_SUITE_P(Each, ImageFormats,
                         ::testing::Values(Format{"png", OIIO::TypeDesc::UINT8}, Format{"jpg", OIIO::TypeDesc::UINT8},
                                           Format{"tif", OIIO::TypeDesc::UINT8}, Format{"exr", OIIO::TypeDesc::HALF},
                                           Format{"hdr", OIIO::TypeDesc::FLOAT}),
                         [](const ::testing::TestParamInfo<Format>& p) { return std::string(p.param.ext); });

}  // namespace
