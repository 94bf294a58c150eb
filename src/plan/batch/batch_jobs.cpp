// Jobs file parsing and expansion (orbits, scene globs), output names, shards.
#include "plan/batch/batch_jobs.h"
#include "core/error.h"
#include "io/json_parse.h"
#include "plan/frame_part.h"
#include <fmt/format.h>
#include <fnmatch.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

[[noreturn]] void fail(const std::string& file, const std::string& where, const std::string& problem) {
  throw InputError(file + ": " + where + ": " + problem);
}

std::vector<std::string> stringList(const json& node, const std::string& file, const std::string& where) {
  if (!node.is_array()) fail(file, where, "must be a list of strings");
  std::vector<std::string> out;
  for (size_t i = 0; i < node.size(); ++i) {
    if (!node[i].is_string()) fail(file, fmt::format("{}[{}]", where, i), "must be a string");
    out.push_back(node[i].get<std::string>());
  }
  return out;
}

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

// An orbit frame's index in a file name: {i} as it is, {i:0N} zero-padded to N digits
// (1-9), so that ffmpeg's globs and file browsers sort frame 2 before frame 10.
// False for a malformed {i:...}; other braces ({name}, {view}) pass through.
bool expandIndex(const std::string& pattern, int i, std::string& out) {
  out.clear();
  size_t at = 0;
  for (size_t open = pattern.find("{i", at); open != std::string::npos; open = pattern.find("{i", at)) {
    out.append(pattern, at, open - at);
    const std::string_view rest = std::string_view(pattern).substr(open);
    if (rest.substr(0, 3) == "{i}") {
      out += std::to_string(i);
      at = open + 3;
    } else if (rest.size() >= 6 && rest.substr(0, 4) == "{i:0" && rest[4] >= '1' && rest[4] <= '9' && rest[5] == '}') {
      out += fmt::format("{:0{}}", i, rest[4] - '0');
      at = open + 6;
    } else if (rest.substr(0, 3) == "{i:") {
      return false;
    } else {
      out += "{i";
      at = open + 2;
    }
  }
  out.append(pattern, at, std::string::npos);
  return true;
}

// Every view's file: {name} and {view} substituted; views without {view} in a .exr share it.
std::vector<BatchOutput> outputsFor(const std::string& pattern, const std::string& name,
                                    const std::vector<std::string>& views, const std::string& file,
                                    const std::string& where) {
  const bool perView = pattern.find("{view}") != std::string::npos;
  const bool exr = fs::path(pattern).extension() == ".exr";
  if (views.size() > 1 && !perView && !exr) {
    fail(file, where + ".output", "several views need {view} in the name, or one layered .exr");
  }
  std::vector<BatchOutput> out;
  for (const std::string& v : views) {
    out.push_back({v, replaceAll(replaceAll(pattern, "{name}", name), "{view}", v.empty() ? "default" : v)});
  }
  return out;
}

std::vector<std::string> globScenes(const fs::path& pattern, const std::string& file, const std::string& where) {
  const fs::path dir = pattern.parent_path().empty() ? fs::path(".") : pattern.parent_path();
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (fnmatch(pattern.filename().c_str(), e.path().filename().c_str(), 0) == 0) out.push_back(e.path().string());
  }
  if (ec) fail(file, where, "cannot list " + dir.string() + " (" + ec.message() + ")");
  std::sort(out.begin(), out.end());
  if (out.empty()) fail(file, where, "'" + pattern.string() + "' matches no file");
  return out;
}

std::string vec3(double x, double y, double z) { return fmt::format("[{:.9g},{:.9g},{:.9g}]", x, y, z); }

// The orbit's axes: `up` made unit, `front` (angle 0) the direction of +z in the plane
// across `up` (of +x when up lies along z), `side` (90 degrees) = up x front, which is
// +x for the default up +y and front +z.
struct OrbitFrame {
  glm::dvec3 up, front, side;
};

OrbitFrame orbitFrame(const glm::dvec3& up) {
  OrbitFrame f;
  f.up = glm::normalize(up);
  glm::dvec3 front = glm::dvec3(0.0, 0.0, 1.0) - f.up.z * f.up;
  if (glm::length(front) < 1e-6) front = glm::dvec3(1.0, 0.0, 0.0) - f.up.x * f.up;
  f.front = glm::normalize(front);
  f.side = glm::cross(f.up, f.front);
  return f;
}

