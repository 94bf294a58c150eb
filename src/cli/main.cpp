// The penumbra command line: a thin shell over the pipeline. Exit codes:
// 0 ok, 2 bad input (one-line message), 1 internal error, 3 a batch's jobs failed,
// 4 batch --status: not every job is up to date, 143 stopped by SIGTERM.
#include "plan/command_support.h"
#include "plan/cpu_report.h"
#include "plan/memory_limit.h"
#include "plan/pipeline.h"
#include "plan/saved_passes.h"
#include "cli/progress_meter.h"
#include "cli/batch_command.h"
#include "cli/bench_command.h"
#include "cli/build_info.h"
#include "cli/merge_command.h"
#include "cli/plan_command.h"
#include "cli/session_args.h"
#include "cli/sweep_command.h"
#include "core/error.h"
#include <algorithm>
#include <CLI/CLI.hpp>
#include <charconv>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <filesystem>
#include <iostream>
#include <unistd.h>

using namespace penumbra;

namespace {

// "X,Y" as two ints; from_chars, unlike sscanf, rejects out-of-range numbers.
std::pair<int, int> parsePixel(const std::string& arg) {
  int x = 0, y = 0;
  const char* end = arg.data() + arg.size();
  auto [next, ec] = std::from_chars(arg.data(), end, x);
  bool ok = ec == std::errc() && next != end && *next == ',';
  if (ok) {
    auto r = std::from_chars(next + 1, end, y);
    ok = r.ec == std::errc() && r.ptr == end;
  }
  if (!ok) throw InputError("--trace-pixel: expected X,Y, got '" + arg + "'");
  return {x, y};
}

// A seed is a 64-bit unsigned number; from_chars into uint64_t refuses a sign, so
// "-1" is an error instead of 2^64 - 1.
uint64_t parseSeed(const std::string& arg) {
  uint64_t seed = 0;
  const char* end = arg.data() + arg.size();
  auto [next, ec] = std::from_chars(arg.data(), end, seed);
  if (ec != std::errc() || next != end) {
    throw InputError("--seed: expected an integer 0.." + std::to_string(UINT64_MAX) + ", got '" + arg + "'");
  }
  return seed;
}

// An option another command has: say which, so a habit from one command is not a
// dead end in the next (" (--threads is an option of render, sweep, batch and bench)").
std::string otherCommandsHint(const CLI::App& app, const CLI::App& current, const std::string& option) {
  std::vector<std::string> owners;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub == &current) continue;
    for (const CLI::Option* o : sub->get_options()) {
      const auto& names = o->get_lnames();
      const auto& shorts = o->get_snames();
      const bool match = (option.rfind("--", 0) == 0 && std::count(names.begin(), names.end(), option.substr(2))) ||
                         (option.size() == 2 && std::count(shorts.begin(), shorts.end(), option.substr(1)));
      if (match) owners.push_back(sub->get_name());
    }
  }
  if (owners.empty()) return "";
  std::string list;
  for (size_t i = 0; i < owners.size(); ++i) {
    list += (i == 0 ? "" : i + 1 == owners.size() ? " and " : ", ") + owners[i];
  }
  return " (" + option + " is an option of " + list + ", not of " + current.get_name() + ")";
}

