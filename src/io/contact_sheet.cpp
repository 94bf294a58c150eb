// Contact sheets through OIIO's ImageBufAlgo: each image resized in linear light,
// pasted into one linear canvas, labelled with render_text in DejaVu Sans (Debian's
// fonts-dejavu-core, which make deps installs), and written as PNG by writeImage.
#include "io/contact_sheet.h"
#include "io/image_io.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <algorithm>
#include <cmath>
#include <filesystem>

namespace penumbra {

namespace {

constexpr int kTileWidth = 192, kColumns = 8, kLabelHeight = 34, kGap = 6, kFontSize = 12;
constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

}  // namespace

std::string writeContactSheet(const std::string& png, const std::vector<SheetTile>& tiles) {
  if (tiles.empty()) return "";
  if (tiles.size() > kMaxSheetTiles) {
    return png + " not drawn: " + std::to_string(tiles.size()) + " runs, more than a sheet shows (" +
           std::to_string(kMaxSheetTiles) + ")";
  }
  if (!std::filesystem::exists(kFont)) return png + " not drawn: no font for its labels (make deps installs fonts-dejavu-core)";
  std::vector<OIIO::ImageBuf> thumbs;
  int tileHeight = 1;
  for (const SheetTile& t : tiles) {
    OIIO::ImageBuf in(t.image);
    if (!in.read(0, 0, 0, 3, true, OIIO::TypeDesc::FLOAT)) return png + " not drawn: cannot read " + t.image;
    const OIIO::ImageSpec& spec = in.spec();
    const int h = std::max(1, int(std::lround(double(kTileWidth) * spec.height / std::max(1, spec.width))));
    thumbs.push_back(OIIO::ImageBufAlgo::resize(in, "", 0.0f, OIIO::ROI(0, kTileWidth, 0, h, 0, 1, 0, 3)));
    tileHeight = std::max(tileHeight, h);
  }
  const int columns = std::min<int>(kColumns, int(tiles.size()));
  const int rows = int((tiles.size() + size_t(columns) - 1) / size_t(columns));
  const int cellW = kTileWidth + kGap, cellH = tileHeight + kLabelHeight + kGap;
  OIIO::ImageBuf sheet(OIIO::ImageSpec(columns * cellW + kGap, rows * cellH + kGap, 3, OIIO::TypeDesc::FLOAT));
  OIIO::ImageBufAlgo::fill(sheet, {0.02f, 0.02f, 0.02f});
  const float white[] = {1.0f, 1.0f, 1.0f};
  for (size_t i = 0; i < tiles.size(); ++i) {
    const int x = kGap + int(i % size_t(columns)) * cellW, y = kGap + int(i / size_t(columns)) * cellH;
    OIIO::ImageBufAlgo::paste(sheet, x, y, 0, 0, thumbs[i]);
    for (size_t l = 0; l < tiles[i].lines.size() && l < 2; ++l) {
      const int baseline = y + tileHeight + kFontSize + 2 + int(l) * (kFontSize + 3);
      if (!OIIO::ImageBufAlgo::render_text(sheet, x, baseline, tiles[i].lines[l], kFontSize, kFont, white)) {
        return png + " not drawn: cannot draw its labels: " + sheet.geterror();
      }
    }
  }
  Image out(sheet.spec().width, sheet.spec().height);
  sheet.get_pixels(OIIO::ROI(0, out.width, 0, out.height, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, out.pixels.data());
  writeImage(png, out);
  return "";
}

}  // namespace penumbra
