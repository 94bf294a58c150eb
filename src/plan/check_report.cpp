// The lines of penumbra check: counts, bounds and the glTF defaults of one scene.
#include "plan/check_report.h"
#include "plan/transport_model.h"
#include "io/scene_defaults.h"
#include "io/scene_loader.h"
#include <fmt/format.h>
#include <vector>

namespace penumbra {
namespace {

// What loading adds to a glTF scene, or would add without --no-defaults; "" when the
// scene lacks nothing (or is not a glTF file).
std::string defaultsLine(const LoadReport& load) {
  if (!load.noCamera && !load.noLight) return "";
  std::vector<std::string> parts;
  if (load.noCamera) parts.push_back("a camera framing the bounds (the file has none)");
  if (load.noLight) parts.push_back("the studio environment (the file has no light)");
  const bool added = load.framedCamera || load.defaultSky;
  std::string line = added ? "  adds " : "  would add ";
  for (size_t i = 0; i < parts.size(); ++i) line += (i ? " and " : "") + parts[i];
  return line + (added ? "; --no-defaults keeps the file as it is\n" : " without --no-defaults\n");
}

}  // namespace

std::string checkReport(const Scene& s) {
  const LoadReport& load = s.load;
  size_t triangles = 0;
  for (const TriangleMesh& m : s.meshes) triangles += m.triangles.size();
  // The file's own lights and materials: the default sky is reported below as an
  // addition, and the implicit "default" material is no file's.
  const size_t lights = s.lights.size() - (load.defaultSky ? 1 : 0);
  const size_t materials = s.materials.size() - load.implicitMaterials;
  std::string out = fmt::format("ok ({}, {} meshes with {} triangles, {} spheres, {} lights, {} materials)\n",
                                transportOf(s).name(), s.meshes.size(), triangles, s.spheres.size(), lights,
                                materials);
  // Where the geometry is: what a camera must frame (a model's units are its own).
  const SceneBounds b = sceneBounds(s);
  if (!b.empty()) {
    const Vec3 lo = b.lo, hi = b.hi;
    out += fmt::format("  bounds [{:g}, {:g}, {:g}] .. [{:g}, {:g}, {:g}] (size {:g} x {:g} x {:g})\n", lo.x, lo.y,
                       lo.z, hi.x, hi.y, hi.z, hi.x - lo.x, hi.y - lo.y, hi.z - lo.z);
  }
  return out + defaultsLine(load);
}

}  // namespace penumbra
