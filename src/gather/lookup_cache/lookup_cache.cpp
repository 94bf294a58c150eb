// Building the lookup cache: bin photons into (cell, normal bucket) keys, count the
// gate's photons per key, then vote and estimate once per key, in parallel.
#include "gather/lookup_cache/lookup_cache.h"
#include "gather/lookup_cache/lookup_cache_cells.h"
#include "gather/kth_distance.h"
#include "gather/radiance_estimate.h"
#include "gather/morton.h"
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {
constexpr int64_t kAxisCells = int64_t(1) << 20;  // 20 bits per axis in a key


// Median k-th-neighbour distance at up to 256 photons of one shadow light (without
// its KD-tree, which precomputed lookups leave unbuilt).
float typicalShadowRadius(const ShadowPhotonMap& map, int k) {
  uint32_t best = 0;
  for (uint32_t l = 0; l < map.numLights(); ++l)
    if (map.photons(l).size() > map.photons(best).size()) best = l;
  const auto& photons = map.photons(best);
  if (photons.empty() || k <= 0) return 0.0f;
  const size_t probes = std::min<size_t>(256, photons.size()), step = photons.size() / probes;
  std::vector<Vec3> sites;
  for (size_t i = 0; i < probes; ++i) sites.push_back(photons[i * step].position);
  std::vector<float> radii = kthNearestDistances(photons.data(), photons.size(), sites, static_cast<size_t>(k));
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  return radii[radii.size() / 2];
}
}  // namespace

float cacheCellSize(const IndirectPhotonMap* indirect, int k, const ShadowPhotonMap* shadow,
                    int kShadow, float scale) {
  GatherScratch scratch;
  if (indirect && !indirect->empty() && k > 0) return cacheCellSize(typicalKnnRadius(*indirect, k, scratch), k, scale);
  if (shadow && shadow->size() > 0 && kShadow > 0) {
    return cacheCellSize(typicalShadowRadius(*shadow, kShadow), kShadow, scale,
                         kMinPhotonsPerGateCell);
  }
  return 0.0f;
}

namespace {
// The cell in units of r: k photons within r put k h^2 / (pi r^2) of them in a cell
// of h, so at least minPhotonsPerCell where h >= r sqrt(minPhotonsPerCell pi / k).
float cellScale(int k, float scale, float minPhotonsPerCell) {
  return std::max(scale, std::sqrt(minPhotonsPerCell * kPi / static_cast<float>(k)));
}
}  // namespace

float cacheCellSize(float r, int k, float scale, float minPhotonsPerCell) {
  if (!(r > 0.0f) || k <= 0) return 0.0f;
  return r * cellScale(k, scale, minPhotonsPerCell);
}

float photonsPerCacheCell(int k, float scale, float minPhotonsPerCell) {
  if (k <= 0) return minPhotonsPerCell;
  const float h = cellScale(k, scale, minPhotonsPerCell);
  return static_cast<float>(k) * h * h / kPi;
}

uint64_t LookupCache::keyOf(int64_t x, int64_t y, int64_t z, unsigned bucket) const {
  if (x < 0 || y < 0 || z < 0 || x >= kAxisCells || y >= kAxisCells || z >= kAxisCells)
    return kEmpty;
  return (uint64_t(x) << 44) | (uint64_t(y) << 24) | (uint64_t(z) << 4) | bucket;
}

uint64_t LookupCache::keyAt(const Vec3& p, unsigned bucket) const {
  const Vec3 u = (p - origin_) * invCell_;
  return keyOf(static_cast<int64_t>(std::floor(u.x)), static_cast<int64_t>(std::floor(u.y)),
               static_cast<int64_t>(std::floor(u.z)), bucket);
}

const LookupCache::Slot* LookupCache::slotOf(uint64_t key) const {
  if (key == kEmpty || slots_.empty()) return nullptr;
  const size_t mask = slots_.size() - 1;
  for (size_t i = slotHash(key) & mask;; i = (i + 1) & mask) {
    const Slot& s = slots_[i];
    if (s.key == key) return &s;
    if (s.key == kEmpty) return nullptr;
  }
}

