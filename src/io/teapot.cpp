// Tessellation of Newell's teapot patches: Bezier evaluation, normals that
// survive degenerate patch corners, and welding patches into one smooth mesh.
#include "io/teapot.h"

#include "core/error.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace penumbra::teapot_data {
// The control net, defined in teapot_data.cpp: 32 patches x 16 point indices.
extern const uint16_t kPatches[32][16];
extern const float kPoints[290][3];
}  // namespace penumbra::teapot_data

namespace penumbra {
namespace {

using DVec3 = glm::dvec3;

constexpr int kPatchCount = 32;
constexpr int kMaxSubdivisions = 128;
constexpr double kScale = 1.0 / 3.15;  // data height (knob top z = 3.15) -> 1
// Positions closer than this (after scaling) are one point. Patch evaluations
// of a shared edge differ by ~1e-16; distinct grid points at N = 128 are >5e-6 apart.
constexpr double kWeldTolerance = 1e-7;
constexpr double kWeldCell = 1e-6;
// Normals of coincident vertices are averaged only when they roughly agree, so
// a genuine crease (the handle's end meets a body corner) stays a crease.
constexpr double kSmoothCos = 0.5;

// Data frame is z-up: rotate -90 degrees about x, (x, y, z) -> (x, z, -y). A
// proper rotation, so cross products (and hence outward normals) carry over.
DVec3 controlPoint(int index) {
  const float* p = teapot_data::kPoints[index];
  return DVec3(p[0], p[2], -p[1]) * kScale;
}

struct Patch {
  DVec3 p[4][4];  // [row: v][column: u]
};

Patch loadPatch(int patch) {
  Patch result;
  for (int k = 0; k < 16; ++k) result.p[k / 4][k % 4] = controlPoint(teapot_data::kPatches[patch][k]);
  return result;
}

void bernstein(double t, double b[4], double d[4]) {
  double s = 1.0 - t;
  b[0] = s * s * s;
  b[1] = 3.0 * t * s * s;
  b[2] = 3.0 * t * t * s;
  b[3] = t * t * t;
  d[0] = -3.0 * s * s;
  d[1] = 3.0 * s * s - 6.0 * t * s;
  d[2] = 6.0 * t * s - 3.0 * t * t;
  d[3] = 3.0 * t * t;
}

struct SurfacePoint {
  DVec3 position{0.0}, du{0.0}, dv{0.0};
};

SurfacePoint evaluate(const Patch& patch, double u, double v) {
  double bu[4], du[4], bv[4], dv[4];
  bernstein(u, bu, du);
  bernstein(v, bv, dv);
  SurfacePoint s;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      s.position += bv[i] * bu[j] * patch.p[i][j];
      s.du += bv[i] * du[j] * patch.p[i][j];
      s.dv += dv[i] * bu[j] * patch.p[i][j];
    }
  return s;
}

// dP/du x dP/dv points outward for every patch of this data set (checked patch
// by patch). Where a whole patch edge collapses to one point (lid knob top,
// base centre) one derivative vanishes; the normal there is the limit from
// inside the patch, so step a hair towards the patch centre and ask again.
DVec3 patchNormal(const Patch& patch, double u, double v) {
  constexpr double kStep = 1e-5;
  for (int attempt = 0; attempt < 4; ++attempt) {
    SurfacePoint s = evaluate(patch, u, v);
    DVec3 n = glm::cross(s.du, s.dv);
    double length = glm::length(n);
    if (length > 1e-12) return n / length;
    double step = kStep * std::pow(10.0, attempt);
    u += u < 0.5 ? step : -step;
    v += v < 0.5 ? step : -step;
  }
  return DVec3(0.0, 1.0, 0.0);  // unreachable for this data set
}

struct RawVertex {
  DVec3 position, normal;
  int i, j;  // grid row (v) and column (u)
};

// Groups positions within kWeldTolerance: hash on a fine grid, search the 27
// neighbouring cells so points straddling a cell border still meet. Only a patch's
// border can meet another patch (a patch's own grid points lie far apart), so
// inner points join as classes of their own without a search.
class PositionWelder {
 public:
  int classOf(const DVec3& p) {
    int64_t key[3];
    for (int a = 0; a < 3; ++a) key[a] = static_cast<int64_t>(std::llround(p[a] / kWeldCell));
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = cells_.find(hash(key[0] + dx, key[1] + dy, key[2] + dz));
          if (it == cells_.end()) continue;
          for (int id : it->second)
            if (glm::length(representatives_[id] - p) < kWeldTolerance) return id;
        }
    const int id = ownClass(p);
    cells_[hash(key[0], key[1], key[2])].push_back(id);
    return id;
  }
  int ownClass(const DVec3& p) {
    representatives_.push_back(p);
    return static_cast<int>(representatives_.size()) - 1;
  }
  const DVec3& representative(int id) const { return representatives_[id]; }
  size_t classes() const { return representatives_.size(); }

 private:
  static uint64_t hash(int64_t x, int64_t y, int64_t z) {
    return static_cast<uint64_t>(x) * 73856093u ^ static_cast<uint64_t>(y) * 19349663u ^
           static_cast<uint64_t>(z) * 83492791u;
  }
  std::unordered_map<uint64_t, std::vector<int>> cells_;
  std::vector<DVec3> representatives_;
};

