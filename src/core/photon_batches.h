// Photons as an emission stores them: one span per batch, read in batch order as one
// sequence, in the blocks the emitting threads filled. The map build sorts
// straight out of the spans (Morton order, the default), so it makes no merged copy.
#pragma once
#include "core/photon.h"
#include "core/mapped_memory.h"
#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <iterator>
#include <vector>

namespace penumbra {

template <class Photon>
class PhotonBatches {
 public:
  struct Span {
    const Photon* data = nullptr;
    size_t size = 0;
  };

  PhotonBatches() { seal(); }
  // A plain array as one batch, owned, without a copy (a prefix cut, a test's photons).
  PhotonBatches(PhotonArray<Photon> all) : owned_(std::move(all)) {  // NOLINT: implicit on purpose
    if (!owned_.empty()) spans_.push_back({owned_.data(), owned_.size()});
    seal();
  }
  PhotonBatches(std::initializer_list<Photon> photons) : PhotonBatches(PhotonArray<Photon>(photons)) {}
  // The emitters' batches: span b is batch b's photons, inside `blocks` (kept alive here).
  PhotonBatches(std::vector<Span> spans, std::vector<MappedBlock> blocks)
      : spans_(std::move(spans)), blocks_(std::move(blocks)) {
    seal();
  }
  // A copy is one contiguous array (sweeps keep the full emission and hand out copies).
  PhotonBatches(const PhotonBatches& o) : PhotonBatches(o.flatten()) {}
  PhotonBatches& operator=(const PhotonBatches& o) {
    if (this != &o) *this = PhotonBatches(o.flatten());
    return *this;
  }
  PhotonBatches(PhotonBatches&&) noexcept = default;
  PhotonBatches& operator=(PhotonBatches&&) noexcept = default;

  size_t batchCount() const { return spans_.size(); }
  const Span& batch(size_t b) const { return spans_[b]; }
  size_t offset(size_t b) const { return offsets_[b]; }  // where batch b starts in the sequence
  size_t size() const { return offsets_.empty() ? 0 : offsets_.back(); }
  bool empty() const { return size() == 0; }

  // Photon i of the sequence: a binary search over the batches, for cold paths and tests.
  const Photon& operator[](size_t i) const {
    const size_t b = std::upper_bound(offsets_.begin(), offsets_.end(), i) - offsets_.begin() - 1;
    return spans_[b].data[i - offsets_[b]];
  }

  // Calls f(i, photon) for every i in [begin, end), walking the batches in order.
  template <class F>
  void forRange(size_t begin, size_t end, F&& f) const {
    end = std::min(end, size());
    if (begin >= end) return;
    size_t b = std::upper_bound(offsets_.begin(), offsets_.end(), begin) - offsets_.begin() - 1;
    for (size_t i = begin; i < end; ++b) {
      const Span& span = spans_[b];  // empty spans (even with a null data) add nothing
      for (const size_t e = std::min(end, offsets_[b + 1]); i < e; ++i) f(i, span.data[i - offsets_[b]]);
    }
  }

  // The sequence as one array: the owned array itself when that is all there is
  // (no copy), else a copy. Leaves this empty.
  PhotonArray<Photon> takeArray() && {
    PhotonArray<Photon> out =
        spans_.size() == 1 && spans_[0].data == owned_.data() ? std::move(owned_) : flatten();
    *this = PhotonBatches();
    return out;
  }
  // A contiguous copy of the sequence.
  PhotonArray<Photon> flatten() const {
    PhotonArray<Photon> out(size());
    for (size_t b = 0; b < spans_.size(); ++b) {
      std::copy(spans_[b].data, spans_[b].data + spans_[b].size, out.begin() + offsets_[b]);
    }
    return out;
  }

  // Forward iteration in sequence order (range-for over an emission's photons).
  class const_iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = Photon;
    using difference_type = std::ptrdiff_t;
    using pointer = const Photon*;
    using reference = const Photon&;
    const_iterator(const PhotonBatches* s, size_t b, size_t i) : s_(s), b_(b), i_(i) { skipEmpty(); }
    reference operator*() const { return s_->spans_[b_].data[i_]; }
    pointer operator->() const { return &**this; }
    const_iterator& operator++() {
      ++i_;
      skipEmpty();
      return *this;
    }
    bool operator==(const const_iterator& o) const { return b_ == o.b_ && i_ == o.i_; }
    bool operator!=(const const_iterator& o) const { return !(*this == o); }

   private:
    void skipEmpty() {
      while (b_ < s_->spans_.size() && i_ >= s_->spans_[b_].size) {
        ++b_;
        i_ = 0;
      }
    }
    const PhotonBatches* s_;
    size_t b_, i_;
  };
  const_iterator begin() const { return {this, 0, 0}; }
  const_iterator end() const { return {this, spans_.size(), 0}; }

 private:
  void seal() {
    offsets_.assign(spans_.size() + 1, 0);
    for (size_t b = 0; b < spans_.size(); ++b) offsets_[b + 1] = offsets_[b] + spans_[b].size;
  }

  std::vector<Span> spans_;
  std::vector<size_t> offsets_{0};
  std::vector<MappedBlock> blocks_;
  PhotonArray<Photon> owned_;
};

}  // namespace penumbra
