// Memory for large photon arrays, mapped straight from the kernel: from 2 MB on,
// 2 MB-aligned and advised for transparent huge pages; below, populated up front.
// First-touch faults of 4 KB pages are expensive on the VMs this project runs on; a
// huge page takes one fault per 2 MB instead.
#pragma once
#include <cstddef>
#include <utility>

namespace penumbra {

// Photon arrays at least this large are mapped here; smaller ones use malloc.
constexpr size_t kMappedMinBytes = size_t(256) << 10;

// An anonymous private mapping of at least `bytes`: from 2 MB on 2 MB-aligned and
// advised for huge pages (faulted in where written), below 2 MB populated (no fault
// per 4 KB page). Throws std::bad_alloc when the mapping fails. Release with
// unmapPhotonMemory and the same `bytes`.
void* mapPhotonMemory(size_t bytes);
void unmapPhotonMemory(void* p, size_t bytes) noexcept;

// Faults in the whole 4 KB pages of [p, p + bytes) in one call (MADV_POPULATE_WRITE),
// for memory another allocator hands out (a library's std::vector) that is about to
// be written in full. Best effort: on a kernel without it, pages fault as written.
void prefaultForWrite(void* p, size_t bytes) noexcept;

// One such mapping, owned (move-only).
class MappedBlock {
 public:
  MappedBlock() = default;
  explicit MappedBlock(size_t bytes) : data_(mapPhotonMemory(bytes)), bytes_(bytes) {}
  MappedBlock(MappedBlock&& o) noexcept
      : data_(std::exchange(o.data_, nullptr)), bytes_(std::exchange(o.bytes_, 0)) {}
  MappedBlock& operator=(MappedBlock&& o) noexcept {
    if (this != &o) {
      reset();
      data_ = std::exchange(o.data_, nullptr);
      bytes_ = std::exchange(o.bytes_, 0);
    }
    return *this;
  }
  MappedBlock(const MappedBlock&) = delete;
  MappedBlock& operator=(const MappedBlock&) = delete;
  ~MappedBlock() { reset(); }

  void* data() const { return data_; }
  size_t bytes() const { return bytes_; }
  void reset() noexcept {
    if (data_) unmapPhotonMemory(data_, bytes_);
    data_ = nullptr;
    bytes_ = 0;
  }

 private:
  void* data_ = nullptr;
  size_t bytes_ = 0;
};

}  // namespace penumbra
