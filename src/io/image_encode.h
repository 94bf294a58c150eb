// The one encode-and-write of an image file, for io's writers: the image module
// encodes it in memory by the path's extension, then io/temp_file.h writes it whole
// or not at all.
#pragma once
#include "core/image_codec.h"
#include <string>

namespace penumbra {

// Throws InputError naming `path` when the writer refuses or the write fails.
void writeAtomically(const std::string& path, const EncodeSpec& spec, const void* pixels);

}  // namespace penumbra
