// The 8-bit pictures of the geometric views, whose images hold physical values
// (core/image.h): the PNG writer shows these; EXR files keep the values.
#pragma once
#include "core/image.h"

namespace penumbra {

// A radiance image in [0, 1] showing a Depth or Normal image as the report does:
//   depth:  (d - nearest) / (farthest - nearest) over the pixels that hit; misses white
//   normal: coverage * (n * 0.5 + 0.5); misses black
// A Radiance image comes back unchanged.
Image aovDisplay(const Image& image);

}  // namespace penumbra
