// Contact sheets: drawn by the image module (each image resized in linear light,
// pasted into one canvas, labelled) and written as PNG by writeImage.
#include "io/contact_sheet.h"
#include "io/image_io.h"

#include "core/image_codec.h"

namespace penumbra {

std::string writeContactSheet(const std::string& png, const std::vector<SheetTile>& tiles) {
  if (tiles.empty()) return "";
  if (tiles.size() > kMaxSheetTiles) {
    return png + " not drawn: " + std::to_string(tiles.size()) + " runs, more than a sheet shows (" +
           std::to_string(kMaxSheetTiles) + ")";
  }
  std::vector<std::string> images;
  std::vector<std::vector<std::string>> labels;
  for (const SheetTile& t : tiles) {
    images.push_back(t.image);
    labels.push_back(t.lines);
  }
  Image sheet;
  const std::string problem = imageCodec().drawContactSheet(images, labels, sheet);
  if (!problem.empty()) return png + " not drawn: " + problem;
  writeImage(png, sheet);
  return "";
}

}  // namespace penumbra