// "tiles": N turns each of a node's jobs (from `first` on) into N jobs, one per band
// of rows, named NAME_tileI, each view's output "out/f.png" becoming the part file
// "out/f.tileIofN.exr" (frame_part.h); penumbra merge makes the frame.
void expandTiles(const json& node, std::vector<BatchJob>& jobs, size_t first, const std::string& file,
                 const std::string& where) {
  const bool ok = node.is_number_integer() && node.get<int64_t>() >= 1 && node.get<int64_t>() <= 10000;
  if (!ok) fail(file, where + ".tiles", "must be an integer 1..10000 (bands of rows of each frame)");
  const int count = static_cast<int>(node.get<int64_t>());
  std::vector<BatchJob> whole(jobs.begin() + static_cast<std::ptrdiff_t>(first), jobs.end());
  jobs.resize(first);
  for (const BatchJob& job : whole) {
    if (job.budget.any()) fail(file, where + ".tiles", "a tiled job cannot run to a budget (time_limit, target_error)");
    for (size_t v = 1; v < job.outputs.size(); ++v) {
      if (job.outputs[v].path == job.outputs.front().path) {
        fail(file, where + ".tiles", "tiles need one file per view: put {view} in the output name");
      }
    }
    for (int i = 1; i <= count; ++i) {
      BatchJob t = job;
      t.name = fmt::format("{}_tile{}", job.name, i);
      t.where = fmt::format("{} (tile {}/{})", job.where, i, count);
      for (BatchOutput& o : t.outputs) o.path = tilePartPath(o.path, i, count);
      t.tile = BatchTile{i, count, job.outputs};
      jobs.push_back(std::move(t));
    }
  }
}

}  // namespace

