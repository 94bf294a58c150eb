// OpenVDB float grids resampled into dense density lattices. Placement: the grid's own
// linear transform takes index space to the file's world, then the density's optional
// "transform" (scale, rotate, translate) moves that into the scene.
#include "io/vdb_reader.h"

#include "core/byte_size.h"
#include "io/float_checks.h"
#include "io/input_file.h"
#include "io/scene_sections.h"
#include "io/transform.h"

#include <openvdb/openvdb.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <algorithm>
#include <cmath>
#include <mutex>

namespace penumbra {

namespace {

void initializeOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// The grid's metadata: the named one, or the first float grid.
openvdb::GridBase::Ptr chooseGrid(const openvdb::GridPtrVec& grids, const std::string& wanted) {
  std::vector<std::string> names;
  for (const openvdb::GridBase::Ptr& g : grids) {
    if (!g) continue;
    if (wanted.empty() && g->isType<openvdb::FloatGrid>()) return g;
    if (!wanted.empty() && g->getName() == wanted) {
      if (!g->isType<openvdb::FloatGrid>()) {
        throw VdbError(fmt::format("grid \"{}\" holds {} values, not float", wanted, g->valueType()));
      }
      return g;
    }
    names.push_back("\"" + g->getName() + "\"");
  }
  if (wanted.empty()) throw VdbError("has no float grid");
  throw VdbError(fmt::format("has no grid \"{}\" (it has {})", wanted,
                             names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
}

// Voxels in an inclusive index box, in 64 bits (each side may span 2^32).
uint64_t voxelsIn(const openvdb::CoordBBox& box) {
  uint64_t n = 1;
  for (int a = 0; a < 3; ++a) {
    const uint64_t side = uint64_t(int64_t(box.max()[a]) - int64_t(box.min()[a]) + 1);
    if (side != 0 && n > UINT64_MAX / side) return UINT64_MAX;
    n *= side;
  }
  return n;
}

void checkBudget(const openvdb::CoordBBox& box, const VdbRequest& request) {
  const uint64_t voxels = voxelsIn(box);
  if (request.maxVoxels > 0 && voxels > request.maxVoxels) {
    throw VdbError(fmt::format("its active box has {} voxels, more than the {} a density grid may hold", voxels,
                               request.maxVoxels));
  }
  if (request.maxBytes > 0 && voxels > request.maxBytes / sizeof(float)) {
    throw VdbError(fmt::format("its dense grid would take {}, more than the load budget of {}",
                               formatBytes(double(voxels) * sizeof(float)), formatBytes(double(request.maxBytes))));
  }
}

// The file's own bounding box, written beside each grid by OpenVDB's writer: the budget
// is checked before the tree is read.
void checkBudgetFromMetadata(const openvdb::GridBase& meta, const VdbRequest& request) {
  const auto lo = meta.getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MIN);
  const auto hi = meta.getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MAX);
  if (!lo || !hi) return;
  const openvdb::Coord a(lo->value()), b(hi->value());
  if (a.x() > b.x() || a.y() > b.y() || a.z() > b.z()) return;  // empty: judged after reading
  checkBudget(openvdb::CoordBBox(a, b), request);
}

// Index space -> world of the file, as a column-vector matrix. OpenVDB multiplies row
// vectors (p' = p M), so glm's column-major element [i][j] is M(i, j).
glm::dmat4 indexToWorld(const openvdb::math::Transform& transform) {
  if (!transform.isLinear()) {
    throw VdbError(fmt::format("its transform ({}) is not linear (frustum grids are not supported)",
                               transform.mapType()));
  }
  const openvdb::math::Mat4d m = transform.baseMap()->getAffineMap()->getMat4();
  glm::dmat4 out(1.0);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) out[i][j] = m(i, j);
  }
  return out;
}

