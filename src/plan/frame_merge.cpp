// The merge reads every header first (cheap), checks, then pastes the pixels and
// writes the frame through the same writer as a whole render, so the bytes agree.
#include "plan/frame_merge.h"
#include "plan/frame_part.h"
#include "plan/image_metadata.h"
#include "core/error.h"
#include "core/error_estimate.h"
#include "io/image_io.h"
#include "io/image_part.h"
#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace penumbra {
namespace {

std::string need(const PartHeader& p, const char* key) {
  const std::string v = p.attribute(key);
  if (v.empty()) throw InputError(p.path + ": not a part of a frame (no " + key + "; render it with --tile)");
  return v;
}

bool isErrorKey(const std::string& key) { return key == "penumbra:error" || key.rfind("penumbra:error.", 0) == 0; }

// Every pixel in exactly one part: the first pixel two parts share, or no part has.
void checkCover(const std::vector<PartHeader>& parts, int width, int height) {
  std::vector<int> owner(static_cast<size_t>(width) * height, -1);
  for (size_t k = 0; k < parts.size(); ++k) {
    const PixelBounds& b = parts[k].bounds;
    if (b.empty() || b.x0 < 0 || b.y0 < 0 || b.x1 > width || b.y1 > height) {
      throw InputError(fmt::format("merge: {}: its pixels {} are not inside the {}x{} frame", parts[k].path,
                                   need(parts[k], kPartBounds), width, height));
    }
    for (int y = b.y0; y < b.y1; ++y) {
      for (int x = b.x0; x < b.x1; ++x) {
        int& o = owner[static_cast<size_t>(y) * width + x];
        if (o >= 0) {
          throw InputError(fmt::format("merge: {} and {} overlap (both hold pixel {},{}): each pixel must be in one "
                                       "part", parts[o].path, parts[k].path, x, y));
        }
        o = static_cast<int>(k);
      }
    }
  }
  const auto gap = std::find(owner.begin(), owner.end(), -1);
  if (gap != owner.end()) {
    const size_t i = static_cast<size_t>(gap - owner.begin());
    const size_t missing = static_cast<size_t>(std::count(owner.begin(), owner.end(), -1));
    throw InputError(fmt::format("merge: the parts leave a gap: pixel {},{} is in no part ({} of {} pixels missing)",
                                 i % width, i / width, missing, owner.size()));
  }
}

// The frame's error figure from the parts' shares (frame_part.h's keys).
ErrorEstimate pooledError(const std::vector<PartHeader>& parts, const std::vector<std::pair<std::string, Image>>& images,
                          size_t pixels) {
  int source = 0, count = 0, shared = 0;
  std::istringstream(need(parts.front(), kPartError)) >> source >> count >> shared;
  auto find = [&](const char* name) -> const Image* {
    for (const auto& [n, image] : images)
      if (n == name) return &image;
    return nullptr;
  };
  auto layer = [&](const char* name) -> const Image& {
    if (const Image* image = find(name)) return *image;
    throw InputError(parts.front().path + ": part has no '" + name + "' layer for its error figure");
  };
  const Image* emitterImage = find(kEmitterLayer);
  const EmitterMask emitters = emitterImage ? emitterMaskOf(*emitterImage) : EmitterMask();
  ErrorEstimate e;
  if (source == static_cast<int>(ErrorSource::Samples)) {
    e = sampleError(layer("se"), count, emitters);
  } else if (source == static_cast<int>(ErrorSource::Passes)) {
    PassCheckpoint c;
    std::istringstream(need(parts.front(), kPartBias)) >> c.passes >> c.half;
    if (c.half > 0) {
      c.firstEven = layer("bias_first_even");
      c.firstOdd = layer("bias_first_odd");
      c.even = layer("bias_even");
      c.odd = layer("bias_odd");
    }
    // A model that probes its gathers' smoothing kept a group per pass, up to four.
    SmoothingSums smoothing;
    for (int g = 0; g < SmoothingSums::kGroups && find(kSmoothingLayers[g]); ++g) smoothing.groups[g] = layer(kSmoothingLayers[g]);
    const int groups = smoothing.filled();
    if (groups != 0 && groups != std::min(count, SmoothingSums::kGroups)) {
      throw InputError(parts.front().path + ": part has " + std::to_string(groups) + " smoothing layers for " +
                       std::to_string(count) + " passes");
    }
    e = PassSpread::fromHalves(layer("even"), layer("odd"), count, c, smoothing, emitters);
  } else if (source == static_cast<int>(ErrorSource::Probes)) {
    double squares = 0.0;
    for (const PartHeader& p : parts) {
      const std::string probes = need(p, kPartProbes);
      char* at = nullptr;
      squares += std::strtod(probes.c_str(), &at);
      e.count += static_cast<int>(std::strtol(at, nullptr, 10));
    }
    e.source = ErrorSource::Probes;
    e.noiseRmse = std::sqrt(std::max(0.0, squares / double(pixels)));
    e.lowerBound = !(squares > 0.0);
  }
  e.sharedMaps = shared != 0;
  return e;
}

// The merged header: the parts' keys for this kind of file, in their order, with the
// error keys recomputed and penumbra:job the frame's.
ImageMetadata mergedMetadata(const PartHeader& first, const ErrorEstimate& error, bool png) {
  ImageMetadata m;
  bool errorDone = false;
  std::istringstream keys(need(first, png ? kPartPngKeys : kPartExrKeys));
  for (std::string key; std::getline(keys, key, ',');) {
    if (isErrorKey(key)) {
      if (!errorDone) for (auto& kv : errorMetadata(error)) m.push_back(std::move(kv));
      errorDone = true;
    } else {
      m.emplace_back(key, key == "penumbra:job" ? need(first, kPartJob) : first.attribute(key));
    }
  }
  return m;
}

}  // namespace

