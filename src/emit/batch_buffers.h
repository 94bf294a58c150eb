// Photon storage during emission: each thread appends the batches it runs to its own
// blocks of huge-page memory, and batch b's photons stay one span, so the stored sequence
// (batches in batch order) does not depend on which thread ran which batch.
#pragma once
#include "core/photon_batches.h"
#include <tbb/enumerable_thread_specific.h>
#include <algorithm>
#include <cstddef>
#include <vector>

namespace penumbra {

// One thread's append buffer: a batch grows at the tail of the current block; when
// the block is full, the batch so far moves to a fresh, larger block (the old block
// keeps the batches already finished in it). No vector doubling, one fault per 2 MB.
template <class Photon>
class BatchAppender {
 public:
  void push_back(const Photon& p) {
    if (end_ == cap_) grow();
    *end_++ = p;
  }
  size_t size() const { return static_cast<size_t>(end_ - begin_); }

  void start() { begin_ = end_; }  // a new batch begins where the last one ended
  typename PhotonBatches<Photon>::Span span() const { return {begin_, size()}; }
  std::vector<MappedBlock>& blocks() { return blocks_; }

 private:
  // Blocks double from one huge page (2 MB) up to 32 MB: small emissions map little,
  // large ones few.
  static constexpr size_t kFirstBlock = size_t(2) << 20, kLargestBlock = size_t(32) << 20;
  void grow() {
    const size_t batch = size();
    size_t bytes = std::min(kLargestBlock, blocks_.empty() ? kFirstBlock : 2 * blocks_.back().bytes());
    bytes = std::max(bytes, 4 * (batch + 1) * sizeof(Photon));
    blocks_.emplace_back(bytes);
    Photon* base = static_cast<Photon*>(blocks_.back().data());
    std::copy(begin_, end_, base);
    begin_ = base;
    end_ = base + batch;
    cap_ = base + bytes / sizeof(Photon);
  }

  Photon *begin_ = nullptr, *end_ = nullptr, *cap_ = nullptr;
  std::vector<MappedBlock> blocks_;
};

template <class Photon>
class BatchBuffers {
 public:
  explicit BatchBuffers(size_t batches) : spans_(batches) {}

  // Runs fill(out) for batch b with the calling thread's appender as `out` (push_back,
  // size). Emission tasks must not nest parallel work inside: the appender is per thread.
  template <class Fill>
  void fill(size_t b, Fill&& fill) {
    BatchAppender<Photon>& out = local_.local();
    out.start();
    fill(out);
    spans_[b] = out.span();
  }

  // Photons stored per batch, in batch order.
  std::vector<size_t> sizes() const {
    std::vector<size_t> n(spans_.size());
    for (size_t b = 0; b < spans_.size(); ++b) n[b] = spans_[b].size;
    return n;
  }

  // Every batch as one sequence; the blocks move into it.
  PhotonBatches<Photon> finish() {
    std::vector<MappedBlock> blocks;
    for (BatchAppender<Photon>& a : local_) {
      for (MappedBlock& block : a.blocks()) blocks.push_back(std::move(block));
    }
    local_.clear();
    return PhotonBatches<Photon>(std::move(spans_), std::move(blocks));
  }

 private:
  std::vector<typename PhotonBatches<Photon>::Span> spans_;
  tbb::enumerable_thread_specific<BatchAppender<Photon>> local_;
};

}  // namespace penumbra
