// batch --stats (plan/batch/batch_stats.h).
#include "plan/batch/batch_stats.h"
#include <nlohmann/json.hpp>

namespace penumbra {

std::string batchStatsJson(const BatchOutcome& o) {
  nlohmann::json j;
  j["jobs"] = {{"total", o.jobs.size()}, {"rendered", o.rendered}, {"up_to_date", o.upToDate},
               {"not_up_to_date", o.notUpToDate}, {"failed", o.failed}};
  j["shard"] = o.shardLabel;
  j["scene_files_read"] = o.sceneReads;
  j["scenes_built"] = o.sceneBuilds;
  j["photon_maps"] = {{"built", o.photonBuilds}, {"reused", o.photonReuses}, {"evicted", o.evictions},
                      {"cache_peak_bytes", o.peakCacheBytes},
                      {"files_loaded", o.mapLoads}, {"files_written", o.mapWrites}};
  j["seconds"] = o.seconds;
  j["cpu_seconds"] = o.cpu.cpuSeconds;
  j["job_list"] = nlohmann::json::array();
  for (const BatchJobResult& r : o.jobs) {
    j["job_list"].push_back({{"name", r.name}, {"status", r.status}, {"seconds", r.seconds},
                             {"cpu_seconds", r.cpu.cpuSeconds}, {"estimate_seconds", r.estimate}});
  }
  return j.dump(2) + "\n";
}

}  // namespace penumbra
