// The lookup cache's lazy cells: where no precomputed cell is near a shading point,
// the estimate of its own (cell, bucket) is computed once, on first use, and kept.
#include "gather/lookup_cache/lookup_cache.h"
#include <cmath>

namespace penumbra {
namespace {

constexpr size_t kLazyProbes = 32;  // a longer run: compute without keeping

}  // namespace

void LookupCache::makeLazyTable() {
  // Fallbacks come from surfaces the photons did not reach in that orientation: far
  // fewer cells than the photons reached. An eighth of the records (>= 4096 slots)
  // keeps them at low load, costs 3 B per record and is cheap to construct; beyond
  // it, points are still answered, just not kept.
  size_t size = 4096;
  while (size < records_ / 8) size *= 2;
  lazy_ = std::make_unique<LazyTable>();
  lazy_->slots = std::make_unique<LazySlot[]>(size);
  lazy_->mask = size - 1;
}

Color LookupCache::lazyIndirect(const IndirectPhotonMap& map, const Vec3& p, const Vec3& n,
                                GatherScratch& s) const {
  // The bucket's axis, signed: the normal every point of the (cell, bucket) shares.
  const unsigned bucket = bucketOf(n);
  Vec3 axisNormal(0.0f);
  axisNormal[bucket / 2] = bucket & 1u ? -1.0f : 1.0f;
  const uint64_t key = keyAt(p, bucket);
  const Vec3 centre = cellCentreOf(p);
  if (key == kEmpty || !lazy_) return estimateAt(map, centre, axisNormal, s);

  LazyTable& table = *lazy_;
  size_t i = slotHash(key) & table.mask;
  for (size_t probe = 0; probe < kLazyProbes; ++probe, i = (i + 1) & table.mask) {
    LazySlot& slot = table.slots[i];
    uint64_t seen = slot.key.load(std::memory_order_acquire);
    if (seen == kEmpty && slot.key.compare_exchange_strong(seen, key, std::memory_order_acq_rel)) {
      // This thread claimed the slot: compute, then publish.
      slot.value = estimateAt(map, centre, axisNormal, s);
      slot.ready.store(1, std::memory_order_release);
      table.count.fetch_add(1, std::memory_order_relaxed);
      return slot.value;
    }
    if (seen != key) continue;  // another key (or one claimed just now): probe on
    // Ours: read it if published, else compute the same value alongside.
    if (slot.ready.load(std::memory_order_acquire)) return slot.value;
    return estimateAt(map, centre, axisNormal, s);
  }
  return estimateAt(map, centre, axisNormal, s);
}

}  // namespace penumbra