void LookupCache::insertKeys(const std::vector<uint64_t>& keys) {
  size_t size = 16;
  while (size < 2 * keys.size()) size *= 2;
  slots_.assign(size, Slot{});
  const size_t mask = size - 1;
  for (uint32_t r = 0; r < keys.size(); ++r) {
    size_t i = slotHash(keys[r]) & mask;
    while (slots_[i].key != kEmpty) i = (i + 1) & mask;
    slots_[i].key = keys[r];
    slots_[i].record = r;
  }
}

namespace {
// Where the irradiance estimate of the record in cell `c` is taken: the cell's centre
// across the surface, within its photons' extent, on their plane (centroid, mean
// normal). Not their centroid: the k nearest around a point the photons chose are
// denser than around a fixed one, more so at the small k late progressive passes
// reach, and find() blends the cells' values as at their centres.
Vec3 centredSite(const CellKey& c, const Vec3& centre, const Vec3& centroid, const Vec3& normal,
                 const Bounds& extent) {
  const unsigned axis = LookupCache::bucketAxis(c.bucket), t1 = (axis + 1) % 3, t2 = (axis + 2) % 3;
  Vec3 site = centroid;
  for (unsigned t : {t1, t2}) site[t] = std::clamp(centre[t], extent.lo[t], extent.hi[t]);
  // Along the bucket's axis (the normal's largest component): onto the photons' plane.
  if (std::abs(normal[axis]) > 0.0f)
    site[axis] -= (normal[t1] * (site[t1] - centroid[t1]) + normal[t2] * (site[t2] - centroid[t2])) / normal[axis];
  return site;
}
}  // namespace

