// sweep.json holds one field per thing that changes a row, so a refusal can say
// which one differs; the knob values are the rows' own keys in results.csv.
#include "plan/sweep/sweep_folder.h"
#include "plan/sweep/sweep_run.h"
#include "plan/reuse_key.h"
#include "core/error.h"
#include "io/temp_file.h"
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <filesystem>
#include <fstream>
#include <set>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json toJson(const SweepIdentity& id) {
  return {{"scene", id.scene},         {"scene_files", id.sceneFiles}, {"set", id.overrides},
          {"view", id.view},           {"plan", id.plan},              {"reference", id.reference}};
}

// The names a refusal uses for each field, in the order they are compared.
const std::pair<const char*, const char*> kFields[] = {
    {"scene", "scene"},          {"scene_files", "scene's files (edited since)"},
    {"set", "--set values"},     {"view", "view"},
    {"plan", "--enable/--disable"}, {"reference", "reference image"}};

// Whether results.csv has a row below its header.
bool hasFinishedRuns(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  if (!std::getline(in, line)) return false;
  while (std::getline(in, line)) {
    if (!line.empty()) return true;
  }
  return false;
}

}  // namespace

SweepIdentity sweepIdentity(const SweepRequest& req, const std::vector<std::string>& inputs) {
  SweepIdentity id;
  id.scene = req.scenePath;
  id.sceneFiles = inputsStamp(inputs);
  std::set<std::string> knobKeys;
  for (const SweepKnob& k : req.spec.knobs) knobKeys.insert(k.keys.begin(), k.keys.end());
  for (const std::string& o : jobOverrides(req.session, req.spec.runs.front().overrides)) {
    if (!knobKeys.count(o.substr(0, o.find('=')))) id.overrides.push_back(o);
  }
  id.view = req.aov;
  for (Pass p : req.session.plan.enable) id.plan.push_back(std::string("+") + passName(p));
  for (Pass p : req.session.plan.disable) id.plan.push_back(std::string("-") + passName(p));
  for (const std::string& f : req.session.load.flags()) id.plan.push_back(f);  // another picture of a model
  id.plan.push_back(std::string("error-of=") + kErrorFigureNames[static_cast<size_t>(req.errorOf)]);
  if (!req.referencePath.empty()) {
    id.reference = inputsStamp({req.referencePath});
  } else if (req.referencePasses > 1) {
    id.reference = fmt::format("its own, {}x the passes", req.referencePasses);
  }
  return id;
}

void checkSweepFolder(const std::string& dir, const SweepIdentity& identity) {
  const fs::path file = fs::path(dir) / "sweep.json";
  std::error_code ec;
  const bool results = hasFinishedRuns(fs::path(dir) / "results.csv");
  // Nothing finished (no results, or a failed sweep's header alone): nothing to resume
  // and nothing a new sweep could mix with, so the folder is free.
  if (!results) return;
  if (!fs::exists(file, ec)) {
    if (results) {
      throw InputError(dir + ": has a results.csv but no sweep.json, so its rows cannot be told apart from "
                             "another sweep's; use another -o folder or --force to start again");
    }
    return;
  }
  std::ifstream in(file, std::ios::binary);
  const json saved = json::parse(in, nullptr, /*allow_exceptions=*/false);
  const json now = toJson(identity);
  if (!saved.is_object()) {
    throw InputError(file.string() + ": not a sweep.json penumbra wrote; use another -o folder or --force");
  }
  for (const auto& [key, name] : kFields) {
    if (!saved.contains(key) || saved[key] != now[key]) {
      const std::string was = saved.contains(key) ? saved[key].dump() : std::string("none");
      const std::string values = was.size() + now[key].dump().size() < 160 ? " (" + was + ", now " + now[key].dump() + ")" : "";
      throw InputError(dir + ": holds a sweep with another " + name + values +
                       "; use another -o folder or --force to start again");
    }
  }
}

void checkSweepFiles(const std::string& dir, const SweepSpec& spec) {
  std::vector<fs::path> files = {"results.csv",   "report.md", "sweep.json",
                                 "reference.exr", "runs.png",  "tradeoff.png"};
  for (const SweepRun& run : spec.runs) files.push_back(fs::path("runs") / (run.slug + ".exr"));
  for (const fs::path& f : files) {
    const std::string path = (fs::path(dir) / f).string();
    const std::string problem = outputPathProblem(path);
    if (!problem.empty()) throw InputError(path + ": cannot write: " + problem);
  }
}

void writeSweepFolder(const std::string& dir, const SweepIdentity& identity) {
  writeTextFileAtomic((fs::path(dir) / "sweep.json").string(), toJson(identity).dump(2) + "\n");
}

}  // namespace penumbra
