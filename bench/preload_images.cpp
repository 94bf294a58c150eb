// Linked into every benchmark: loads the image module before any benchmark runs, so a
// timed render measures the render, as with the image library linked, and not the
// process's first image read loading OpenImageIO (core/image_codec.h).
#include "core/image_codec.h"

namespace {
const bool kImagesLoaded = (penumbra::imageCodec(), true);
}  // namespace