void LookupCache::build(const ShadowPhotonMap* shadow, const IndirectPhotonMap* indirect,
                        const LookupCacheParams& params) {
  *this = LookupCache{};
  numLights_ = params.gate && shadow ? shadow->numLights() : 0;
  const bool useIndirect = params.indirect != CachedIndirect::None && indirect && !indirect->empty();
  // The sources: 0 the indirect map, 1 + l the shadow photons of light l.
  std::vector<size_t> sourceSize{useIndirect ? indirect->size() : 0};
  for (uint32_t l = 0; l < numLights_; ++l) sourceSize.push_back(shadow->photons(l).size());
  std::vector<size_t> offsets{0};
  for (size_t c : sourceSize) offsets.push_back(offsets.back() + c);
  const size_t total = offsets.back();
  if (total == 0 || !(params.cellSize > 0.0f)) return;

  auto photonPos = [&](size_t src, size_t i) -> const Vec3& {
    return src == 0 ? indirect->photons()[i].position : shadow->photons(src - 1)[i].position;
  };
  // A shadow photon met from behind keys the back side's bucket; indirect photons
  // carry no side (their estimate is read on the front side's keys).
  auto photonBucket = [&](size_t src, size_t i, const Vec3& n) {
    const bool back = src != 0 && shadow->photons(static_cast<uint32_t>(src - 1))[i].backSide;
    return sidedBucket(bucketOf(n), back);
  };
  auto photonNormal = [&](size_t src, size_t i) {
    return decodeOctahedral(src == 0 ? indirect->photons()[i].normal
                                     : shadow->photons(static_cast<uint32_t>(src - 1))[i].normal);
  };

  // Cells are counted from below the photons' box, so every neighbour of an occupied
  // cell has a valid key; the cell grows if the box would need > 2^20 per axis.
  Bounds box;
  for (size_t src = 0; src < sourceSize.size(); ++src)
    for (size_t i = 0; i < sourceSize[src]; ++i) box.extend(photonPos(src, i));
  const Vec3 extent = box.hi - box.lo;
  const float widest = std::max({extent.x, extent.y, extent.z});
  cell_ = std::max(params.cellSize, widest / static_cast<float>(kAxisCells - 4));
  invCell_ = 1.0f / cell_;
  // One and a half cells below the box: its faces (often the floor and outer walls)
  // land mid-layer, not on a layer boundary a point could round across.
  origin_ = box.lo - Vec3(1.5f * cell_);

  CacheCells cells;
  PhotonArray<CacheEntry>& entries = cells.entries;
  entries.resize(total);
  for (size_t src = 0; src < sourceSize.size(); ++src) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, sourceSize[src], 1 << 14), [&](const auto& r) {
      for (size_t i = r.begin(); i != r.end(); ++i)
        entries[offsets[src] + i] = {keyAt(photonPos(src, i), photonBucket(src, i, photonNormal(src, i))),
                                     static_cast<uint32_t>(i), static_cast<uint32_t>(src)};
    });
  }
  sortCacheEntries(entries);
  std::vector<uint32_t>& starts = cells.starts;
  for (size_t i = 0; i < total; ++i)
    if (i == 0 || entries[i].key != entries[i - 1].key) starts.push_back(static_cast<uint32_t>(i));
  records_ = starts.size();
  starts.push_back(static_cast<uint32_t>(total));
  std::vector<uint64_t>& keys = cells.keys;
  keys.resize(records_);
  for (size_t r = 0; r < records_; ++r) keys[r] = entries[starts[r]].key;
  insertKeys(keys);
  progressExpect(params.progress, records_ * (1 + (numLights_ > 0) + useIndirect));

  // A light's strata are those its photons name; a light's own verdict sums them.
  strata_.assign(numLights_, 1);
  strataStart_.assign(numLights_, 0);
  size_t numStrata = 0;
  for (uint32_t l = 0; l < numLights_; ++l) {
    for (const ShadowPhoton& ph : shadow->photons(l))
      strata_[l] = std::max<uint8_t>(strata_[l], static_cast<uint8_t>(ph.stratum + 1));
    strataStart_[l] = static_cast<uint32_t>(numStrata);
    numStrata += strata_[l];
  }
  rowWidth_ = numLights_ + numStrata;
  cells.numStrata = numStrata;

  // Per record: where its photons are (centroid), which way they face (mean normal),
  // and per stratum of each light how many arrived direct, behind something opaque,
  // behind glass (saturating bytes: the vote only asks zero or not, and >= minVoters).
  std::vector<Vec3> sites(records_);
  std::vector<Vec3>& normals = cells.normals;
  normals.resize(records_);
  std::vector<CellCounts>& counts = cells.counts;
  counts.resize(records_ * numStrata);
  const float minCos = params.gateParams.minNormalCos;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, records_, 256), [&](const auto& range) {
    for (size_t r = range.begin(); r != range.end(); ++r) {
      Vec3 sum(0.0f), nsum(0.0f);
      Bounds spread;
      for (uint32_t e = starts[r]; e < starts[r + 1]; ++e) {
        const Vec3& pos = photonPos(entries[e].source, entries[e].index);
        sum += pos;
        spread.extend(pos);
        nsum += photonNormal(entries[e].source, entries[e].index);
      }
      sites[r] = sum / static_cast<float>(starts[r + 1] - starts[r]);
      normals[r] = glm::length(nsum) > 0.0f ? glm::normalize(nsum) : photonNormal(entries[starts[r]].source, entries[starts[r]].index);
      if (params.indirect == CachedIndirect::Irradiance) {
        const CellKey c = decodeCellKey(keys[r]);
        const Vec3 centre = origin_ + (Vec3(float(c.x), float(c.y), float(c.z)) + Vec3(0.5f)) * cell_;
        sites[r] = centredSite(c, centre, sites[r], normals[r], spread);
      }
      const NormalFilter filter(normals[r], minCos);
      for (uint32_t e = starts[r]; e < starts[r + 1]; ++e) {
        const uint32_t src = entries[e].source;
        if (src == 0) continue;
        const ShadowPhoton& ph = shadow->photons(src - 1)[entries[e].index];
        if (!filter.passes(ph.normal)) continue;
        CellCounts& c = counts[r * numStrata + strataStart_[src - 1] + ph.stratum];
        uint8_t& n = ph.shadow == kDirect ? c.direct : ph.shadow == kShadowGlass ? c.glass : c.opaque;
        if (n < 255) ++n;
      }
    }
    progressAdd(params.progress, range.size());
  });
  if (numLights_ > 0) voteGate(cells, *shadow, params);
  cells.entries = {};
  cells.counts = {};

  // The indirect estimate, by the exact estimator, at each record's site.
  if (!useIndirect) return;
  kind_ = params.indirect;
  std::vector<Color> values(records_, Color(0.0f));
  // Gathers in Morton order of their cells: consecutive queries are neighbours, so the
  // KD-tree's search hints and the caches serve them (keys order by x first).
  std::vector<std::pair<uint64_t, uint32_t>> order(records_);
  for (uint32_t r = 0; r < records_; ++r) {
    const CellKey c = decodeCellKey(keys[r]);
    order[r] = {spreadBits21(uint32_t(c.x)) << 2 | spreadBits21(uint32_t(c.y)) << 1 | spreadBits21(uint32_t(c.z)), r};
  }
  tbb::parallel_sort(order.begin(), order.end());
  k_ = params.k;
  maxRadius_ = params.maxRadius;
  radius_ = params.radius;
  tbb::enumerable_thread_specific<GatherScratch> scratch;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, records_, 64), [&](const auto& range) {
    GatherScratch& s = scratch.local();
    for (size_t i = range.begin(); i != range.end(); ++i) {
      const uint32_t r = order[i].second;
      // A back side's record holds shadow photons only: find reads no estimate there.
      if (!(decodeCellKey(keys[r]).bucket & kBackSideBucket))
        values[r] = estimateAt(*indirect, sites[r], normals[r], s);
    }
    progressAdd(params.progress, range.size());
  });
  for (Slot& slot : slots_)
    if (slot.key != kEmpty) slot.indirect = values[slot.record];
  makeLazyTable();
}

