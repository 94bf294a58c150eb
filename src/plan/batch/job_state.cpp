// A job's stamp and input record, and the up-to-date verdict read from its outputs.
#include "plan/batch/job_state.h"
#include "plan/render_plan.h"
#include "io/image_io.h"
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <filesystem>
#include <functional>

namespace penumbra {

namespace fs = std::filesystem;

RenderBudget jobBudget(const BatchJob& job, const RenderBudget& command) {
  RenderBudget b = job.budget;
  if (command.seconds > 0.0) b.seconds = command.seconds;
  if (command.targetError > 0.0) b.targetError = command.targetError;
  b.figure = command.figure;  // the command line's, for every job
  b.bias = command.bias;
  return b;
}

JobDefinition definitionOf(const BatchJob& job, const SessionOptions& s) {
  JobDefinition d;
  d.scene = job.scene;
  d.overrides = jobOverrides(s, job.overrides);
  for (const BatchOutput& o : job.outputs) d.viewFiles.push_back({o.view, o.path});
  // --no-defaults and --camera change the picture of a model: outputs of another choice are stale.
  for (const std::string& f : s.load.flags()) d.choices.push_back(f);
  for (Pass p : s.plan.enable) d.choices.push_back(std::string("--enable ") + passName(p));
  for (Pass p : s.plan.disable) d.choices.push_back(std::string("--disable ") + passName(p));
  const RenderBudget b = jobBudget(job, s.budget);
  if (b.seconds > 0.0) d.choices.push_back(fmt::format("time_limit={}", b.seconds));
  if (b.targetError > 0.0) {
    // The default bias keeps the stamps made before the bound could be chosen.
    d.choices.push_back(fmt::format("target_error={} of {}{}", b.targetError,
                                    kErrorFigureNames[static_cast<size_t>(b.figure)],
                                    b.bias == BiasFigure::Bound ? " with the bias bound" : ""));
  }
  return d;
}

std::string jobStamp(const JobDefinition& job) {
  std::string s = job.scene;
  for (const std::string& o : job.overrides) s += "\n" + o;
  for (const auto& [view, path] : job.viewFiles) s += "\n" + view + ">" + path;
  for (const std::string& c : job.choices) s += "\n!" + c;
  return fmt::format("{:016x}", std::hash<std::string>{}(s));
}

std::vector<InputRecord> recordInputs(const std::vector<std::string>& paths) {
  std::vector<InputRecord> out;
  for (const std::string& path : paths) {
    InputRecord r{path};
    std::error_code ec;
    const uintmax_t size = fs::file_size(path, ec);
    if (!ec) r.size = size;
    const auto time = fs::last_write_time(path, ec);
    if (!ec) r.mtimeNs = std::chrono::duration_cast<std::chrono::nanoseconds>(time.time_since_epoch()).count();
    if (std::find(out.begin(), out.end(), r) == out.end()) out.push_back(r);
  }
  return out;
}

std::string inputsAttribute(const std::vector<InputRecord>& inputs) {
  nlohmann::json j = nlohmann::json::array();
  for (const InputRecord& r : inputs) j.push_back({r.path, r.size, r.mtimeNs});
  return j.dump();
}

bool parseInputsAttribute(const std::string& text, std::vector<InputRecord>& inputs) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_array()) return false;
  inputs.clear();
  for (const nlohmann::json& e : j) {
    if (!e.is_array() || e.size() != 3 || !e[0].is_string() || !e[1].is_number_unsigned() || !e[2].is_number_integer())
      return false;
    inputs.push_back({e[0].get<std::string>(), e[1].get<uint64_t>(), e[2].get<int64_t>()});
  }
  return true;
}

const char* jobStateName(JobState state) {
  switch (state) {
    case JobState::UpToDate: return "up to date";
    case JobState::Missing: return "missing";
    case JobState::Stale: return "stale";
  }
  return "";
}

OutputsVerdict judgeOutputs(const std::vector<std::string>& outputs, const std::string& stamp) {
  OutputsVerdict v;
  std::error_code ec;
  for (const std::string& out : outputs) {
    if (!fs::exists(out, ec)) return {JobState::Missing, out + " does not exist", {}};
  }
  for (const std::string& out : outputs) {
    const std::string written = readImageAttribute(out, kJobStampAttribute);
    if (written.empty()) return {JobState::Stale, out + " was not written by a batch", {}};
    if (written != stamp) return {JobState::Stale, out + ": the job changed", {}};
    // The stamp sits in the header: a file cut short after it is no render of the job.
    if (!imageComplete(out)) return {JobState::Stale, out + " is cut short", {}};
    std::vector<InputRecord> recorded;
    if (!parseInputsAttribute(readImageAttribute(out, kJobInputsAttribute), recorded)) {
      return {JobState::Stale, out + " has no record of its inputs", {}};
    }
    for (const InputRecord& r : recorded) {
      if (!(recordInputs({r.path}).front() == r)) return {JobState::Stale, r.path + " changed", {}};
      if (std::find(v.inputs.begin(), v.inputs.end(), r.path) == v.inputs.end()) v.inputs.push_back(r.path);
    }
  }
  v.state = JobState::UpToDate;
  return v;
}

}  // namespace penumbra
