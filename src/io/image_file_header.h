// What penumbra's own PNG and EXR files say in their headers, read without the image
// library: a "penumbra:" string attribute, and whether an EXR's last chunk is all there.
// A batch or sweep that only asks whether its outputs are up to date loads no codec.
#pragma once
#include <optional>
#include <string>

namespace penumbra {

// The value of string attribute `name` ("penumbra:..." only: names the image library
// keeps as they are) in a PNG's text chunks before its pixels or a single-part OpenEXR
// header; nullopt when the file is neither, cannot be parsed, or lacks it (the image
// library then answers).
std::optional<std::string> penumbraAttribute(const std::string& path, const std::string& name);

// Whether a single-part scanline OpenEXR file holds all of its last chunk (the
// offset table's last entry, its row and byte count within the file); nullopt for
// any other file, which the image library then decodes.
std::optional<bool> exrLastChunkWhole(const std::string& path);

}  // namespace penumbra