Color LookupCache::estimateAt(const IndirectPhotonMap& map, const Vec3& p, const Vec3& n,
                              GatherScratch& s) const {
  switch (kind_) {
    case CachedIndirect::Classic: return map.classic(p, n, k_, maxRadius_, s).value;
    case CachedIndirect::Density: return map.density(p, n, k_, maxRadius_, s).value;
    case CachedIndirect::Irradiance: {
      Bsdf white;  // rho = 1, no glossy or mirror part: photonRadiance = irradiance / pi
      white.type = BsdfType::Opaque;
      white.diffuse = Color(1.0f);
      return photonRadiance(map, white, BsdfFrame{n, n, true}, p, n, PhotonGather{k_, radius_}, s).value;
    }
    case CachedIndirect::None: break;
  }
  return Color(0.0f);
}

LookupCache::Answer LookupCache::find(const Vec3& p, const Vec3& n, bool backSide) const {
  Answer a;
  if (records_ == 0) return a;
  const unsigned bucket = bucketOf(n), axis = bucket / 2;
  const unsigned gateBucket = sidedBucket(bucket, backSide);
  const Vec3 cellOf = (p - origin_) * invCell_;
  int64_t own[3];  // p's own cell
  for (int i = 0; i < 3; ++i) own[i] = static_cast<int64_t>(std::floor(cellOf[i]));
  if (kind_ == CachedIndirect::None) {  // the gate alone reads only p's own cell
    const int32_t r = recordOf(keyOf(own[0], own[1], own[2], gateBucket));
    if (r >= 0) a.verdicts = &verdicts_[size_t(r) * rowWidth_];
    else if (numLights_ > 0) a.verdicts = verdictsAround(own, cellOf, gateBucket);
    return a;
  }
  // The surface runs across the bucket's axis: blend bilinearly over the 2x2 cells
  // around p along the other two axes, in p's own layer along this one.
  const unsigned t1 = (axis + 1) % 3, t2 = (axis + 2) % 3;
  const float u1 = cellOf[t1] - 0.5f, u2 = cellOf[t2] - 0.5f;
  const float b1 = std::floor(u1), b2 = std::floor(u2), f1 = u1 - b1, f2 = u2 - b2;
  Color sum(0.0f);
  float weight = 0.0f;
  int64_t c[3];
  c[axis] = own[axis];
  for (unsigned corner = 0; corner < 4; ++corner) {
    const unsigned d1 = corner & 1, d2 = corner >> 1;
    c[t1] = static_cast<int64_t>(b1) + d1;
    c[t2] = static_cast<int64_t>(b2) + d2;
    const Slot* slot = slotOf(keyOf(c[0], c[1], c[2], bucket));
    if (!slot) continue;
    const float w = (d1 ? f1 : 1.0f - f1) * (d2 ? f2 : 1.0f - f2);
    sum += w * slot->indirect;
    weight += w;
    if (c[t1] == own[t1] && c[t2] == own[t2] && numLights_ > 0 && !backSide)
      a.verdicts = &verdicts_[size_t(slot->record) * rowWidth_];
  }
  if (weight > 1e-6f) {
    a.indirect = sum / weight;
    a.hasIndirect = true;
  }
  if (backSide && numLights_ > 0) {
    const int32_t r = recordOf(keyOf(own[0], own[1], own[2], gateBucket));
    if (r >= 0) a.verdicts = &verdicts_[size_t(r) * rowWidth_];
  }
  if (!a.verdicts && numLights_ > 0) a.verdicts = verdictsAround(own, cellOf, gateBucket);
  return a;
}

const uint8_t* LookupCache::verdictsAround(const int64_t* own, const Vec3& cellOf, unsigned bucket) const {
  const unsigned axis = bucketAxis(bucket), t1 = (axis + 1) % 3, t2 = (axis + 2) % 3;
  int32_t nearest = -1;
  float best = kInf;
  int64_t c[3] = {own[0], own[1], own[2]};
  for (int d1 = -1; d1 <= 1; ++d1) {
    for (int d2 = -1; d2 <= 1; ++d2) {
      if (d1 == 0 && d2 == 0) continue;
      c[t1] = own[t1] + d1;
      c[t2] = own[t2] + d2;
      const int32_t r = recordOf(keyOf(c[0], c[1], c[2], bucket));
      if (r < 0) continue;
      // Distance from p to the cell's centre; ties keep the first in this fixed order.
      const float e1 = cellOf[t1] - (static_cast<float>(c[t1]) + 0.5f);
      const float e2 = cellOf[t2] - (static_cast<float>(c[t2]) + 0.5f);
      const float d = e1 * e1 + e2 * e2;
      if (d < best) {
        best = d;
        nearest = r;
      }
    }
  }
  return nearest >= 0 ? &verdicts_[size_t(nearest) * rowWidth_] : nullptr;
}

double LookupCache::estimateBytes(double records, size_t verdictColumns, double splitsPerRecord, bool indirect) {
  // insertKeys: 2 to 4 slots a record (a power of two), about 2 / ln 2 on average.
  double perRecord = 3.0 * sizeof(Slot);
  if (verdictColumns > 0)
    perRecord += static_cast<double>(verdictColumns) + sizeof(uint32_t) + splitsPerRecord * sizeof(StratumSplit);
  // makeLazyTable: records / 8 slots, doubled up to a power of two, at least 4096.
  const double lazy = indirect ? std::max(4096.0, records / 4.0) * sizeof(LazySlot) : 0.0;
  return records * perRecord + lazy;
}

size_t LookupCache::memoryBytes() const {
  return slots_.capacity() * sizeof(Slot) + verdicts_.capacity() + splits_.capacity() * sizeof(StratumSplit) +
         splitStart_.capacity() * sizeof(uint32_t) +
         (lazy_ ? (lazy_->mask + 1) * sizeof(LazySlot) : 0);
}

}  // namespace penumbra
