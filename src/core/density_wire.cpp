// The reader process's request and answer (core/density_wire.h).
#include "core/density_wire.h"

#include <cmath>
#include <cstring>
#include <type_traits>

namespace penumbra {
namespace {

constexpr uint32_t kJobMagic = 0x4a564450u;     // "PDVJ"
constexpr uint32_t kAnswerMagic = 0x41564450u;  // "PDVA"

class Writer {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void putString(const std::string& s) {
    put(uint64_t(s.size()));
    bytes += s;
  }
  std::string bytes;
};

class Reader {
 public:
  explicit Reader(const std::string& b) : bytes_(b) {}
  template <class T>
  bool get(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (bytes_.size() - at_ < sizeof(T)) return false;
    std::memcpy(&v, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  // A string no longer than what is left (a length is never trusted).
  bool getString(std::string& s) {
    uint64_t n = 0;
    if (!get(n) || n > bytes_.size() - at_) return false;
    s.assign(bytes_.data() + at_, size_t(n));
    at_ += size_t(n);
    return true;
  }
  size_t left() const { return bytes_.size() - at_; }
  const char* here() const { return bytes_.data() + at_; }

 private:
  const std::string& bytes_;
  size_t at_ = 0;
};

}  // namespace

std::string encodeJob(const DensityJob& job) {
  Writer w;
  w.put(kJobMagic);
  w.putString(job.path);
  w.putString(job.request.grid);
  w.put(job.request.scale);
  w.put(job.request.objectToWorld);
  w.put(job.request.maxVoxels);
  w.put(job.request.maxBytes);
  w.put(job.request.maxValue);
  w.put(job.request.maxCoordinate);
  w.put(job.memoryCap);
  w.put(job.seconds);
  return w.bytes;
}

bool decodeJob(const std::string& bytes, DensityJob& job) {
  Reader r(bytes);
  uint32_t magic = 0;
  return r.get(magic) && magic == kJobMagic && r.getString(job.path) && r.getString(job.request.grid) &&
         r.get(job.request.scale) && r.get(job.request.objectToWorld) && r.get(job.request.maxVoxels) &&
         r.get(job.request.maxBytes) && r.get(job.request.maxValue) && r.get(job.request.maxCoordinate) &&
         r.get(job.memoryCap) && r.get(job.seconds) && r.left() == 0;
}

std::string encodeAnswer(const std::string& problem, const DensityGrid& grid) {
  Writer w;
  w.put(kAnswerMagic);
  w.putString(problem);
  if (!problem.empty()) return w.bytes;
  w.put(int32_t(grid.nx));
  w.put(int32_t(grid.ny));
  w.put(int32_t(grid.nz));
  w.put(grid.worldToGrid);
  w.put(grid.worldLo);
  w.put(grid.worldHi);
  w.put(uint64_t(grid.values.size()));
  w.bytes.append(reinterpret_cast<const char*>(grid.values.data()), grid.values.size() * sizeof(float));
  return w.bytes;
}

std::string decodeAnswer(const std::string& bytes, const DensityRequest& request, DensityGrid& grid) {
  Reader r(bytes);
  uint32_t magic = 0;
  std::string problem;
  if (!r.get(magic) || magic != kAnswerMagic || !r.getString(problem)) return "the reader's answer is damaged";
  if (!problem.empty()) return problem;
  int32_t nx = 0, ny = 0, nz = 0;
  uint64_t count = 0;
  if (!r.get(nx) || !r.get(ny) || !r.get(nz) || !r.get(grid.worldToGrid) || !r.get(grid.worldLo) ||
      !r.get(grid.worldHi) || !r.get(count)) {
    return "the reader's answer is cut short";
  }
  uint64_t voxels = 0, payload = 0;
  const bool sized = nx > 0 && ny > 0 && nz > 0 && !__builtin_mul_overflow(uint64_t(nx), uint64_t(ny), &voxels) &&
                     !__builtin_mul_overflow(voxels, uint64_t(nz), &voxels) && voxels == count &&
                     !__builtin_mul_overflow(count, sizeof(float), &payload);
  if (!sized || (request.maxVoxels && count > request.maxVoxels) || r.left() != payload) {
    return "the reader's answer does not hold the lattice it names";
  }
  auto placed = [&](float v) { return std::isfinite(v) && std::fabs(double(v)) <= request.maxCoordinate; };
  bool finite = true;
  for (int c = 0; c < 4; ++c) {
    for (int k = 0; k < 4; ++k) finite = finite && std::isfinite(grid.worldToGrid[c][k]);
  }
  for (int a = 0; a < 3; ++a) {
    finite = finite && placed(grid.worldLo[a]) && placed(grid.worldHi[a]) && grid.worldLo[a] <= grid.worldHi[a];
  }
  if (!finite) return "the reader's answer places the lattice outside the scene's limits";
  grid.nx = nx, grid.ny = ny, grid.nz = nz;
  grid.values.resize(size_t(count));
  std::memcpy(grid.values.data(), r.here(), size_t(count) * sizeof(float));
  return "";
}

}  // namespace penumbra