int runRenderCommand(RenderRequest& req, const std::string& statsPath, const std::string& tracePixelArg,
                     bool quiet, bool verbose) {
  if (!tracePixelArg.empty()) {
    req.tracePixel = parsePixel(tracePixelArg);
  }
  // "-": the statistics go to stdout, which then carries nothing else.
  const bool statsToStdout = statsPath == "-";
  if (statsToStdout && req.tracePixel && (req.outputPath.empty() || req.outputPath == "-")) {
    throw InputError("--stats - and --trace-pixel both write to stdout: give one of them a file");
  }
  if (!statsPath.empty() && !statsToStdout) req.statsPaths.push_back(statsPath);
  // The estimate of a long job, before it starts; --quiet silences it like every note.
  if (!quiet) req.session.notice = [](const std::string& note) { std::cerr << "note: " << note << "\n"; };
  // Progress goes to stderr: stdout may carry --trace-pixel's JSON.
  std::optional<ProgressMeter> meter;
  if (!quiet) {
    meter.emplace(progressDisplay());
    meter->startTicker();
    req.session.progress = &*meter;
  }
  // A time limit counts the whole process: its start-up (loading the shared
  // libraries) and the image's write are the user's wait too.
  if (processSeconds() >= 0.0) req.jobClock = [] { return processSeconds(); };
  RenderResult result = runRender(req);
  if (meter) meter->finish();
  if (req.tracePixel) {
    std::string json = rayTreeReport(result, req.tracePixel->first, req.tracePixel->second);
    if (req.outputPath.empty() || req.outputPath == "-") std::cout << json;
    else writeTextOutput(req.outputPath, json);
  }
  if (statsToStdout) std::cout << statsReport(result);
  else if (!statsPath.empty()) writeTextOutput(statsPath, statsReport(result));
  if (!quiet) {
    for (const std::string& note : result.notes) std::cerr << noteLine(note) << "\n";
    std::cerr << renderSummary(result, verbose || !statsPath.empty()) << "\n";
  }
  return 0;
}

// What went to stdout (--stats -, --trace-pixel, plan, --list-shard) is checked like
// a file: redirected onto a full disk, the command must not exit 0 with half of it.
int checkedStdout(int code) {
  std::cout.flush();
  if (std::fflush(stdout) == 0 && !std::ferror(stdout) && std::cout.good()) return code;
  std::cerr << "penumbra: cannot write to standard output: " << std::strerror(errno) << "\n";
  return code == 0 ? 2 : code;
}

int runCommandLine(int argc, char** argv);

}  // namespace

int main(int argc, char** argv) { return checkedStdout(runCommandLine(argc, argv)); }

