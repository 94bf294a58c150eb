// Longest-processing-time placement of photon-key groups, and larger groups cut to
// fill the shards to one level (plan/batch/shard_split.h).
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
  split.jobSeconds.assign(jobs.size(), 0.0);
  split.shardSeconds.assign(std::max<size_t>(count, 1), 0.0);
  if (jobs.empty()) return split;
  // Groups in order of their first job; each pays its maps once.
  std::map<size_t, size_t> groupIndex;
  std::vector<std::vector<size_t>> groups;
  std::vector<double> photons, module;
  for (size_t j = 0; j < jobs.size(); ++j) {
    auto [it, added] = groupIndex.try_emplace(jobs[j].group, groups.size());
    if (added) {
      groups.emplace_back();
      photons.push_back(0.0);
      module.push_back(0.0);
    }
    groups[it->second].push_back(j);
    photons[it->second] = std::max(photons[it->second], jobs[j].photonSeconds);
    module[it->second] = std::max(module[it->second], jobs[j].moduleSeconds);
  }
  // The module counts once: the farm's least (one shard loads it).
  double total = *std::max_element(module.begin(), module.end());
  for (size_t g = 0; g < groups.size(); ++g) {
    total += photons[g];
    for (size_t j : groups[g]) total += jobs[j].frameSeconds;
  }
  const double fair = total / double(split.shardSeconds.size());
  const auto frameSeconds = [&](size_t g) {
    double frames = 0.0;
    for (size_t j : groups[g]) frames += jobs[j].frameSeconds;
    return frames;
  };
  // The image module, loaded once by a shard for every job that reads textures.
  std::vector<double> loaded(split.shardSeconds.size(), 0.0);
  const auto moduleFor = [&](size_t g, size_t shard) { return std::max(0.0, module[g] - loaded[shard]); };
  // A piece's first job carries its maps and the module where the shard lacks it.
  const auto place = [&](size_t g, const std::vector<size_t>& pieceJobs, double seconds, size_t shard) {
    const double loads = moduleFor(g, shard);
    split.shardSeconds[shard] += seconds + loads;
    loaded[shard] = std::max(loaded[shard], module[g]);
    for (size_t j : pieceJobs) split.shardOf[j] = shard, split.jobSeconds[j] = jobs[j].frameSeconds;
    split.jobSeconds[pieceJobs.front()] += photons[g] + loads;
  };
  // Groups within a fair share stay whole: largest first, each onto the shard it
  // leaves least loaded (its module counted where that shard lacks it; ties: the
  // lower index).
  std::vector<size_t> whole, cut;
  for (size_t g = 0; g < groups.size(); ++g) (photons[g] + frameSeconds(g) > fair ? cut : whole).push_back(g);
  const auto bySize = [&](size_t a, size_t b) { return photons[a] + frameSeconds(a) > photons[b] + frameSeconds(b); };
  std::stable_sort(whole.begin(), whole.end(), bySize);
  std::stable_sort(cut.begin(), cut.end(), bySize);
  for (size_t g : whole) {
    size_t s = 0;
    for (size_t t = 1; t < split.shardSeconds.size(); ++t)
      if (split.shardSeconds[t] + moduleFor(g, t) < split.shardSeconds[s] + moduleFor(g, s)) s = t;
    place(g, groups[g], photons[g] + frameSeconds(g), s);
  }
  // A larger group is cut into runs of consecutive jobs that fill the least-loaded
  // shards up to one level, each run paying the maps: the level L where the m lowest
  // shards take the frames and m maps, L = (their load + frames + m x maps) / m,
  // with m the fewest shards whose level lies below the next one's load.
  for (size_t g : cut) {
    // A shard's load as this group sees it: the module counted where the shard lacks it.
    std::vector<double> load(split.shardSeconds.size());
    for (size_t s = 0; s < load.size(); ++s) load[s] = split.shardSeconds[s] + moduleFor(g, s);
    std::vector<size_t> order(load.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return load[a] < load[b]; });
    const double frames = frameSeconds(g);
    double below = 0.0, level = 0.0;
    size_t m = 0;
    while (m < order.size()) {
      below += load[order[m]];
      ++m;
      level = (below + frames + double(m) * photons[g]) / double(m);
      if (m == order.size() || level <= load[order[m]]) break;
    }
    size_t k = 0;
    for (size_t r = 0; r < m && k < groups[g].size(); ++r) {
      const size_t shard = order[r];
      const double room = level - load[shard] - photons[g];
      Piece piece;
      // A job goes in while at least half of it fits; the last run takes the rest.
      while (k < groups[g].size() &&
             (r + 1 == m || piece.jobs.empty() || piece.seconds + 0.5 * jobs[groups[g][k]].frameSeconds <= room)) {
        piece.jobs.push_back(groups[g][k]);
        piece.seconds += jobs[groups[g][k]].frameSeconds;
        ++k;
      }
      place(g, piece.jobs, piece.seconds + photons[g], shard);
    }
  }
  return split;
}

}  // namespace penumbra
