// A medium's "density" key: the file, grid, scale and placement checked, then the grid
// read by the OpenVDB reader process and its block majorants built. Placement: the
// grid's own linear transform takes index space to the file's world, then the optional
// "transform" moves that into the scene.
#include "io/vdb_reader.h"

#include "core/media/majorant_grid.h"
#include "io/float_checks.h"
#include "io/input_file.h"
#include "io/scene_sections.h"
#include "io/transform.h"

#include <fmt/format.h>

namespace penumbra {

DensityGrid loadDensityGrid(const std::string& path, const DensityRequest& request) {
  if (const std::string why = unreadableFileReason(path); !why.empty()) throw VdbError("cannot open: " + why);
  DensityGrid grid;
  std::string problem;
  try {
    problem = densityCodec().load(path, request, grid);
  } catch (const std::runtime_error& e) {
    problem = e.what();  // the reader process cannot be found or started
  }
  if (!problem.empty()) throw VdbError(problem);
  grid.majorants = buildMajorantGrid(grid);
  return grid;
}

std::shared_ptr<const DensityGrid> readDensity(const JsonNode& node, Scene& scene) {
  node.allowKeys({"file", "grid", "scale", "transform"});
  const JsonNode fileNode = node.required("file", " for a density (an OpenVDB .vdb path)");
  const std::string file = fileNode.asString();
  if (file.empty()) fileNode.fail("must not be empty");
  DensityRequest request;
  if (node.has("grid")) {
    request.grid = node.child("grid").asString();
    if (request.grid.empty()) node.child("grid").fail("must not be empty (leave it out for the first float grid)");
  }
  request.scale = node.floatOr("scale", 1.0f, Range::between(0.0, kMaxColorComponent));
  if (node.has("transform")) {
    const JsonNode t = node.child("transform");
    t.allowKeys({"translate", "rotate", "scale"});
    const Transform placed = readTransform(t);
    glm::dmat4 m(glm::dmat3(placed.linear()));
    m[3] = glm::dvec4(glm::dvec3(placed.translate), 1.0);
    request.objectToWorld = m;
  }
  request.maxVoxels = kMaxDensityVoxels;
  request.maxBytes = node.context().limits.maxBytes;
  request.maxValue = kMaxColorComponent;
  request.maxCoordinate = kMaxCoordinate;
  const std::string path = resolvePath(fileNode, file);
  try {
    auto grid = std::make_shared<const DensityGrid>(loadDensityGrid(path, request));
    scene.inputs.push_back(path);
    return grid;
  } catch (const VdbError& e) {
    fileNode.fail(fmt::format("{}: {}", file, e.what()));
  }
}

}  // namespace penumbra
