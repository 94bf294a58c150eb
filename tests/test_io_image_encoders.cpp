// The encoder module (libpng, OpenEXR) against OpenImageIO's writers: the same spec and
// pixels give the same bytes, headers and pixels alike, for every layout penumbra writes.
#include "core/image_codec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace penumbra {
namespace {

std::vector<unsigned char> encodedBy(bool encoderModule, const std::string& path, const EncodeSpec& spec,
                                     const void* pixels) {
  std::vector<unsigned char> bytes;
  const std::string problem = encoderModule ? imageEncoder().encode(path, spec, pixels, bytes)
                                            : imageCodec().encode(path, spec, pixels, bytes);
  EXPECT_EQ(problem, "") << path;
  return bytes;
}

void expectSameBytes(const std::string& path, const EncodeSpec& spec, const void* pixels) {
  ASSERT_TRUE(imageEncoder().handles(path, spec)) << path;
  const auto ours = encodedBy(true, path, spec, pixels), library = encodedBy(false, path, spec, pixels);
  ASSERT_FALSE(ours.empty());
  EXPECT_EQ(ours.size(), library.size()) << path;
  EXPECT_TRUE(ours == library) << path;
}

EncodeSpec specOf(int width, int height, int channels, PixelType file, PixelType given) {
  EncodeSpec s;
  s.width = width;
  s.height = height;
  s.nchannels = channels;
  s.fileType = file;
  s.given = given;
  return s;
}

// Noise that compresses poorly, so every row filter and several IDAT chunks are used.
std::vector<float> ramp(size_t n, float scale) {
  std::vector<float> v(n);
  uint32_t state = 12345u;
  for (size_t i = 0; i < n; ++i) {
    state = state * 1664525u + 1013904223u;
    v[i] = scale * (float(i % 97) / 97.0f + float(state >> 8) / float(1u << 24) * 0.25f);
  }
  return v;
}

TEST(ImageEncoders, PngMatchesTheImageLibrarysBytes) {
  EncodeSpec spec = specOf(300, 170, 3, PixelType::UInt8, PixelType::UInt8);
  spec.attributes = {{"oiio:ColorSpace", "sRGB"}, {"Software", "penumbra"}, {"penumbra:job", "abc"},
                     {"penumbra:exposure", "", 1.5f, true}};
  std::vector<uint8_t> pixels(size_t(300) * 170 * 3);
  const std::vector<float> noise = ramp(pixels.size(), 255.0f / 1.25f);
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = uint8_t(noise[i]);
  expectSameBytes("a.png", spec, pixels.data());
  EncodeSpec grey = specOf(7, 5, 1, PixelType::UInt8, PixelType::UInt8);
  expectSameBytes("b.PNG", grey, pixels.data());
}

TEST(ImageEncoders, ExrMatchesTheImageLibrarysBytes) {
  const std::vector<float> pixels = ramp(size_t(64) * 40 * 10, 3.0f);
  EncodeSpec half = specOf(64, 40, 3, PixelType::Half, PixelType::Float);
  // A fixed date: the library stamps the time of writing otherwise.
  half.attributes = {{"oiio:ColorSpace", "Linear"}, {"Software", "penumbra"}, {"DateTime", "2020:01:02 03:04:05"},
                     {"penumbra:plan", "{\"a\": 1}"}, {"penumbra:weight", "", 0.25f, true}};
  expectSameBytes("a.exr", half, pixels.data());

  // A layered file: half beauty, float depth with its coverage as A.
  EncodeSpec layered = specOf(64, 40, 7, PixelType::Float, PixelType::Float);
  layered.channelNames = {"beauty.R", "beauty.G", "beauty.B", "depth.R", "depth.G", "depth.B", "depth.A"};
  layered.channelTypes = {PixelType::Half, PixelType::Half, PixelType::Half, PixelType::Float,
                          PixelType::Float, PixelType::Float, PixelType::Float};
  layered.attributes = half.attributes;
  expectSameBytes("b.exr", layered, pixels.data());

  // A part of a frame with alpha: its data window inside the display window.
  EncodeSpec part = specOf(20, 10, 4, PixelType::Float, PixelType::Float);
  part.x = 30;
  part.y = 17;
  part.fullWidth = 64;
  part.fullHeight = 40;
  part.alphaChannel = 3;
  part.channelNames = {"R", "G", "B", "A"};
  part.attributes = half.attributes;
  expectSameBytes("c.exr", part, pixels.data());
}

TEST(ImageEncoders, EncodedFilesReadBackAsTheirPixels) {
  const std::vector<float> pixels = ramp(size_t(16) * 8 * 3, 2.0f);
  EncodeSpec spec = specOf(16, 8, 3, PixelType::Float, PixelType::Float);
  std::vector<unsigned char> bytes;
  ASSERT_EQ(imageEncoder().encode("x.exr", spec, pixels.data(), bytes), "");
  const std::string path = ::testing::TempDir() + "/encoders_readback.exr";
  FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  std::fwrite(bytes.data(), 1, bytes.size(), f);
  std::fclose(f);
  std::string error;
  auto in = imageCodec().open(path, error);
  ASSERT_TRUE(in) << error;
  std::vector<float> back(pixels.size());
  ASSERT_TRUE(in->readFloat(0, 16, 0, 8, 0, 3, back.data(), kAutoStride, kAutoStride));
  EXPECT_EQ(back, pixels);  // float channels: exact
}

TEST(ImageEncoders, WhatTheyDoNotWriteIsLeftToTheImageLibrary) {
  EncodeSpec rgba = specOf(4, 4, 4, PixelType::UInt8, PixelType::UInt8);
  rgba.alphaChannel = 3;  // the library un-premultiplies a PNG's colour
  EXPECT_FALSE(imageEncoder().handles("a.png", rgba));
  EXPECT_FALSE(imageEncoder().handles("a.tif", specOf(4, 4, 3, PixelType::UInt8, PixelType::UInt8)));
  EXPECT_TRUE(imageEncoder().handles("a.png", specOf(4, 4, 3, PixelType::UInt8, PixelType::UInt8)));
}

}  // namespace
}  // namespace penumbra
