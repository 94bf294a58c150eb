// Whether a batch job's outputs are up to date, decided from the outputs alone:
// each carries the job's stamp and the size and time of every file the render
// read, so no scene is loaded to decide, and each job is judged by itself.
#pragma once
#include "plan/batch/batch_run.h"
#include "plan/render_budget.h"
#include "plan/session_options.h"
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

// What makes a job's pixels, expanded: its scene, overrides (-D, the file's "set",
// the job's, an orbit frame's camera), views and output files, and the command's
// choices that change pixels. Two equal definitions have equal stamps.
struct JobDefinition {
  std::string scene;
  std::vector<std::string> overrides;
  std::vector<std::pair<std::string, std::string>> viewFiles;  // view, file
  std::vector<std::string> choices;  // --no-defaults, --enable/--disable, a budget, a tile
};
std::string jobStamp(const JobDefinition& job);
// A job's definition under the command line's options.
JobDefinition definitionOf(const BatchJob& job, const SessionOptions& session);
// The job's budget: the command line's wins over the job's own, field by field.
RenderBudget jobBudget(const BatchJob& job, const RenderBudget& command);

// One file a render read, as it was when read.
struct InputRecord {
  std::string path;
  uint64_t size = 0;
  int64_t mtimeNs = 0;
  bool operator==(const InputRecord& o) const {
    return path == o.path && size == o.size && mtimeNs == o.mtimeNs;
  }
};
// The files as they are now (a missing one: size 0, time 0).
std::vector<InputRecord> recordInputs(const std::vector<std::string>& paths);
// The record as an image attribute's text, and back (false: not a record).
std::string inputsAttribute(const std::vector<InputRecord>& inputs);
bool parseInputsAttribute(const std::string& text, std::vector<InputRecord>& inputs);

// The image attributes that carry them.
inline constexpr const char* kJobStampAttribute = "penumbra:job";
inline constexpr const char* kJobInputsAttribute = "penumbra:inputs";

enum class JobState { UpToDate, Missing, Stale };
const char* jobStateName(JobState state);  // "up to date", "missing", "stale"

struct OutputsVerdict {
  JobState state = JobState::Missing;
  std::string why;  // "out/a.png: the job changed", "scenes/a.json changed", ...
  std::vector<std::string> inputs;  // what the outputs say the job read (up to date)
};
// Up to date when every output exists whole, carries `stamp` and a record of
// inputs that all still have the size and time recorded.
OutputsVerdict judgeOutputs(const std::vector<std::string>& outputs, const std::string& stamp);

}  // namespace penumbra
