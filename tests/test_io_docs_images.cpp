// Images committed in docs/ carry no path of the machine that made them: no
// string attribute of any docs/*.png names an absolute path (make gallery-docs
// and the plots strip them; a hand-made image that does not fails here).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <filesystem>

namespace {

namespace fs = std::filesystem;

TEST(DocsImages, NoAttributeNamesAnAbsolutePath) {
  size_t images = 0;
  for (const auto& e : fs::directory_iterator(fs::path(PENUMBRA_SOURCE_DIR) / "docs")) {
    if (e.path().extension() != ".png") continue;
    ++images;
    auto in = OIIO::ImageInput::open(e.path().string());
    ASSERT_TRUE(in) << e.path();
    for (const OIIO::ParamValue& p : in->spec().extra_attribs) {
      if (p.type() != OIIO::TypeString) continue;
      const std::string value = p.get_string();
      for (const char* root : {"/work/", "/home/", "/root/", "/tmp/", "/Users/"}) {
        EXPECT_EQ(value.find(root), std::string::npos) << e.path().filename() << " " << p.name() << ": " << value;
      }
    }
    in->close();
  }
  EXPECT_GE(images, 3u) << "docs/ should hold the showcase, the contact sheet and the plots";
}

}  // namespace
