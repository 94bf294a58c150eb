// The one rule for an image penumbra decodes itself, judged from its header before
// any pixel buffer is allocated: an OpenEXR header's sizes checked before OpenEXR
// reads it, each side and the pixel count bounded, and a file that really holds the
// rows its header claims. Also the band reader both decoders use.
#pragma once
#include "core/image_codec.h"
#include <cstdint>
#include <memory>
#include <string>

namespace penumbra {


// imageCodec().open after the checks a decoder skips (an OpenEXR header's
// attribute sizes against the file: OpenEXR allocates what one claims before reading
// it). Null with the problem, one line naming `label`, in `problem`.
std::unique_ptr<ImageReader> openImage(const std::string& path, const std::string& label, std::string& problem);

// What an image may claim: at most `maxPixels`, spelled `maxText` in a refusal
// ("the 8192x4096 an environment map may have"), and at most `maxSide` pixels a row or
// column: a row is one buffer, whole, in penumbra's bands and in the decoder (OpenEXR
// allocates a chunk of rows), so a side is bounded on its own.
struct ImageBound {
  uint64_t maxPixels = 0;
  std::string maxText;
  int maxSide = 0;
};

// "" when the header of `in` (opened from the file `label` names: "texture a.png")
// describes a flat image of 1..bound.maxSide pixels each way, at most bound.maxPixels,
// in tiles (if any) a band of rows can hold; else the problem, one line.
std::string imageHeaderProblem(const ImageReader& in, const std::string& label, const ImageBound& bound);
// "" when the file holds the last row its header claims: read first, through a
// one-row buffer, before a caller allocates the whole image (a header that lies about
// its size is refused unallocated). A reader that decodes in bands needs no such check.
std::string lastRowProblem(ImageReader& in, const std::string& label);

// Rows [y, y + rows) of `in`, channels [chbegin, chend), as float at `data` with the
// given strides in bytes; scanline or tiled (then `y` and `rows` follow the tile rows,
// as bandRows gives them). False with the decoder's error in `in`.
bool readRows(ImageReader& in, int y, int rows, int chbegin, int chend, float* data,
              std::ptrdiff_t xstride = kAutoStride, std::ptrdiff_t ystride = kAutoStride);
// Rows per band: a tile row of a tiled file, 64 rows of a scanline file.
int bandRows(const ImageInfo& spec);

// The image library stacks one line per layer ("Read error: hit end of file", "PNG read error:
// ...", "PNG library error"); the first says what happened.
std::string firstLine(const std::string& s);

}  // namespace penumbra
