// Per-thread photon buffers that remember which batch wrote which run, so the
// merge can concatenate runs in batch order: deterministic for any thread count.
#pragma once
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <algorithm>
#include <cstdint>
#include <vector>

namespace penumbra {

template <class Photon>
class BatchBuffers {
 public:
  // The calling thread's buffer; a batch appends its photons and then calls endBatch.
  struct Local {
    std::vector<Photon> photons;
    struct Run { uint64_t batch; size_t begin, count; };
    std::vector<Run> runs;
    size_t open = 0;
    void endBatch(uint64_t batch) {
      runs.push_back({batch, open, photons.size() - open});
      open = photons.size();
    }
  };
  Local& local() { return buffers_.local(); }

  std::vector<Photon> merge() {
    struct Source { uint64_t batch; const Photon* data; size_t count; };
    std::vector<Source> sources;
    for (Local& l : buffers_) {
      for (const auto& run : l.runs) sources.push_back({run.batch, l.photons.data() + run.begin, run.count});
    }
    std::sort(sources.begin(), sources.end(), [](const Source& a, const Source& b) { return a.batch < b.batch; });
    std::vector<size_t> offset(sources.size() + 1, 0);
    for (size_t i = 0; i < sources.size(); ++i) offset[i + 1] = offset[i] + sources[i].count;
    std::vector<Photon> out(offset.back());
    tbb::parallel_for(size_t(0), sources.size(), [&](size_t i) {
      std::copy_n(sources[i].data, sources[i].count, out.begin() + offset[i]);
    });
    buffers_.clear();
    return out;
  }

 private:
  tbb::enumerable_thread_specific<Local> buffers_;
};

}  // namespace penumbra