namespace {

int runCommandLine(int argc, char** argv) {
  CLI::App app{"penumbra: a CPU photon-mapping renderer (Whitted core + shadow and indirect photon maps)"};
  app.require_subcommand(1);
  app.footer("Exit codes: 0 done; 1 internal error (a bug: please report it); 2 bad input or a job refused "
             "before any work (one line says which file, JSON path and problem); " +
             std::to_string(kExitJobsFailed) + " batch: some jobs failed, the others finished; " +
             std::to_string(kExitNotUpToDate) + " batch --status: some job is missing, stale or broken; " +
             std::to_string(kExitTerminated) + " stopped by SIGTERM (a progressive frame saved its passes as "
             "OUTPUT.passes: the same command resumes it).");
  // A bad option is bad input like any other: one line, exit 2.
  app.failure_message([](const CLI::App*, const CLI::Error& e) { return std::string(e.what()) + " (see --help)\n"; });
  app.set_version_flag("--version", std::string("penumbra ") + PENUMBRA_VERSION + " (commit " + buildCommit() + ", " +
                                        buildType() + ")");

  RenderRequest req;
  std::string statsPath, tracePixelArg;
  bool verbose = false;
  std::string seedArg;
  SessionArgs session;
  std::optional<int> spp;
  CLI::App* render = app.add_subcommand("render", "Render a JSON scene to an image (PNG or EXR)");
  render->add_option("scene", req.scenePath, "Scene file (JSON, or a model: .gltf, .glb, .obj; - reads JSON from stdin)")->required();
  render->add_option("-o,--output,--outfile", req.outputPath,
                     "Output image: .png (8-bit sRGB) or .exr (linear: half colour, float depth in scene units and normals in [-1,1]); with --trace-pixel, "
                     "the JSON file (default stdout)");
  render->add_option("--seed", seedArg, "Random seed, 0..2^64-1 (overrides render.seed)");
  render->add_option("--spp", spp, "Samples per pixel (overrides camera.spp)")->check(CLI::Range(1, 4096));
  render->add_option("--stats", statsPath, "Write render statistics as JSON to this file (- : stdout)");
  render->add_option("--aov", req.aov,
                     "What to render: beauty, depth, normal, indirect, direct, caustic, error (the beauty's "
                     "per-pixel standard error), bias (its per-pixel photon-map bias, 4 passes or more) or spp "
                     "(the camera samples each pixel took) (default: the scene's render.aov, else beauty)");
  std::string tileArg, boundsArg;
  render->add_option("--tile", tileArg,
                     "Render tile I of N (1-based, as batch --shard): a band of whole rows, written as a part file "
                     "(.exr) for penumbra merge");
  render->add_option("--pixel-bounds", boundsArg,
                     "Render only pixels [x0,x1) x [y0,y1) (pbrt-v4's convention), written as a part file (.exr)")
      ->excludes("--tile");
  render->add_option("--trace-pixel", tracePixelArg,
                     "Write the ray tree of pixel X,Y as JSON instead of rendering an image");
  render->add_flag("-v,--verbose", verbose, "The summary also gives the reasons of automatic decisions (the gate)");
  addSessionOptions(*render, session,
                    kThreadsOption | kMaxMemoryOption | kSetOption | kQuietOption | kPlanOption | kBudgetOption |
                        kMapDirOption | kForceOption | kDisplayOption,
                    "");

  std::string textureName, textureOut;
  int textureWidth = 2048;
  uint64_t textureSeed = 1;
  CLI::App* texture = app.add_subcommand("texture", "Write a procedural lat-long texture (checker, grid, planet, earthlike)");
  texture->add_option("name", textureName, "Texture name")->required();
  texture->add_option("-o,--output", textureOut, "Output image (.png or .exr)")->required();
  texture->add_option("--width", textureWidth, "Width in pixels; height is width / 2")->check(CLI::Range(2, 16384));
  texture->add_option("--seed", textureSeed, "Noise seed");

  SweepCommand sweep(app);
  PlanCommand plan(app);
  CheckCommand check(app);
  BatchCommand batch(app);
  BenchCommand bench(app);
  MergeCommand merge(app);

  // From here on an interrupt removes our temp files, never an old output.
  installOutputCleanup();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ExtrasError& e) {
    // An unknown option: name the closest one the subcommand has.
    for (CLI::App* sub : app.get_subcommands()) {
      for (const std::string& extra : sub->remaining()) {
        if (extra.rfind("-", 0) != 0) continue;
        std::vector<std::string> names;
        for (const CLI::Option* o : sub->get_options()) {
          for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
        }
        std::string hint = optionHint(extra.substr(0, extra.find('=')), names);
        if (hint.empty()) hint = otherCommandsHint(app, *sub, extra.substr(0, extra.find('=')));
        std::cerr << "penumbra " << sub->get_name() << ": unknown option '" << extra << "'" << hint << "\n";
        return 2;
      }
    }
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (*render) {
      if (req.outputPath.empty() && tracePixelArg.empty()) throw InputError("render: -o OUT is required");
      const std::string ext = std::filesystem::path(req.outputPath).extension().string();
      if (!tracePixelArg.empty() && (ext == ".png" || ext == ".exr")) {
        throw InputError("--trace-pixel writes JSON, not an image: give -o a .json path (got '" + req.outputPath + "')");
      }
      std::vector<std::string> own;  // the render's options that stand for scene values
      if (!seedArg.empty()) own.push_back("render.seed=" + std::to_string(parseSeed(seedArg)));
      if (spp) own.push_back("camera.spp=" + std::to_string(*spp));
      req.session = session.options(own);
      req.display = session.display();
      if (!tileArg.empty()) {
        const auto [i, n] = parseTile(tileArg);
        req.tile = TileRequest{i, n, std::nullopt};
      }
      if (!boundsArg.empty()) req.tile = TileRequest{0, 0, parsePixelBounds(boundsArg)};
      return runRenderCommand(req, statsPath, tracePixelArg, session.quiet, verbose);
    }
    if (sweep.selected()) return sweep.run();
    if (plan.selected()) return plan.run();
    if (check.selected()) return check.run();
    if (batch.selected()) return batch.run();
    if (bench.selected()) return bench.run();
    if (merge.selected()) return merge.run();
    if (*texture) {
      writeProceduralTexture(textureName, textureWidth, textureSeed, textureOut);
      return 0;
    }
  } catch (const InputError& e) {
    std::cerr << "penumbra: " << e.what() << "\n";
    return 2;
  } catch (const Terminated& t) {
    std::cerr << "penumbra: " << t.message << "\n";
    return kExitTerminated;
  } catch (const std::exception& e) {
    std::cerr << "penumbra: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace
