// Prefix cuts: which batches a smaller budget covers, and where its photons end.
#include "emit/photon_prefix.h"
#include <algorithm>

namespace penumbra {

PrefixCuts::PrefixCuts(const std::vector<double>& weights, const std::vector<uint64_t>& counts,
                       const std::vector<uint64_t>& budgets, const std::vector<PhotonBatch>& batches)
    : batches_(batches), marks_(batches.size()), recorded_(batches.size()) {
  uint64_t total = 0;
  for (uint64_t c : counts) total += c;
  std::vector<uint64_t> sorted(budgets);
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  for (uint64_t budget : sorted) {
    if (budget >= total) continue;  // the full emission itself, or more than it
    std::vector<uint64_t> share = splitByWeight(weights, budget);
    bool prefix = true;
    for (size_t l = 0; l < counts.size(); ++l) prefix = prefix && share[l] <= counts[l];
    if (!prefix) continue;
    PrefixCut cut;
    cut.budget = budget;
    cut.emitted = share;
    cuts_.push_back(std::move(cut));
  }
  // A cut ends in the batch holding its light's last photon (none if it takes 0).
  for (size_t b = 0; b < batches.size(); ++b) {
    const PhotonBatch& batch = batches[b];
    for (size_t c = 0; c < cuts_.size(); ++c) {
      const uint64_t n = cuts_[c].emitted[batch.light];
      if (n > batch.first && n <= batch.first + batch.count) marks_[b].push_back({n - batch.first, c});
    }
    std::sort(marks_[b].begin(), marks_[b].end(),
              [](const Mark& x, const Mark& y) { return x.after < y.after; });
    recorded_[b].assign(marks_[b].size(), 0);
  }
}

void PrefixCuts::finish(const std::vector<size_t>& storedPerBatch) {
  const size_t lights = cuts_.empty() ? 0 : cuts_[0].emitted.size();
  std::vector<size_t> offset(storedPerBatch.size() + 1, 0);
  for (size_t b = 0; b < storedPerBatch.size(); ++b) offset[b + 1] = offset[b] + storedPerBatch[b];
  std::vector<size_t> lightBegin(lights, 0);
  std::vector<bool> seen(lights, false);
  for (size_t b = 0; b < batches_.size(); ++b) {
    const uint32_t l = batches_[b].light;
    if (!seen[l]) { lightBegin[l] = offset[b]; seen[l] = true; }
  }
  for (PrefixCut& cut : cuts_) {
    cut.begin = lightBegin;
    cut.end = lightBegin;  // a light taking 0 photons: an empty range
    cut.powerScale.assign(lights, 1.0f);
  }
  for (size_t b = 0; b < batches_.size(); ++b) {
    const uint32_t l = batches_[b].light;
    for (size_t m = 0; m < marks_[b].size(); ++m) {
      cuts_[marks_[b][m].cut].end[l] = offset[b] + recorded_[b][m];
    }
  }
  // The full count per light, from the batches (the last batch of each light ends it).
  std::vector<uint64_t> full(lights, 0);
  for (const PhotonBatch& batch : batches_) full[batch.light] = batch.first + batch.count;
  for (PrefixCut& cut : cuts_) {
    for (size_t l = 0; l < lights; ++l) {
      if (cut.emitted[l] > 0) cut.powerScale[l] = static_cast<float>(double(full[l]) / double(cut.emitted[l]));
    }
  }
}

const PrefixCut* PrefixCuts::find(uint64_t budget) const {
  for (const PrefixCut& c : cuts_) {
    if (c.budget == budget) return &c;
  }
  return nullptr;
}

namespace {

// Each light's range of the cut, in light order, through `adjust(photon, light)`.
template <class Photon, class Adjust>
PhotonArray<Photon> copyRanges(const PhotonBatches<Photon>& all, const PrefixCut& cut, Adjust&& adjust) {
  PhotonArray<Photon> out;
  size_t n = 0;
  for (size_t l = 0; l < cut.begin.size(); ++l) n += cut.end[l] - cut.begin[l];
  out.reserve(n);
  for (size_t l = 0; l < cut.begin.size(); ++l) {
    all.forRange(cut.begin[l], cut.end[l], [&](size_t, const Photon& p) { out.push_back(adjust(p, l)); });
  }
  return out;
}

}  // namespace

PhotonArray<ShadowPhoton> takePrefix(const PhotonBatches<ShadowPhoton>& all, const PrefixCut& cut) {
  return copyRanges(all, cut, [](const ShadowPhoton& p, size_t) { return p; });
}

namespace {
// Power-carrying photons, rescaled to the cut's count per light.
template <class Photon>
PhotonArray<Photon> rescaledPrefix(const PhotonBatches<Photon>& all, const PrefixCut& cut) {
  return copyRanges(all, cut, [&](Photon p, size_t light) {
    p.power = PackedPower(p.power.color() * cut.powerScale[light]);
    return p;
  });
}
}  // namespace

PhotonArray<IndirectPhoton> takePrefix(const PhotonBatches<IndirectPhoton>& all, const PrefixCut& cut) {
  return rescaledPrefix(all, cut);
}

PhotonArray<VolumePhoton> takePrefix(const PhotonBatches<VolumePhoton>& all, const PrefixCut& cut) {
  return rescaledPrefix(all, cut);
}

}  // namespace penumbra