DensityGrid resample(const openvdb::FloatGrid& grid, const VdbRequest& request) {
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  if (box.empty()) throw VdbError(fmt::format("grid \"{}\" has no active voxels", grid.getName()));
  checkBudget(box, request);
  DensityGrid out;
  const openvdb::Coord lo = box.min(), dim = box.dim();
  out.nx = dim.x();
  out.ny = dim.y();
  out.nz = dim.z();
  out.values.resize(voxelsIn(box));
  auto accessor = grid.getConstAccessor();
  size_t index = 0;
  for (int k = 0; k < out.nz; ++k) {
    for (int j = 0; j < out.ny; ++j) {
      for (int i = 0; i < out.nx; ++i, ++index) {
        const openvdb::Coord c(lo.x() + i, lo.y() + j, lo.z() + k);
        const float v = accessor.getValue(c);
        const double scaled = double(v) * request.scale;
        if (!std::isfinite(v) || v < 0.0f || !(scaled <= kMaxColorComponent)) {
          throw VdbError(fmt::format("grid \"{}\" has {} at voxel ({}, {}, {}); densities must be finite and "
                                     ">= 0 (and at most 1e+30 after the scale)",
                                     grid.getName(), v, c.x(), c.y(), c.z()));
        }
        out.values[index] = float(scaled);
        out.maxDensity = std::max(out.maxDensity, out.values[index]);
      }
    }
  }
  // World -> lattice: undo the object's placement, the grid's transform, then shift the
  // box's first voxel to (0, 0, 0).
  const glm::dmat4 toWorld = request.objectToWorld * indexToWorld(grid.transform()) *
                             glm::translate(glm::dmat4(1.0), glm::dvec3(lo.x(), lo.y(), lo.z()));
  const double det = glm::determinant(toWorld);
  if (!std::isfinite(det) || det == 0.0) throw VdbError("its transform is singular (a voxel of zero size)");
  out.worldToGrid = glm::mat4(glm::inverse(toWorld));
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(out.worldToGrid[c][r])) throw VdbError("its voxels are too small for single precision");
    }
  }
  // Trilinear lookups reach one voxel past the centres at either end: lattice [-1, n].
  glm::dvec3 wlo(INFINITY), whi(-INFINITY);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec4 p = toWorld * glm::dvec4(corner & 1 ? out.nx : -1, corner & 2 ? out.ny : -1,
                                              corner & 4 ? out.nz : -1, 1.0);
    wlo = glm::min(wlo, glm::dvec3(p));
    whi = glm::max(whi, glm::dvec3(p));
  }
  for (int a = 0; a < 3; ++a) {
    if (!(std::abs(wlo[a]) <= kMaxCoordinate && std::abs(whi[a]) <= kMaxCoordinate)) {
      throw VdbError("its world box reaches beyond 1e+15 (the coordinate limit)");
    }
  }
  out.worldLo = Vec3(wlo);
  out.worldHi = Vec3(whi);
  return out;
}

}  // namespace

DensityGrid loadDensityGrid(const std::string& path, const VdbRequest& request) {
  if (const std::string why = unreadableFileReason(path); !why.empty()) throw VdbError("cannot open: " + why);
  initializeOpenVdb();
  try {
    openvdb::io::File file(path);
    try {
      file.open(false);  // read, not memory-mapped: the file may change while we render
    } catch (const openvdb::Exception&) {
      throw VdbError("not an OpenVDB file");
    }
    const openvdb::GridBase::Ptr meta = chooseGrid(*file.readAllGridMetadata(), request.grid);
    checkBudgetFromMetadata(*meta, request);
    const openvdb::FloatGrid::Ptr grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(meta->getName()));
    file.close();
    if (!grid) throw VdbError(fmt::format("grid \"{}\" is not a float grid", meta->getName()));
    return resample(*grid, request);
  } catch (const openvdb::Exception& e) {
    throw VdbError(fmt::format("cannot be read ({})", e.what()));
  } catch (const std::bad_alloc&) {
    throw VdbError("cannot be read (out of memory while reading its tree)");
  } catch (const std::ios_base::failure& e) {
    throw VdbError(fmt::format("cannot be read ({})", e.what()));
  }
}

std::shared_ptr<const DensityGrid> readDensity(const JsonNode& node, Scene& scene) {
  node.allowKeys({"file", "grid", "scale", "transform"});
  const JsonNode fileNode = node.required("file", " for a density (an OpenVDB .vdb path)");
  const std::string file = fileNode.asString();
  if (file.empty()) fileNode.fail("must not be empty");
  VdbRequest request;
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
