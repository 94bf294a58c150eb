// Texture checks for the material reader: the image module decodes every pixel of an
// image file (in bands of rows, so memory stays small), and builtin names are
// matched against the generator's list.
#include "io/texture_check.h"

#include "io/image_header.h"
#include "io/texture_gen.h"

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PENUMBRA_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(PENUMBRA_ASAN)
#include <sanitizer/lsan_interface.h>
// OIIO 2.4's PNG reader builds its error string in the libpng read callback and then
// libpng longjmps out of a truncated file past that string's destructor: 31 bytes
// leak per truncated PNG, in OIIO, not here. Leak checking skips just that decode.
#define PENUMBRA_THIRD_PARTY_LEAKS_BEGIN __lsan_disable()
#define PENUMBRA_THIRD_PARTY_LEAKS_END __lsan_enable()
#else
#define PENUMBRA_THIRD_PARTY_LEAKS_BEGIN ((void)0)
#define PENUMBRA_THIRD_PARTY_LEAKS_END ((void)0)
#endif

namespace penumbra {

namespace {

// libpng prints its own "libpng error: ..." to stderr before OIIO sees the
// error; the one-line InputError says it all, so stderr is muted while decoding.
// The loader runs before any worker prints, so nothing else is lost.
class MutedStderr {
 public:
  MutedStderr() {
    std::fflush(stderr);
    saved_ = ::dup(STDERR_FILENO);
    const int null = ::open("/dev/null", O_WRONLY);
    if (saved_ >= 0 && null >= 0) ::dup2(null, STDERR_FILENO);
    if (null >= 0) ::close(null);
  }
  ~MutedStderr() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      ::dup2(saved_, STDERR_FILENO);
      ::close(saved_);
    }
  }
  MutedStderr(const MutedStderr&) = delete;
  MutedStderr& operator=(const MutedStderr&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace

std::string textureFileProblem(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::file_size(path, ec) > kMaxTextureFileBytes && !ec) {
    return "texture " + path + " is larger than " + std::to_string(kMaxTextureFileBytes >> 30) + " GB";
  }
  MutedStderr muted;
  std::string problem;
  auto in = openImage(path, "texture " + path, problem);
  if (!in) return problem;
  // The header's size, before a pixel is decoded: a small file may claim billions.
  // The bands read below hold a few rows, so a file shorter than its header costs nothing.
  const std::string header =
      imageHeaderProblem(*in, "texture " + path, {kMaxTexturePixels, "the 16384x16384 penumbra reads", kMaxTextureSide});
  if (!header.empty()) return header;
  const ImageInfo spec = in->info();
  const int band = bandRows(spec);
  std::vector<float> pixels(size_t(spec.width) * size_t(band) * size_t(spec.nchannels));
  const int yEnd = spec.y + spec.height;
  for (int y = spec.y; y < yEnd; y += band) {
    const int rows = std::min(band, yEnd - y);
    PENUMBRA_THIRD_PARTY_LEAKS_BEGIN;
    const bool read =
        readRows(*in, y, rows, 0, spec.nchannels, pixels.data());
    PENUMBRA_THIRD_PARTY_LEAKS_END;
    if (!read) {
      return "texture " + path + " is truncated or corrupt: " + firstLine(in->error());
    }
    const size_t count = size_t(spec.width) * size_t(rows) * size_t(spec.nchannels);
    for (size_t i = 0; i < count; ++i) {
      if (!std::isfinite(pixels[i])) {
        return "texture " + path + " has a non-finite value in row " +
               std::to_string(y - spec.y + int(i / (size_t(spec.width) * spec.nchannels)));
      }
    }
  }
  return "";
}

std::string builtinTextureProblem(const std::string& spec) {
  const std::string prefix = "builtin:";
  std::string name = spec.substr(std::min(spec.size(), prefix.size()));
  if (const size_t at = name.find('@'); at != std::string::npos) {
    const std::string digits = name.substr(at + 1);
    name.resize(at);
    char* end = nullptr;
    const long width = digits.empty() ? 0 : std::strtol(digits.c_str(), &end, 10);
    if (digits.empty() || *end != '\0' || width < 2 || width > 16384) {
      return "builtin texture width must be an integer in [2, 16384], got \"" + digits + "\"";
    }
  }
  const std::vector<std::string>& names = builtinTextureNames();
  if (std::find(names.begin(), names.end(), name) != names.end()) return "";
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return "unknown builtin texture \"" + name + "\" (valid: " + list + ")";
}

}  // namespace penumbra
