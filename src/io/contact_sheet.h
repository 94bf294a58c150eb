// A contact sheet: every image of a sweep as a labelled thumbnail on one PNG, so a
// user sees what an error figure looks like next to its settings and time.
#pragma once
#include <string>
#include <vector>

namespace penumbra {

struct SheetTile {
  std::string image;               // a linear image file OpenImageIO reads (the run's EXR)
  std::vector<std::string> lines;  // its label, one or two short lines under it
};

// Sheets above this many tiles are not drawn (a note says so): they would not fit a screen.
inline constexpr size_t kMaxSheetTiles = 256;

// Writes `png` (tiles left to right, up to 8 a row, each 192 pixels wide) through the
// PNG writer's temp file. Returns "" on success, else one line saying why no sheet
// (too many tiles, an unreadable image, no font for the labels).
std::string writeContactSheet(const std::string& png, const std::vector<SheetTile>& tiles);

}  // namespace penumbra
