// The OpenVDB reader: its module in the reader process, and the codec that runs that
// process (core/density_codec.h).
#include "core/density_codec.h"

#include "core/density_wire.h"
#include "core/module_loader.h"
#include "core/subprocess.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#ifndef PENUMBRA_VOLUME_MODULE
#define PENUMBRA_VOLUME_MODULE nullptr
#endif
#ifndef PENUMBRA_VOLUME_READER
#define PENUMBRA_VOLUME_READER nullptr
#endif

namespace penumbra {
namespace {

constexpr uint64_t kMiB = uint64_t(1) << 20;
// OpenVDB's registries, grid descriptors and metadata beside the grid itself.
constexpr uint64_t kReaderBaseBytes = 128 * kMiB;
// A deadline generous for a real file on a loaded machine: start-up (OpenVDB and its
// libraries) plus reading and decompressing at a few MB/s.
constexpr double kReaderBaseSeconds = 30.0;
constexpr double kReaderBytesPerSecond = 4e6;

// The most bytes the lattice may take: the voxel limit's, within the load budget
// (0: neither is set, no limit).
uint64_t latticeBytes(const DensityRequest& request) {
  const uint64_t voxels = request.maxVoxels * sizeof(float);
  if (!voxels || !request.maxBytes) return voxels ? voxels : request.maxBytes;
  return std::min(voxels, request.maxBytes);
}

// How long the reader may take for a file of `fileBytes`, in seconds.
double deadlineSeconds(uint64_t fileBytes) { return kReaderBaseSeconds + double(fileBytes) / kReaderBytesPerSecond; }

// Values finite and >= 0, their maximum the majorant: checked again on this side, as
// the answer came from another process.
std::string checkValues(DensityGrid& grid) {
  grid.maxDensity = 0.0f;
  for (float v : grid.values) {
    if (!(v >= 0.0f) || !std::isfinite(v)) return "the reader's answer holds a value that is negative or not finite";
    grid.maxDensity = std::max(grid.maxDensity, v);
  }
  return "";
}

class ReaderProcess final : public DensityCodec {
 public:
  std::string load(const std::string& path, const DensityRequest& request, DensityGrid& out) const override {
    const std::string reader = helperExecutable(kVolumeReaderName, PENUMBRA_VOLUME_READER);
    if (reader.empty()) {
      throw std::runtime_error(fmt::format("cannot find the OpenVDB reader {} beside the executable", kVolumeReaderName));
    }
    struct stat st {};
    const uint64_t fileBytes = ::stat(path.c_str(), &st) == 0 ? uint64_t(st.st_size) : 0;
    const double seconds = deadlineSeconds(fileBytes);
    ProcessLimits limits;
    limits.seconds = seconds;
    const uint64_t lattice = latticeBytes(request);
    limits.maxOutputBytes = lattice ? size_t(64 * 1024 + lattice) : 0;
    const ProcessResult r =
        runProcess(reader, {}, encodeJob({path, request, densityMemoryCap(request), seconds + 1.0}), limits);
    if (!r.started) throw std::runtime_error(fmt::format("cannot start the OpenVDB reader {}: {}", reader, r.error));
    if (r.timedOut) return fmt::format("cannot be read (OpenVDB did not finish within {:.0f} s)", seconds);
    if (r.outputCapped) return "cannot be read (OpenVDB's answer was larger than the lattice allowed)";
    if (r.signal != 0) return fmt::format("cannot be read (OpenVDB failed on it: {})", ::strsignal(r.signal));
    if (r.exitCode != 0) return fmt::format("cannot be read (the OpenVDB reader exited with code {})", r.exitCode);
    if (std::string problem = decodeAnswer(r.output, request, out); !problem.empty()) return problem;
    return checkValues(out);
  }
};

}  // namespace

uint64_t densityMemoryCap(const DensityRequest& request) {
  const uint64_t lattice = latticeBytes(request);
  return lattice ? kReaderBaseBytes + 3 * lattice : 0;
}

const DensityCodec& densityCodec() {
  static const ReaderProcess codec;
  return codec;
}

const DensityCodec& densityModule() {
  static const DensityCodec* const codec =
      moduleObject<DensityCodec>(kVolumeModuleName, kDensityCodecEntry, PENUMBRA_VOLUME_MODULE, "OpenVDB");
  return *codec;
}

}  // namespace penumbra
