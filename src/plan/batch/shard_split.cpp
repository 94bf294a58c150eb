// Longest-processing-time placement of photon-key groups (plan/batch/shard_split.h).
#include "plan/batch/shard_split.h"
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace penumbra {

std::vector<size_t> ShardSplit::jobsOf(size_t shard) const {
  std::vector<size_t> out;
  for (size_t j = 0; j < shardOf.size(); ++j) if (shardOf[j] == shard) out.push_back(j);
  return out;
}

namespace {

// Jobs of one group that one shard renders, and what they cost it.
struct Piece {
  std::vector<size_t> jobs;
  double seconds = 0.0;
};

}  // namespace

ShardSplit splitShards(const std::vector<JobCost>& jobs, size_t count) {
  ShardSplit split;
  split.shardOf.assign(jobs.size(), 0);
  split.shardSeconds.assign(std::max<size_t>(count, 1), 0.0);
  if (jobs.empty() || count <= 1) {
    for (const JobCost& j : jobs) split.shardSeconds[0] += j.frameSeconds;
    return split;
  }
  // Groups in order of their first job; each pays its maps once.
  std::map<size_t, size_t> groupIndex;
  std::vector<std::vector<size_t>> groups;
  std::vector<double> photons;
  for (size_t j = 0; j < jobs.size(); ++j) {
    auto [it, added] = groupIndex.try_emplace(jobs[j].group, groups.size());
    if (added) {
      groups.emplace_back();
      photons.push_back(0.0);
    }
    groups[it->second].push_back(j);
    photons[it->second] = std::max(photons[it->second], jobs[j].photonSeconds);
  }
  double total = 0.0;
  for (size_t g = 0; g < groups.size(); ++g) {
    total += photons[g];
    for (size_t j : groups[g]) total += jobs[j].frameSeconds;
  }
  const double fair = total / double(count);
  // A group above a fair share is cut into runs of consecutive jobs, each paying the maps.
  std::vector<Piece> pieces;
  for (size_t g = 0; g < groups.size(); ++g) {
    double frames = 0.0;
    for (size_t j : groups[g]) frames += jobs[j].frameSeconds;
    const size_t runs = std::min(groups[g].size(),
                                 std::max<size_t>(1, static_cast<size_t>(std::ceil((photons[g] + frames) / fair - 1e-9))));
    // A run ends once the frames placed reach its share of the group's.
    const double target = frames / double(runs);
    Piece piece;
    double placed = 0.0;
    size_t made = 0;
    for (size_t k = 0; k < groups[g].size(); ++k) {
      const size_t j = groups[g][k];
      piece.jobs.push_back(j);
      piece.seconds += jobs[j].frameSeconds;
      placed += jobs[j].frameSeconds;
      const bool last = k + 1 == groups[g].size();
      if (last || (made + 1 < runs && placed >= target * double(made + 1))) {
        piece.seconds += photons[g];
        pieces.push_back(std::move(piece));
        piece = Piece{};
        ++made;
      }
    }
  }
  // Largest first, each onto the least-loaded shard (ties: the lower index).
  std::vector<size_t> order(pieces.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return pieces[a].seconds > pieces[b].seconds; });
  for (size_t p : order) {
    const size_t s = static_cast<size_t>(std::min_element(split.shardSeconds.begin(), split.shardSeconds.end()) -
                                         split.shardSeconds.begin());
    split.shardSeconds[s] += pieces[p].seconds;
    for (size_t j : pieces[p].jobs) split.shardOf[j] = s;
  }
  return split;
}

}  // namespace penumbra
