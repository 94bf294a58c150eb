// The parts of a frame one job may render: tile I of N (bands of whole rows) or
// explicit pixel bounds, parsed and checked against the frame before any work.
#pragma once
#include "core/pixel_bounds.h"
#include <optional>
#include <string>
#include <utility>

namespace penumbra {

// --tile I/N (1-based, as --shard) or --pixel-bounds x0,x1,y0,y1.
struct TileRequest {
  int index = 0, count = 0;  // count > 0: tile `index` of `count`
  std::optional<PixelBounds> bounds;
};

// "2/4" -> {2, 4}; throws InputError unless 1 <= I <= N.
std::pair<int, int> parseTile(const std::string& text);
// "0,320,0,100" -> {0, 320, 0, 100}; throws InputError unless four integers with x0 < x1, y0 < y1.
PixelBounds parsePixelBounds(const std::string& text);

// Tile `index` (1-based) of `count` of a width x height frame: rows
// [(I-1) H / N, I H / N) of every column. Bands of whole rows: each part is one run of
// the file's scanlines, N needs no factoring, and the rows' counts differ by at most one.
PixelBounds tileBounds(int index, int count, int width, int height);

// The request's bounds in a width x height frame; throws InputError (naming the
// option) for a tile count above the rows or bounds outside the frame.
PixelBounds resolveTile(const TileRequest& request, int width, int height);

// "x0,x1,y0,y1", as --pixel-bounds reads it.
std::string boundsText(const PixelBounds& b);

}  // namespace penumbra
