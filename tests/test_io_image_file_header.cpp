// Headers read without the image library (io/image_file_header.h): the attributes
// penumbra writes into PNG and EXR files read back as OpenImageIO reads them, and an
// EXR cut anywhere in its last chunk is not whole.
#include "core/image.h"
#include "io/image_file_header.h"
#include "io/image_io.h"
#include "support/scratch_dir.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>

using namespace penumbra;
namespace fs = std::filesystem;

namespace {

std::string libraryAttribute(const std::string& path, const std::string& name) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << OIIO::geterror();
  return in ? in->spec().get_string_attribute(name) : "";
}

Image gradient(int w, int h, ImageContent content = ImageContent::Radiance) {
  Image image(w, h);
  image.content = content;
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = Color(float(i % 17) / 17.0f, 0.25f, 2.0f);
  if (content != ImageContent::Radiance) image.coverage.assign(image.pixels.size(), 1.0f);
  return image;
}

const ImageMetadata kMetadata = {{"penumbra:job", "0123456789abcdef"},
                                 {"penumbra:inputs", R"([["/a b/scene.json",1732,-46]])"},
                                 {"penumbra:empty", ""}};

TEST(ImageFileHeader, AttributesAsTheImageLibraryReadsThem) {
  const penumbra::testing::ScratchDir dir;
  for (const char* ext : {"png", "exr"}) {
    const std::string path = (dir / (std::string("out.") + ext)).string();
    writeImage(path, gradient(7, 5), kMetadata);
    for (const auto& [name, value] : kMetadata) {
      const std::optional<std::string> read = penumbraAttribute(path, name);
      ASSERT_TRUE(read.has_value()) << ext << " " << name;
      EXPECT_EQ(*read, value) << ext;
      EXPECT_EQ(*read, libraryAttribute(path, name)) << ext << " " << name;
    }
    // Not penumbra's, or not there: the image library answers.
    EXPECT_FALSE(penumbraAttribute(path, "Software").has_value()) << ext;
    EXPECT_FALSE(penumbraAttribute(path, "penumbra:missing").has_value()) << ext;
    for (const char* name : {"Software", "penumbra:missing", "penumbra:job"}) {
      EXPECT_EQ(readImageAttribute(path, name), libraryAttribute(path, name)) << ext << " " << name;
    }
  }
  EXPECT_EQ(readImageAttribute((dir / "missing.png").string(), "penumbra:job"), "");
}

TEST(ImageFileHeader, AnExrCutInItsLastChunkIsNotWhole) {
  const penumbra::testing::ScratchDir dir;
  // Half radiance (zip, 16 rows a chunk), float depth with coverage, and a layered file.
  const std::string half = (dir / "half.exr").string(), depth = (dir / "depth.exr").string(),
                    layered = (dir / "layered.exr").string();
  writeImage(half, gradient(9, 40), kMetadata);
  writeImage(depth, gradient(9, 33, ImageContent::Depth));
  writeLayeredExr(layered, {{"beauty", gradient(9, 17)}, {"depth", gradient(9, 17, ImageContent::Depth)}});
  for (const std::string& whole : {half, depth, layered}) {
    EXPECT_EQ(exrLastChunkWhole(whole), std::optional<bool>(true)) << whole;
    const auto size = fs::file_size(whole);
    for (const auto cut : {size - 1, size - 9, size / 2, size_t(9)}) {
      const std::string part = (dir / "part.exr").string();
      fs::copy_file(whole, part, fs::copy_options::overwrite_existing);
      fs::resize_file(part, cut);
      EXPECT_NE(exrLastChunkWhole(part), std::optional<bool>(true)) << whole << " cut to " << cut;
      EXPECT_FALSE(imageComplete(part)) << whole << " cut to " << cut;
    }
  }
  // Tiled EXRs and other formats are left to the image library.
  const std::string tiled = (dir / "tiled.exr").string();
  {
    OIIO::ImageSpec spec(8, 8, 3, OIIO::TypeDesc::HALF);
    spec.tile_width = spec.tile_height = 4;
    std::vector<float> pixels(8 * 8 * 3, 0.5f);
    auto out = OIIO::ImageOutput::create(tiled);
    ASSERT_TRUE(out && out->open(tiled, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
  }
  EXPECT_FALSE(exrLastChunkWhole(tiled).has_value());
  EXPECT_TRUE(imageComplete(tiled));
  const std::string png = (dir / "a.png").string();
  writeImage(png, gradient(3, 3));
  EXPECT_FALSE(exrLastChunkWhole(png).has_value());
}

}  // namespace
