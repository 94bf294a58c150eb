// The plan and check subcommands: load, decide (or validate), print; nothing is emitted
// or rendered (the BVH is built only for the light split of photon passes).
#include "cli/plan_command.h"
#include "core/error.h"
#include "plan/memory_limit.h"
#include "plan/render_frame.h"
#include "plan/transport_model.h"
#include "io/scene_defaults.h"
#include "io/scene_loader.h"
#include <fmt/format.h>
#include <algorithm>
#include <iostream>

namespace penumbra {

namespace {

// What loading adds to a glTF scene, or would add without --no-defaults; "" when the
// scene lacks nothing (or is not a glTF file).
std::string defaultsLine(const LoadReport& load) {
  if (!load.noCamera && !load.noLight) return "";
  std::vector<std::string> parts;
  if (load.noCamera) parts.push_back("a camera framing the bounds (the file has none)");
  if (load.noLight) parts.push_back("a neutral sky (the file has no light)");
  const bool added = load.framedCamera || load.defaultSky;
  std::string line = added ? "  adds " : "  would add ";
  for (size_t i = 0; i < parts.size(); ++i) line += (i ? " and " : "") + parts[i];
  return line + (added ? "; --no-defaults keeps the file as it is\n" : " without --no-defaults\n");
}

}  // namespace

PlanCommand::PlanCommand(CLI::App& app) {
  command_ = app.add_subcommand("plan", "Print what a render would run, and why, without rendering");
  command_->add_option("scene", scene_, "Scene file (JSON)")->required();
  command_->add_option("--aov", aov_, "View (default: the scene's render.aov)");
  command_->add_flag("--json", json_, "Print the plan as JSON (as in --stats)");
  addSessionOptions(*command_, args_, kSetOption | kPlanOption, "");
}

int PlanCommand::run() {
  const SessionOptions options = args_.options();
  Scene scene = loadJobScene(scene_, options);
  const Aov aov = parseAov(aov_.empty() ? scene.render.aov : aov_);
  RenderPlan plan = makePlan(scene, aov, options.plan);
  // The light split needs a few rays per light: build the BVH only when a photon
  // pass could be split (no textures, no photons, no render).
  const bool split = plan[Pass::IndirectPhotons].on || plan[Pass::GlobalPhotons].on || plan[Pass::CausticPhotons].on;
  if (split) {
    const SceneAssets assets = prepareAssets(scene, false);
    splitByReach(plan, scene, *assets.tracer);
  }
  std::cout << (json_ ? planJson(plan) + "\n" : planText(plan));
  return 0;
}

CheckCommand::CheckCommand(CLI::App& app) {
  command_ = app.add_subcommand("check", "Validate scene files (every value, mesh and texture) without rendering");
  command_->add_option("scenes", scenes_, "Scene files")->required();
  addSessionOptions(*command_, args_, kSetOption | kDefaultsOption, "");
}

int CheckCommand::run() {
  const SessionOptions options = args_.options();
  for (const std::string& path : scenes_) {
    const Scene s = loadJobScene(path, options);
    const LoadReport& load = s.load;
    size_t triangles = 0;
    for (const TriangleMesh& m : s.meshes) triangles += m.triangles.size();
    // The file's own lights: the default sky is reported below as an addition.
    const size_t lights = s.lights.size() - (load.defaultSky ? 1 : 0);
    std::cout << path << ": ok (" << transportOf(s).name() << ", "
              << s.meshes.size() << " meshes with " << triangles << " triangles, " << s.spheres.size()
              << " spheres, " << lights << " lights, " << s.materials.size() << " materials)\n";
    // Where the geometry is: what a camera must frame (a model's units are its own).
    const SceneBounds b = sceneBounds(s);
    if (!b.empty()) {
      const Vec3 lo = b.lo, hi = b.hi;
      std::cout << "  bounds " << fmt::format("[{:g}, {:g}, {:g}] .. [{:g}, {:g}, {:g}]", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z)
                << " (size " << fmt::format("{:g} x {:g} x {:g}", hi.x - lo.x, hi.y - lo.y, hi.z - lo.z) << ")\n";
    }
    std::cout << defaultsLine(load);
    for (const std::string& note : load.notes) std::cerr << "note: " << note << "\n";
  }
  return 0;
}

}  // namespace penumbra
