// Tile arithmetic and the two options' parsing; 64-bit products, so a frame of any
// size splits without overflow.
#include "plan/frame_tiles.h"
#include "core/error.h"
#include <fmt/format.h>
#include <charconv>
#include <vector>

namespace penumbra {

std::pair<int, int> parseTile(const std::string& text) {
  int i = 0, n = 0;
  const char* end = text.data() + text.size();
  auto a = std::from_chars(text.data(), end, i);
  bool ok = a.ec == std::errc() && a.ptr != end && *a.ptr == '/';
  if (ok) {
    auto b = std::from_chars(a.ptr + 1, end, n);
    ok = b.ec == std::errc() && b.ptr == end;
  }
  if (!ok || n < 1 || i < 1 || i > n) {
    throw InputError("--tile: expected I/N with 1 <= I <= N (tile I of N, 1-based like --shard), got '" + text + "'");
  }
  return {i, n};
}

PixelBounds parsePixelBounds(const std::string& text) {
  std::vector<int> v;
  const char* at = text.data();
  const char* end = text.data() + text.size();
  bool ok = true;
  while (ok && v.size() < 5) {
    int x = 0;
    auto r = std::from_chars(at, end, x);
    ok = r.ec == std::errc();
    v.push_back(x);
    at = r.ptr;
    if (at == end) break;
    ok = ok && *at == ',';
    ++at;
  }
  if (!ok || v.size() != 4) {
    throw InputError("--pixel-bounds: expected x0,x1,y0,y1 (four integers), got '" + text + "'");
  }
  const PixelBounds b{v[0], v[1], v[2], v[3]};
  if (b.empty()) {
    throw InputError("--pixel-bounds: " + text + " is empty (pixels [x0,x1) x [y0,y1) need x0 < x1 and y0 < y1)");
  }
  return b;
}

PixelBounds tileBounds(int index, int count, int width, int height) {
  auto row = [&](int k) { return static_cast<int>(int64_t(k) * height / count); };
  return {0, width, row(index - 1), row(index)};
}

PixelBounds resolveTile(const TileRequest& request, int width, int height) {
  if (request.count > 0) {
    if (request.count > height) {
      throw InputError(fmt::format("--tile: {} tiles of a {}x{} frame: a tile is a band of rows, at most {}",
                                   request.count, width, height, height));
    }
    return tileBounds(request.index, request.count, width, height);
  }
  const PixelBounds& b = *request.bounds;
  if (b.x0 < 0 || b.y0 < 0 || b.x1 > width || b.y1 > height) {
    throw InputError(fmt::format("--pixel-bounds: {} is outside the {}x{} frame (x in [0,{}], y in [0,{}])",
                                 boundsText(b), width, height, width, height));
  }
  return b;
}

std::string boundsText(const PixelBounds& b) { return fmt::format("{},{},{},{}", b.x0, b.x1, b.y0, b.y1); }

}  // namespace penumbra