// The members of each class, as one array sorted by class (a class's members in
// their order of appearance): offsets[c] .. offsets[c + 1] index into members.
struct ClassMembers {
  std::vector<uint32_t> offsets, members;
  ClassMembers(const std::vector<int>& classOf, size_t classes) : offsets(classes + 1, 0), members(classOf.size()) {
    for (int c : classOf) ++offsets[c + 1];
    for (size_t c = 0; c < classes; ++c) offsets[c + 1] += offsets[c];
    std::vector<uint32_t> next(offsets.begin(), offsets.end() - 1);
    for (size_t r = 0; r < classOf.size(); ++r) members[next[classOf[r]]++] = static_cast<uint32_t>(r);
  }
};

}  // namespace

TriangleMesh makeTeapot(int subdivisions) {
  if (subdivisions < 1 || subdivisions > kMaxSubdivisions) {
    throw InputError("teapot: subdivisions must be in [1, 128], got " +
                     std::to_string(subdivisions));
  }
  const int n = subdivisions;
  const int side = n + 1;

  // 1. Evaluate every patch on its grid.
  std::vector<RawVertex> raw;
  raw.reserve(static_cast<size_t>(kPatchCount) * side * side);
  for (int patchIndex = 0; patchIndex < kPatchCount; ++patchIndex) {
    Patch patch = loadPatch(patchIndex);
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        double u = static_cast<double>(j) / n, v = static_cast<double>(i) / n;
        raw.push_back({evaluate(patch, u, v).position, patchNormal(patch, u, v), i, j});
      }
  }

  // 2. Group coincident positions; each vertex's normal becomes the average of
  // the agreeing normals in its group, so shared patch edges shade seamlessly.
  PositionWelder welder;
  std::vector<int> classOf(raw.size());
  for (size_t r = 0; r < raw.size(); ++r) {
    const bool border = raw[r].i == 0 || raw[r].j == 0 || raw[r].i == n || raw[r].j == n;
    classOf[r] = border ? welder.classOf(raw[r].position) : welder.ownClass(raw[r].position);
  }
  const ClassMembers groups(classOf, welder.classes());
  std::vector<DVec3> smoothNormal(raw.size());
  for (size_t r = 0; r < raw.size(); ++r) {
    DVec3 sum(0.0);
    for (uint32_t m = groups.offsets[classOf[r]]; m < groups.offsets[classOf[r] + 1]; ++m) {
      const DVec3& other = raw[groups.members[m]].normal;
      if (glm::dot(other, raw[r].normal) > kSmoothCos) sum += other;
    }
    smoothNormal[r] = glm::normalize(sum);  // includes raw[r] itself, so non-zero
  }

  // 3. Merge vertices that agree in position, uv and normal. Patch uvs differ
  // across patch edges, so those stay split (the texture must not wrap back
  // across a triangle); the normals above already hide the split. A vertex is
  // compared with the earlier members of its class that began a vertex.
  std::vector<uint32_t> vertexOf(raw.size());
  std::vector<int> firstRaw;
  for (size_t r = 0; r < raw.size(); ++r) {
    uint32_t found = UINT32_MAX;
    for (uint32_t m = groups.offsets[classOf[r]]; m < groups.offsets[classOf[r] + 1]; ++m) {
      const uint32_t earlier = groups.members[m];
      if (earlier >= r) break;
      const uint32_t candidate = vertexOf[earlier];
      if (static_cast<uint32_t>(firstRaw[candidate]) != earlier) continue;  // merged into another
      const RawVertex& c = raw[earlier];
      if (c.i == raw[r].i && c.j == raw[r].j &&
          glm::dot(smoothNormal[earlier], smoothNormal[r]) > 1.0 - 1e-9) {
        found = candidate;
        break;
      }
    }
    if (found == UINT32_MAX) {
      found = static_cast<uint32_t>(firstRaw.size());
      firstRaw.push_back(static_cast<int>(r));
    }
    vertexOf[r] = found;
  }

  // 4. Two counter-clockwise triangles per grid cell (a -> b is +u, a -> d is
  // +v, so (a, b, c) faces along dP/du x dP/dv, outward); drop zero-area ones.
  TriangleMesh mesh;
  mesh.name = "teapot";
  std::vector<uint32_t> remap(firstRaw.size(), UINT32_MAX);
  auto emit = [&](size_t ra, size_t rb, size_t rc) {
    uint32_t a = vertexOf[ra], b = vertexOf[rb], c = vertexOf[rc];
    if (a == b || b == c || a == c) return;
    const DVec3& pa = welder.representative(classOf[ra]);
    const DVec3& pb = welder.representative(classOf[rb]);
    const DVec3& pc = welder.representative(classOf[rc]);
    if (glm::length(glm::cross(pb - pa, pc - pa)) < 1e-12) return;
    std::array<uint32_t, 3> triangle{};
    const uint32_t vertices[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      uint32_t& index = remap[vertices[k]];
      if (index == UINT32_MAX) {  // first use: append, so unused vertices vanish
        size_t r = static_cast<size_t>(firstRaw[vertices[k]]);
        index = static_cast<uint32_t>(mesh.positions.size());
        mesh.positions.push_back(Vec3(welder.representative(classOf[r])));
        mesh.normals.push_back(Vec3(smoothNormal[r]));
        mesh.uvs.push_back(Vec2(static_cast<float>(raw[r].j) / n, static_cast<float>(raw[r].i) / n));
      }
      triangle[k] = index;
    }
    mesh.triangles.push_back(triangle);
  };
  for (int patchIndex = 0; patchIndex < kPatchCount; ++patchIndex) {
    size_t base = static_cast<size_t>(patchIndex) * side * side;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        size_t a = base + static_cast<size_t>(i) * side + j;
        size_t b = a + 1, d = a + side, c = d + 1;
        emit(a, b, c);
        emit(a, c, d);
      }
  }
  return mesh;
}

}  // namespace penumbra