std::vector<BatchJob> readJobsFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open jobs file");
  std::stringstream text;
  text << in.rdbuf();
  const json doc = parseJsonDocument(text.str(), path);
  if (!doc.is_object() || !doc.contains("jobs") || !doc["jobs"].is_array()) {
    fail(path, "jobs", "a jobs file is an object with a \"jobs\" list");
  }
  for (const auto& [key, v] : doc.items()) {
    if (key != "jobs" && key != "set") fail(path, key, "unknown key (known: jobs, set)");
  }
  const fs::path base = fs::path(path).parent_path();
  auto resolve = [&](const std::string& p) { return fs::path(p).is_absolute() || base.empty() ? p : (base / p).string(); };
  const std::vector<std::string> common = doc.contains("set") ? stringList(doc["set"], path, "set") : std::vector<std::string>{};
  std::vector<BatchJob> jobs;
  for (size_t j = 0; j < doc["jobs"].size(); ++j) {
    const std::string where = fmt::format("jobs[{}]", j);
    const json& node = doc["jobs"][j];
    if (!node.is_object()) fail(path, where, "must be an object");
    for (const auto& [key, v] : node.items()) {
      static const std::set<std::string> known = {"name",   "scene", "scenes",     "set",          "views",
                                                  "output", "orbit", "time_limit", "target_error", "tiles"};
      if (!known.count(key)) {
        fail(path, where + "." + key,
             "unknown key (known: name, scene, scenes, set, views, output, orbit, time_limit, target_error, tiles)");
      }
    }
    RenderBudget budget;
    for (auto [key, field] : {std::pair{"time_limit", &RenderBudget::seconds}, {"target_error", &RenderBudget::targetError}}) {
      if (!node.contains(key)) continue;
      if (!node[key].is_number() || node[key].get<double>() < 0.0) fail(path, where + "." + key, "must be a number >= 0");
      budget.*field = node[key].get<double>();
    }
    if (node.contains("scene") == node.contains("scenes")) fail(path, where, "needs exactly one of \"scene\" and \"scenes\"");
    if (!node.contains("output") || !node["output"].is_string()) fail(path, where + ".output", "must be a file name pattern");
    std::vector<std::string> overrides = common;
    if (node.contains("set")) for (const std::string& s : stringList(node["set"], path, where + ".set")) overrides.push_back(s);
    const std::vector<std::string> views = node.contains("views") ? stringList(node["views"], path, where + ".views")
                                                                  : std::vector<std::string>{""};
    if (views.empty()) fail(path, where + ".views", "must name at least one view");
    for (size_t v = 1; v < views.size(); ++v) {
      if (std::find(views.begin(), views.begin() + v, views[v]) != views.begin() + v) {
        fail(path, fmt::format("{}.views[{}]", where, v), "'" + views[v] + "' is listed twice");
      }
    }
    const std::string output = resolve(node["output"].get<std::string>());
    std::vector<std::string> scenes;
    if (node.contains("scene")) {
      if (!node["scene"].is_string()) fail(path, where + ".scene", "must be a path");
      scenes.push_back(resolve(node["scene"].get<std::string>()));
    } else {
      if (!node["scenes"].is_string()) fail(path, where + ".scenes", "must be a glob pattern");
      scenes = globScenes(resolve(node["scenes"].get<std::string>()), path, where + ".scenes");
    }
    const size_t firstOfNode = jobs.size();
    const std::string given = node.contains("name") && node["name"].is_string() ? node["name"].get<std::string>() : "";
    for (const std::string& scene : scenes) {
      const std::string stem = given.empty() || scenes.size() > 1 ? fs::path(scene).stem().string() : given;
      if (!node.contains("orbit")) {
        jobs.push_back({stem, scene, overrides, outputsFor(output, stem, views, path, where), where, budget, std::nullopt});
        continue;
      }
      const json& o = node["orbit"];
      // get<int64_t> of an unsigned 4294967301 would wrap: range-check in the JSON's own type.
      const bool countOk = o.is_object() && o.contains("count") &&
                           ((o["count"].is_number_unsigned() && o["count"].get<uint64_t>() - 1 < 100000) ||
                            (o["count"].is_number_integer() && !o["count"].is_number_unsigned() &&
                             o["count"].get<int64_t>() >= 1 && o["count"].get<int64_t>() <= 100000));
      if (!countOk) fail(path, where + ".orbit.count", "must be an integer 1..100000");
      auto num = [&](const char* k, double d) {
        if (!o.contains(k)) return d;
        if (!o[k].is_number()) fail(path, where + ".orbit." + k, "must be a number");
        return o[k].get<double>();
      };
      auto triple = [&](const char* k, glm::dvec3 d) {
        if (!o.contains(k)) return d;
        if (!o[k].is_array() || o[k].size() != 3) fail(path, where + ".orbit." + k, "must be [x, y, z]");
        for (int i = 0; i < 3; ++i) {
          if (!o[k][i].is_number()) fail(path, fmt::format("{}.orbit.{}[{}]", where, k, i), "must be a number");
          d[i] = o[k][i].get<double>();
        }
        return d;
      };
      const glm::dvec3 c = triple("center", glm::dvec3(0.0));
      const glm::dvec3 up = triple("up", glm::dvec3(0.0, 1.0, 0.0));
      if (!(glm::length(up) > 1e-12) || !std::isfinite(glm::length(up))) {
        fail(path, where + ".orbit.up", "must be a direction (not zero, finite)");
      }
      const int count = static_cast<int>(o["count"].get<int64_t>());
      const std::string pattern = node["output"].get<std::string>();
      std::string first, second;
      if (!expandIndex(pattern, 0, first)) {
        fail(path, where + ".output", "an orbit index is written {i} or {i:0N} with N from 1 to 9 (e.g. {i:04})");
      }
      expandIndex(pattern, 1, second);
      if (count > 1 && first == second && pattern.find("{name}") == std::string::npos) {
        fail(path, where + ".output", fmt::format("an orbit of {} views needs {{i}} or {{name}} in the file name", count));
      }
      const double radius = num("radius", 5.0), height = num("height", 0.0);
      // Degrees about `up` through the centre, 0 = on the +z side; the arc [from, to)
      // is cut into `count` equal steps (a full circle by default).
      const double from = num("from", 0.0), to = num("to", 360.0);
      const OrbitFrame frame = orbitFrame(up);
      for (int i = 0; i < count; ++i) {
        const double a = (from + (to - from) * i / count) * M_PI / 180.0;
        BatchJob job;
        job.name = fmt::format("{}_{}", stem, i);
        job.scene = scene;
        job.overrides = overrides;
        const glm::dvec3 eye = c + radius * (std::sin(a) * frame.side + std::cos(a) * frame.front) + height * frame.up;
        job.overrides.push_back("camera.position=" + vec3(eye.x, eye.y, eye.z));
        job.overrides.push_back("camera.look_at=" + vec3(c.x, c.y, c.z));
        // The file camera's roll is dropped: every frame's horizon is level about `up`.
        job.overrides.push_back("camera.up=" + vec3(frame.up.x, frame.up.y, frame.up.z));
        std::string named;
        expandIndex(output, i, named);
        job.outputs = outputsFor(named, job.name, views, path, where);
        job.where = fmt::format("{} (orbit {})", where, i);
        job.budget = budget;
        jobs.push_back(std::move(job));
      }
    }
    if (node.contains("tiles")) expandTiles(node["tiles"], jobs, firstOfNode, path, where);
  }
  std::set<std::string> names;
  for (BatchJob& job : jobs) {
    std::string name = job.name;
    for (int k = 2; !names.insert(name).second; ++k) name = fmt::format("{}-{}", job.name, k);
    job.name = name;
  }
  return jobs;
}

bool isJobsFile(const std::string& path) {
  std::ifstream in(path);
  const nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
  return doc.is_object() && doc.contains("jobs");
}

std::vector<BatchJob> jobsForScenes(const std::vector<std::string>& scenes, const std::string& dir,
                                    const std::vector<std::string>& views, const std::string& ext) {
  std::vector<BatchJob> jobs;
  for (size_t i = 0; i < scenes.size(); ++i) {
    BatchJob job;
    job.name = fs::path(scenes[i]).stem().string();
    job.scene = scenes[i];
    job.where = fmt::format("scene {} ({})", i + 1, scenes[i]);
    for (const std::string& v : views) {
      const std::string file = views.size() > 1 && ext != ".exr" ? job.name + "_" + v + ext : job.name + ext;
      job.outputs.push_back({v, (fs::path(dir) / file).string()});
    }
    jobs.push_back(std::move(job));
  }
  return jobs;
}

}  // namespace penumbra
