// Shard selection and the shard file (plan/batch/batch_shards.h).
#include "plan/batch/batch_shards.h"
#include "core/error.h"
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

namespace penumbra {

namespace {

constexpr size_t kMaxShards = 100000;
constexpr const char* kShardFileFormat = "penumbra-shards";
constexpr int kShardFileVersion = 1;

// A whole decimal number, nothing else.
bool parseCount(const std::string& text, size_t& value) {
  if (text.empty() || text.size() > 9 || !std::all_of(text.begin(), text.end(), ::isdigit)) return false;
  value = std::stoul(text);
  return true;
}

}  // namespace

std::pair<size_t, size_t> parseShard(const std::string& text) {
  size_t i = 0, n = 0;
  char slash = 0, extra = 0;
  std::istringstream in(text);
  if (!(in >> i >> slash >> n) || slash != '/' || (in >> extra) || n == 0 || i == 0 || i > n || n > kMaxShards) {
    throw InputError("--shard: expected I/N with 1 <= I <= N, got '" + text + "'");
  }
  return {i - 1, n};
}

ShardChoice shardFromSlash(const std::string& text) {
  const auto [index, count] = parseShard(text);
  return {index, count, fmt::format("shard {}/{}", index + 1, count)};
}

ShardChoice shardFromIndex(const std::string& index, size_t count) {
  if (count == 0 || count > kMaxShards) throw InputError(fmt::format("--shard-count: expected 1..{}, got {}", kMaxShards, count));
  std::string text = index, source = "--shard-index";
  if (index == "env") {
    const char* found = nullptr;
    for (const char* name : kShardIndexVariables) {
      if (std::getenv(name)) {
        found = name;
        break;
      }
    }
    if (!found) {
      throw InputError(fmt::format("--shard-index env: none of {} is set (run it as an array task, or give --shard-index I)",
                                   fmt::join(kShardIndexVariables, ", ")));
    }
    text = std::getenv(found);
    source = found;
  }
  size_t value = 0;
  if (!parseCount(text, value)) throw InputError(fmt::format("{}: expected a 0-based index, got '{}'", source, text));
  if (value >= count) {
    throw InputError(fmt::format("{}={} is not a shard of --shard-count {} (indices are 0-based: 0..{})", source, text,
                                 count, count - 1));
  }
  std::string label = fmt::format("shard {}/{}", value + 1, count);
  if (index == "env") label += fmt::format(" ({}={})", source, text);
  return {value, count, label};
}

std::string shardFileText(const ShardFile& file) {
  nlohmann::json j;
  j["format"] = kShardFileFormat;
  j["version"] = kShardFileVersion;
  j["jobs_file"] = file.jobsFile;
  j["count"] = file.shards.size();
  j["shards"] = nlohmann::json::array();
  for (size_t s = 0; s < file.shards.size(); ++s) {
    nlohmann::json jobs = nlohmann::json::array();
    for (const ShardFile::Job& job : file.shards[s]) jobs.push_back({{"name", job.name}, {"seconds", job.seconds}});
    j["shards"].push_back({{"index", s}, {"seconds", file.seconds[s]}, {"jobs", jobs}});
  }
  return j.dump(2) + "\n";
}

ShardFile readShardFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the shard file");
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  auto fail = [&](const std::string& where, const std::string& problem) -> void {
    throw InputError(path + ": " + where + ": " + problem + " (write it with batch --plan-shards N -o FILE)");
  };
  if (!j.is_object()) fail("(root)", "not a shard file (a JSON object)");
  if (j.value("format", "") != kShardFileFormat) fail("format", std::string("must be \"") + kShardFileFormat + "\"");
  if (!j.contains("version") || j["version"] != kShardFileVersion) fail("version", fmt::format("must be {}", kShardFileVersion));
  if (!j.contains("shards") || !j["shards"].is_array() || j["shards"].empty() || j["shards"].size() > kMaxShards)
    fail("shards", "must be a non-empty list");
  ShardFile file;
  file.jobsFile = j.value("jobs_file", "");
  std::map<std::string, std::string> seen;
  for (size_t s = 0; s < j["shards"].size(); ++s) {
    const nlohmann::json& shard = j["shards"][s];
    const std::string where = fmt::format("shards[{}]", s);
    if (!shard.is_object() || !shard.contains("jobs") || !shard["jobs"].is_array()) fail(where + ".jobs", "must be a list");
    const double seconds = shard.value("seconds", 0.0);
    file.seconds.push_back(std::isfinite(seconds) && seconds >= 0 ? seconds : 0.0);
    file.shards.emplace_back();
    for (size_t k = 0; k < shard["jobs"].size(); ++k) {
      const nlohmann::json& job = shard["jobs"][k];
      const std::string at = fmt::format("{}.jobs[{}]", where, k);
      if (!job.is_object() || !job.contains("name") || !job["name"].is_string()) fail(at + ".name", "must be a job name");
      const std::string name = job["name"].get<std::string>();
      if (!seen.emplace(name, at).second) fail(at + ".name", "'" + name + "' is also in " + seen[name]);
      const double s2 = job.contains("seconds") && job["seconds"].is_number() ? job["seconds"].get<double>() : 0.0;
      file.shards.back().push_back({name, std::isfinite(s2) && s2 >= 0 ? s2 : 0.0});
    }
  }
  if (j.contains("count") && j["count"] != file.shards.size()) fail("count", "does not match the shards listed");
  return file;
}

std::vector<size_t> jobsOfShardFile(const ShardFile& file, const std::vector<std::string>& names, size_t index,
                                    size_t* unplaced) {
  std::map<std::string, size_t> shardOf;
  size_t listed = 0;
  double sum = 0.0;
  for (size_t s = 0; s < file.shards.size(); ++s) {
    for (const ShardFile::Job& job : file.shards[s]) {
      shardOf[job.name] = s;
      sum += job.seconds;
      ++listed;
    }
  }
  const double mean = listed ? sum / double(listed) : 1.0;
  std::vector<double> load = file.seconds;
  std::vector<size_t> mine;
  size_t extra = 0;
  for (size_t j = 0; j < names.size(); ++j) {
    auto it = shardOf.find(names[j]);
    size_t s = 0;
    if (it != shardOf.end()) {
      s = it->second;
    } else {
      s = static_cast<size_t>(std::min_element(load.begin(), load.end()) - load.begin());
      load[s] += mean;
      ++extra;
    }
    if (s == index) mine.push_back(j);
  }
  if (unplaced) *unplaced = extra;
  return mine;
}

}  // namespace penumbra
