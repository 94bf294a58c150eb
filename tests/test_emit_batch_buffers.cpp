// Emission storage without a merge: per-thread blocks of huge-page memory, one span per
// batch, read back in batch order. Checked against the sequence a serial loop writes,
// at 1 and 2 threads, with batches larger than a block (the batch moves to a new one).
#include "emit/batch_buffers.h"
#include "core/mapped_memory.h"
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <cstdint>
#include <cstring>
#include <vector>

namespace penumbra {
namespace {

// Batch b stores sizeOf(b) records whose normal is their position in the sequence.
size_t sizeOf(size_t b) {
  if (b == 7) return 150000;  // 3 MB of records: more than a first block holds
  if (b % 5 == 0) return 0;   // batches that store nothing
  return (b * 7919) % 6000;
}

PhotonBatches<ShadowPhoton> fill(size_t batches, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::vector<size_t> start(batches + 1, 0);
  for (size_t b = 0; b < batches; ++b) start[b + 1] = start[b] + sizeOf(b);
  BatchBuffers<ShadowPhoton> buffers(batches);
  tbb::parallel_for(size_t(0), batches, [&](size_t b) {
    buffers.fill(b, [&](BatchAppender<ShadowPhoton>& out) {
      for (size_t i = 0; i < sizeOf(b); ++i) {
        out.push_back({Vec3(float(b), float(i), 0.0f), static_cast<uint32_t>(start[b] + i), 0, kDirect, 0, 0});
        ASSERT_EQ(out.size(), i + 1);
      }
    });
  });
  EXPECT_EQ(buffers.sizes()[7], 150000u);
  return buffers.finish();
}

TEST(BatchBuffers, BatchesReadBackInBatchOrderForAnyThreadCount) {
  const size_t batches = 300;
  size_t total = 0;
  for (size_t b = 0; b < batches; ++b) total += sizeOf(b);
  for (int threads : {1, 2}) {
    const PhotonBatches<ShadowPhoton> photons = fill(batches, threads);
    ASSERT_EQ(photons.batchCount(), batches);
    ASSERT_EQ(photons.size(), total);
    size_t i = 0;
    for (const ShadowPhoton& p : photons) ASSERT_EQ(p.normal, i++) << threads << " threads";
    for (size_t b = 0; b < batches; ++b) {
      ASSERT_EQ(photons.batch(b).size, sizeOf(b));
      if (sizeOf(b) > 0) {
        EXPECT_EQ(photons.batch(b).data[0].position.x, float(b));
      }
    }
  }
}

TEST(MappedMemory, LargeMappingsAreHugePageAlignedAndWritable) {
  for (size_t bytes : {size_t(4096), size_t(300) << 10, (size_t(3) << 20) + 1}) {
    MappedBlock block(bytes);
    ASSERT_NE(block.data(), nullptr);
    if (bytes >= (size_t(2) << 20)) {
      EXPECT_EQ(reinterpret_cast<uintptr_t>(block.data()) % (size_t(2) << 20), 0u);
    }
    std::memset(block.data(), 0xAB, bytes);
    EXPECT_EQ(static_cast<unsigned char*>(block.data())[bytes - 1], 0xAB);
    MappedBlock moved = std::move(block);
    EXPECT_EQ(block.data(), nullptr);
    EXPECT_EQ(moved.bytes(), bytes);
  }
  // Photon arrays of any size take the same path: a vector grows across the threshold.
  PhotonArray<IndirectPhoton> a;
  for (uint32_t i = 0; i < 200000; ++i) a.push_back({Vec3(float(i)), PackedPower(), i, i});
  for (uint32_t i = 0; i < 200000; i += 997) ASSERT_EQ(a[i].direction, i);
}

}  // namespace
}  // namespace penumbra
