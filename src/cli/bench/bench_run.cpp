// The bench's schedule: validation of every scene first, then rounds of renders
// and control passes, each render a lone one (runRender: a fresh session, so load
// and BVH count as they would for the user).
#include "cli/bench/bench_run.h"
#include "cli/bench/compute_control.h"
#include "plan/cpu_report.h"
#include "plan/pipeline.h"
#include "plan/render_session.h"
#include "plan/transport_model.h"
#include "core/error.h"
#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

BenchSample controlPass(int threads, int round) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
  const CpuSpan span;
  computeControl();  // another translation unit: the call and its work stay
  BenchSample s;
  s.threads = threads;
  s.round = round;
  s.cpu = span.timing(threads);
  s.time.total = s.cpu.wallSeconds;
  return s;
}

}  // namespace

std::vector<int> parseThreadCounts(const std::string& list, int cores) {
  if (cores <= 0) cores = tbb::info::default_concurrency();
  std::vector<int> counts;
  const std::string usage = "--threads: expected thread counts like 1,2 (each 1.." + std::to_string(cores) + ")";
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    const std::string item = list.substr(start, comma - start);
    int n = 0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), n);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size() || n < 1) {
      throw InputError(usage + ", got '" + list + "'");
    }
    if (n > cores) {
      throw InputError(fmt::format("--threads: {} is more than the {} core{} this process may use", n, cores,
                                   cores == 1 ? "" : "s"));
    }
    if (std::count(counts.begin(), counts.end(), n)) throw InputError(fmt::format("--threads: {} is given twice", n));
    counts.push_back(n);
    start = comma + 1;
  }
  return counts;
}

std::string defaultBenchJson(const std::vector<std::string>& scenes) {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  const fs::path dir = xdg && *xdg ? fs::path(xdg) / "penumbra" / "bench"
                       : home && *home ? fs::path(home) / ".cache" / "penumbra" / "bench"
                                       : fs::temp_directory_path() / "penumbra-bench";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir.string() + ": cannot create the bench folder (" + ec.message() + "); give --json FILE");
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
  const std::string more = scenes.size() > 1 ? fmt::format("-and-{}-more", scenes.size() - 1) : "";
  return (dir / fmt::format("bench-{}{}-{}.json", fs::path(scenes.front()).stem().string(), more, stamp)).string();
}

BenchOutcome runBench(const BenchRequest& req) {
  const CpuSpan whole;
  if (req.scenes.empty()) throw InputError("bench: give at least one scene");
  if (req.repeat < 1) throw InputError(fmt::format("--repeat: expected a count of rounds, at least 1, got {}", req.repeat));
  BenchOutcome out;
  const int cores = tbb::info::default_concurrency();
  out.threads = !req.threads.empty() ? req.threads : cores > 1 ? std::vector<int>{1, cores} : std::vector<int>{1};
  out.repeat = req.repeat;
  out.overrides = req.session.overrides;
  const int most = *std::max_element(out.threads.begin(), out.threads.end());

  // 1. Every scene checked as its render would be, before the first render.
  for (const std::string& path : req.scenes) {
    if (path == "-") throw InputError("bench: a scene on stdin can be read only once; give a file");
    SessionOptions options = req.session;
    options.threads = most;
    options.progress = nullptr;
    RenderSession session(options);
    JobRequest request;
    request.scenePath = path;
    if (!req.jsonPath.empty()) request.outputs.push_back({req.jsonPath, "--json", false});
    const PlannedJob job = session.plan(request);
    SceneBench s;
    s.path = path;
    s.name = job.scene.name;
    s.settings = fmt::format("{}x{}, {} spp, {}", job.scene.camera.width, job.scene.camera.height,
                             job.scene.camera.spp, transportOf(job.scene).name());
    for (const std::string& n : job.notes) {
      if (std::find(out.notes.begin(), out.notes.end(), n) == out.notes.end()) out.notes.push_back(n);
    }
    out.scenes.push_back(std::move(s));
  }
  out.jsonPath = req.jsonPath.empty() ? defaultBenchJson(req.scenes) : req.jsonPath;

  // 2. Rounds: each scene at each thread count, then the control at each.
  const size_t total = size_t(req.repeat) * out.threads.size() * (req.scenes.size() + 1);
  size_t done = 0;
  auto report = [&](const std::string& item, const char* phase) {
    if (req.progress) req.progress(done, total, item, phase, whole.wallSeconds());
  };
  for (int round = 0; round < req.repeat; ++round) {
    for (SceneBench& s : out.scenes) {
      for (int threads : out.threads) {
        const std::string item = fmt::format("{} {}T, round {}/{}", s.name, threads, round + 1, req.repeat);
        report(item, "render");
        RenderRequest r;
        r.session = req.session;
        r.session.threads = threads;
        r.scenePath = s.path;
        const RenderResult result = runRender(r);
        s.samples.push_back({threads, round, result.stats.time, result.stats.cpu});
        ++done;
        report(item, "done");
      }
    }
    for (int threads : out.threads) {
      const std::string item = fmt::format("control {}T, round {}/{}", threads, round + 1, req.repeat);
      report(item, "control");
      out.control.push_back(controlPass(threads, round));
      ++done;
      report(item, "done");
    }
  }
  std::vector<CpuTiming> runs;  // renders and control passes alike
  for (const SceneBench& s : out.scenes) {
    for (const BenchSample& b : s.samples) runs.push_back(b.cpu);
  }
  for (const BenchSample& b : out.control) runs.push_back(b.cpu);
  const std::string contended = contendedNote(runs, "run");
  if (!contended.empty()) out.notes.push_back(contended);
  out.whole = whole.timing(most);
  return out;
}

}  // namespace penumbra
