// Why canonical paths and inodes both: "./a.png", "dir/../a.png" and a symlink or
// hard link to a.png all overwrite a.png; weakly_canonical catches the spellings
// (also for files that do not exist yet), equivalent() the links.
#include "plan/output_safety.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/temp_file.h"
#include <fmt/format.h>
#include <sys/stat.h>
#include <unordered_map>
#include <algorithm>
#include <filesystem>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec) && !ec) return true;
  const fs::path ca = fs::weakly_canonical(a, ec);
  if (ec) return false;
  const fs::path cb = fs::weakly_canonical(b, ec);
  return !ec && ca == cb;
}

// A report (JSON) file: any name the write-and-rename can write (io/temp_file.h).
void checkReportPath(const OutputPath& out) {
  const std::string problem = outputPathProblem(out.path);
  if (!problem.empty()) throw InputError(out.what + " " + out.path + ": cannot write: " + problem);
}

// What names a file whatever the spelling: its device and inode when it exists (hard
// and symbolic links alike), else its canonical path.
std::string fileIdentity(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) == 0) return fmt::format("inode {}:{}", st.st_dev, st.st_ino);
  std::error_code ec;
  const fs::path c = fs::weakly_canonical(path, ec);
  return "path " + (ec ? fs::path(path).lexically_normal() : c).string();
}

}  // namespace

std::vector<std::string> sceneInputs(const Scene& scene, const std::string& scenePath) {
  std::vector<std::string> inputs = scene.inputs;
  if (std::find(inputs.begin(), inputs.end(), scenePath) == inputs.end()) inputs.insert(inputs.begin(), scenePath);
  return inputs;
}

void checkJobsApart(const std::vector<JobFiles>& jobs) {
  std::unordered_map<std::string, std::pair<size_t, std::string>> written;  // identity -> (job, path)
  for (size_t j = 0; j < jobs.size(); ++j) {
    for (const std::string& out : jobs[j].outputs) {
      auto [it, inserted] = written.try_emplace(fileIdentity(out), j, out);
      if (!inserted && it->second.first != j) {
        throw InputError(fmt::format("jobs '{}' and '{}' both write {}", jobs[it->second.first].name, jobs[j].name, out));
      }
    }
  }
  for (size_t j = 0; j < jobs.size(); ++j) {
    for (const std::string& in : jobs[j].inputs) {
      auto it = written.find(fileIdentity(in));
      if (it != written.end() && it->second.first != j) {
        throw InputError(fmt::format("job '{}' writes {}, which job '{}' reads ({})", jobs[it->second.first].name,
                                     it->second.second, jobs[j].name, in));
      }
    }
  }
}

void checkOutputs(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    const OutputPath& out = outputs[i];
    if (out.image) checkImageOutputPath(out.path);
    else checkReportPath(out);
    for (const std::string& input : inputs) {
      if (sameFile(out.path, input)) {
        throw InputError(out.what + " " + out.path + ": is an input of this render (" + input +
                         "); refusing to overwrite it");
      }
    }
    for (size_t j = 0; j < i; ++j) {
      if (sameFile(out.path, outputs[j].path)) {
        throw InputError(out.what + " " + out.path + ": names the same file as " + outputs[j].what);
      }
    }
  }
}

}  // namespace penumbra
