// The lookup cache's gate verdicts: per cell, each light's vote over the photons
// around the cell (further around where they are sparse), each stratum's of an area
// light too, and a split line for a stratum whose photons there disagree.
#include "gather/lookup_cache/lookup_cache.h"
#include "gather/lookup_cache/lookup_cache_cells.h"
#include "core/light_strata.h"
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <algorithm>
#include <array>

namespace penumbra {

namespace {

// A cell's neighbourhood is the cells within `reach` of it along each axis, in its
// own normal bucket: every photon within `reach` cells of any point of the cell.
// Where the nearest cells hold fewer voters than the quorum, the gate looks twice as
// far across the surface, as a k-nearest gather widens its radius where photons are
// sparse.
constexpr int kReach = 1, kSparseReach = 2;

// The cells a reach spans either side along each axis: across the surface the reach,
// along the normal's axis (bucket / 2) at most one, since a surface a cell or more
// behind this one (a teapot's body behind its handle) can be in a shadow it is not.
struct Reach3 {
  int x, y, z;
};
Reach3 reachOf(const CellKey& c, int reach) {
  int r[3] = {reach, reach, reach};
  r[LookupCache::bucketAxis(c.bucket)] = std::min(reach, 1);
  return {r[0], r[1], r[2]};
}

// The vote over the wider neighbourhood, kept only where the nearer one's voters, too
// few for its quorum, are there and agree: photons two cells away on a curved surface
// can all lie in a shadow the cell itself is not in.
GateVerdict widenedVerdict(const GateCounts& near, const GateCounts& wide, const GateParams& params) {
  const GateVerdict v = verdictOf(wide, params);
  GateParams any = params;
  any.minVoters = 1;
  return v != GateVerdict::Mixed && verdictOf(near, any) == v ? v : GateVerdict::Mixed;
}

struct SplitRecord {
  uint32_t record, column;
  StratumSplit split;
  bool operator<(const SplitRecord& o) const { return record != o.record ? record < o.record : column < o.column; }
};

// Per-thread scratch: the summed counts per stratum at both reaches, and one light's
// photon positions per stratum for the splits.
struct VoteScratch {
  std::vector<GateCounts> near, wide;
  std::array<std::vector<Vec3>, kMaxLightStrata> lit, shadowed;
  std::vector<SplitRecord> splits;
};

uint32_t voters(const GateCounts& c) { return c.direct + c.opaque + c.glass; }

// A light's own counts: the sum of its strata's, sum[first..last).
GateCounts total(const std::vector<GateCounts>& sum, uint32_t first, uint32_t last) {
  GateCounts all;
  for (uint32_t i = first; i < last; ++i) {
    all.direct += sum[i].direct;
    all.opaque += sum[i].opaque;
    all.glass += sum[i].glass;
  }
  return all;
}

}  // namespace

void LookupCache::voteGate(const CacheCells& cells, const ShadowPhotonMap& shadow, const LookupCacheParams& params) {
  const GateParams& g = params.gateParams;
  const GateParams stratumParams = g.forStratum();
  const size_t numStrata = cells.numStrata;
  verdicts_.assign(records_ * rowWidth_, static_cast<uint8_t>(GateVerdict::Mixed));

  // Each record within `reach` of cell c (reachOf's span), in its bucket.
  auto forEachAround = [&](const CellKey& c, int reach, auto&& visit) {
    const Reach3 span = reachOf(c, reach);
    for (int dz = -span.z; dz <= span.z; ++dz)
      for (int dy = -span.y; dy <= span.y; ++dy)
        for (int dx = -span.x; dx <= span.x; ++dx) {
          const int32_t n = recordOf(keyOf(c.x + dx, c.y + dy, c.z + dz, c.bucket));
          if (n >= 0) visit(static_cast<size_t>(n));
        }
  };
  auto sumAround = [&](const CellKey& c, int reach, std::vector<GateCounts>& sum) {
    std::fill(sum.begin(), sum.end(), GateCounts{});
    forEachAround(c, reach, [&](size_t n) {
      for (size_t i = 0; i < numStrata; ++i) {
        const CellCounts& k = cells.counts[n * numStrata + i];
        sum[i].direct += k.direct;
        sum[i].opaque += k.opaque;
        sum[i].glass += k.glass;
      }
    });
  };
  // Light l's photons within `reach` of cell c that its neighbour cells counted, by
  // stratum and kind (strata whose `want` is false skipped).
  auto collect = [&](const CellKey& c, int reach, uint32_t l, const bool* want, VoteScratch& s) {
    for (int i = 0; i < strata_[l]; ++i) s.lit[i].clear(), s.shadowed[i].clear();
    forEachAround(c, reach, [&](size_t n) {
      const NormalFilter filter(cells.normals[n], g.minNormalCos);
      for (uint32_t e = cells.starts[n]; e < cells.starts[n + 1]; ++e) {
        if (cells.entries[e].source != l + 1) continue;
        const ShadowPhoton& ph = shadow.photons(l)[cells.entries[e].index];
        if (!want[ph.stratum] || !filter.passes(ph.normal)) continue;
        (ph.shadow == kDirect ? s.lit : s.shadowed)[ph.stratum].push_back(ph.position);
      }
    });
  };

  // Cell r's own voters among strata [first, last).
  auto ownVoters = [&](size_t r, uint32_t first, uint32_t last) {
    uint32_t n = 0;
    for (uint32_t i = first; i < last; ++i) {
      const CellCounts& k = cells.counts[r * numStrata + i];
      n += uint32_t(k.direct) + k.opaque + k.glass;
    }
    return n;
  };
  tbb::enumerable_thread_specific<VoteScratch> scratch([&] {
    VoteScratch s;
    s.near.resize(numStrata);
    s.wide.resize(numStrata);
    return s;
  });
  tbb::parallel_for(tbb::blocked_range<size_t>(0, records_, 256), [&](const auto& range) {
    VoteScratch& s = scratch.local();
    for (size_t r = range.begin(); r != range.end(); ++r) {
      const CellKey c = decodeCellKey(cells.keys[r]);
      sumAround(c, kReach, s.near);
      bool wideSummed = false;
      uint8_t* row = &verdicts_[r * rowWidth_];
      for (uint32_t l = 0; l < numLights_; ++l) {
        const uint32_t first = strataStart_[l], last = first + strata_[l];
        const GateCounts near = total(s.near, first, last);
        int reach = kReach;
        GateVerdict v = verdictOf(near, g);
        if (voters(near) < static_cast<uint32_t>(g.minVoters)) {
          if (!wideSummed) sumAround(c, kSparseReach, s.wide);
          wideSummed = true;
          reach = kSparseReach;
          v = widenedVerdict(near, total(s.wide, first, last), g);
        }
        // A shadow needs a voter in the cell itself: from its neighbours alone it can
        // belong to a surface beside the cell's (a handle's lit inside beside its
        // shadowed arc). A lit verdict may come from them alone: sparse lit ground
        // (a far floor) is much of what the gate saves.
        if (v == GateVerdict::Shadowed && ownVoters(r, first, last) == 0) v = GateVerdict::Mixed;
        row[l] = static_cast<uint8_t>(v);
        const bool mixed = strata_[l] > 1 && row[l] == uint8_t(GateVerdict::Mixed);
        // Per stratum: its own reach (further where its own voters are too few), its
        // verdict there, and whether a split line can decide it.
        bool split[2][kMaxLightStrata] = {}, anySplit[2] = {};
        for (uint32_t i = first; i < last; ++i) {
          int own = reach;
          if (mixed && own == kReach && voters(s.near[i]) < static_cast<uint32_t>(stratumParams.minVoters)) {
            if (!wideSummed) sumAround(c, kSparseReach, s.wide);
            wideSummed = true;
            own = kSparseReach;
          }
          const GateCounts* k = own == kReach ? &s.near[i] : &s.wide[i];
          row[numLights_ + i] = static_cast<uint8_t>(
              own == kReach ? verdictOf(*k, stratumParams) : widenedVerdict(s.near[i], *k, stratumParams));
          // Both kinds among a stratum's voters, and no glass whose tint only a ray
          // can measure: the line between them may decide most of the cell.
          const uint32_t shadowed = k->opaque + (g.glassBlocks ? k->glass : 0);
          const bool fits = mixed && k->direct > 0 && shadowed > 0 && (g.glassBlocks || k->glass == 0);
          split[own == kSparseReach][i - first] = fits;
          anySplit[own == kSparseReach] = anySplit[own == kSparseReach] || fits;
        }
        for (int wide = 0; wide < 2; ++wide) {
          if (!anySplit[wide]) continue;
          const int at = wide ? kSparseReach : kReach;
          collect(c, at, l, split[wide], s);
          for (uint32_t i = first; i < last; ++i) {
            if (!split[wide][i - first]) continue;
            const auto& lit = s.lit[i - first];
            const auto& dark = s.shadowed[i - first];
            const float margin = kSplitMarginOfWidth * static_cast<float>(2 * at + 1) * cell_;
            const std::optional<StratumSplit> fit =
                fitStratumSplit(lit.data(), lit.size(), dark.data(), dark.size(), margin);
            if (!fit) continue;
            row[numLights_ + i] = kSplit;
            s.splits.push_back({static_cast<uint32_t>(r), static_cast<uint32_t>(numLights_ + i), *fit});
          }
        }
      }
    }
    progressAdd(params.progress, range.size());
  });

  // The splits in record order, whichever thread fitted them.
  std::vector<SplitRecord> all;
  for (VoteScratch& s : scratch) all.insert(all.end(), s.splits.begin(), s.splits.end());
  std::sort(all.begin(), all.end());
  splits_.resize(all.size());
  splitStart_.assign(records_ + 1, 0);
  for (size_t i = 0; i < all.size(); ++i) {
    splits_[i] = all[i].split;
    ++splitStart_[all[i].record + 1];
  }
  for (size_t r = 0; r < records_; ++r) splitStart_[r + 1] += splitStart_[r];
}

const StratumSplit& LookupCache::splitAt(const uint8_t* row, size_t column) const {
  const size_t record = static_cast<size_t>(row - verdicts_.data()) / rowWidth_;
  size_t index = splitStart_[record];
  for (size_t i = numLights_; i < column; ++i) index += row[i] == kSplit;
  return splits_[index];
}

}  // namespace penumbra