MergeOutcome mergeFrame(const std::vector<std::string>& paths, const std::string& output,
                        const DisplayOptions& display) {
  if (paths.empty()) throw InputError("merge: name the part files to merge");
  checkImageOutputPath(output);
  std::vector<PartHeader> parts;
  for (const std::string& p : paths) {
    parts.push_back(readPartHeader(p));
    if (p == output) throw InputError("merge: -o " + output + " is one of the parts");
  }
  const PartHeader& first = parts.front();
  const std::string job = need(first, kPartJob), frame = need(first, kPartFrame);
  for (const PartHeader& p : parts) {
    if (need(p, kPartFrame) != frame || p.frameWidth != first.frameWidth || p.frameHeight != first.frameHeight) {
      throw InputError(fmt::format("merge: {} is a part of a {} frame, {} of a {} frame", p.path, need(p, kPartFrame),
                                   first.path, frame));
    }
    if (need(p, kPartJob) != job) {
      throw InputError(fmt::format("merge: {} and {} are parts of different jobs (stamps {} and {})", first.path,
                                   p.path, job, p.attribute(kPartJob)));
    }
    if (p.channels != first.channels) {
      throw InputError(fmt::format("merge: {} and {} have different channels", first.path, p.path));
    }
  }
  const int width = first.frameWidth, height = first.frameHeight;
  checkCover(parts, width, height);

  std::vector<std::pair<std::string, Image>> images = pasteParts(parts);
  Image& image = images.front().second;
  const std::string content = first.attribute(kPartContent);
  image.content = content == "depth" ? ImageContent::Depth : content == "normal" ? ImageContent::Normal
                                                                                  : ImageContent::Radiance;
  const ErrorEstimate error = pooledError(parts, images, static_cast<size_t>(width) * height);
  std::string ext = output.substr(output.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  writeImage(output, image, mergedMetadata(first, error, ext == "png"), display);
  return {width, height, parts.size(), describeError(error)};
}

}  // namespace penumbra
