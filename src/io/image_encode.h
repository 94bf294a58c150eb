// The one encode-and-write of an image file, for io's writers: OIIO encodes it in
// memory by the path's extension, then io/temp_file.h writes it whole or not at all.
#pragma once
#include <OpenImageIO/imageio.h>
#include <string>

namespace penumbra {

// Throws InputError naming `path` when the writer refuses or the write fails.
void writeAtomically(const std::string& path, const OIIO::ImageSpec& spec, OIIO::TypeDesc pixelType,
                     const void* pixels);

}  // namespace penumbra
