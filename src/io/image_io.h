// Writes framebuffers through OpenImageIO: PNG (8-bit sRGB) or EXR (linear half;
// depth and normals 32-bit float), chosen by extension, encoded in memory and written
// by the checked write-and-rename of io/temp_file.h; tells whether a file is whole.
#pragma once
#include "core/image.h"
#include "io/tone_map.h"
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

// Throws InputError unless `path` has a supported extension and can be written
// (outputPathProblem, io/temp_file.h): lets a render fail before it starts.
void checkImageOutputPath(const std::string& path);

// Throws InputError for an unsupported extension or an unwritable path. PNG shows a
// depth or normal image as a picture (io/aov_display.h) and applies `display`
// (exposure, tone curve); EXR keeps the linear or physical values, plus A = coverage
// for depth and normals.
void writeImage(const std::string& path, const Image& image, const ImageMetadata& metadata = {},
                const DisplayOptions& display = {});

// Several views of one render in one EXR: layer NAME's channels are NAME.R, NAME.G,
// NAME.B (linear half; float for depth and normals, with NAME.A = coverage). Same
// checks and temp-file write as writeImage.
void writeLayeredExr(const std::string& path, const std::vector<std::pair<std::string, Image>>& layers,
                     const ImageMetadata& metadata = {});

// True when the image file at `path` is whole, cheaply: a PNG ends in its IEND chunk;
// a scanline EXR holds its last chunk's bytes (io/image_file_header.h); another format
// opens and its last row decodes. False if missing.
bool imageComplete(const std::string& path);

// A string attribute of an image file's header ("" if the file or attribute is missing).
std::string readImageAttribute(const std::string& path, const std::string& name);

// Reads any OIIO-readable image as linear RGB (sRGB PNG/JPEG are linearised).
Image readImage(const std::string& path);

}  // namespace penumbra
