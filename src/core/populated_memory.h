// Memory for large photon arrays: huge pages where the kernel grants them, every page
// present before the first write. On the VMs this project runs on, 4 KB pages cost
// ~11 us each at first touch (168 MB: 0.49 s); 2 MB pages populated in bulk, 0.014 s.
#pragma once
#include <cstddef>
#include <utility>

namespace penumbra {

// Allocations at least this large are mapped populated; smaller ones use malloc,
// whose heap pages are mostly warm already.
constexpr size_t kPopulatedMinBytes = size_t(256) << 10;

// An anonymous private mapping of `bytes` with its pages populated; from 2 MB on,
// 2 MB-aligned and advised to use transparent huge pages. Throws std::bad_alloc when
// the mapping fails. Release with freePopulated.
void* allocatePopulated(size_t bytes);
void freePopulated(void* p, size_t bytes) noexcept;

// One populated mapping, owned (move-only).
class PopulatedBlock {
 public:
  PopulatedBlock() = default;
  explicit PopulatedBlock(size_t bytes) : data_(allocatePopulated(bytes)), bytes_(bytes) {}
  PopulatedBlock(PopulatedBlock&& o) noexcept
      : data_(std::exchange(o.data_, nullptr)), bytes_(std::exchange(o.bytes_, 0)) {}
  PopulatedBlock& operator=(PopulatedBlock&& o) noexcept {
    if (this != &o) {
      reset();
      data_ = std::exchange(o.data_, nullptr);
      bytes_ = std::exchange(o.bytes_, 0);
    }
    return *this;
  }
  PopulatedBlock(const PopulatedBlock&) = delete;
  PopulatedBlock& operator=(const PopulatedBlock&) = delete;
  ~PopulatedBlock() { reset(); }

  void* data() const { return data_; }
  size_t bytes() const { return bytes_; }
  void reset() noexcept {
    if (data_) freePopulated(data_, bytes_);
    data_ = nullptr;
    bytes_ = 0;
  }

 private:
  void* data_ = nullptr;
  size_t bytes_ = 0;
};

}  // namespace penumbra
