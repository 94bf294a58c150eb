// The built-in teapot: counts, unit outward normals that agree with the
// winding, the documented frame and bounds, and seamless welded patch edges.
#include "core/error.h"
#include "io/teapot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <tuple>

using namespace penumbra;

namespace {

Vec3 faceNormal(const TriangleMesh& mesh, const std::array<uint32_t, 3>& t) {
  const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
  return glm::normalize(glm::cross(b - a, c - a));
}

// Positions rounded to 1e-5: vertices that are one point land in one key.
std::tuple<long, long, long> positionKey(const Vec3& p) {
  return {std::lround(p.x * 1e5f), std::lround(p.y * 1e5f), std::lround(p.z * 1e5f)};
}

}  // namespace

TEST(Teapot, CountsFollowTheGrid) {
  for (int n : {2, 4, 8, 16}) {
    TriangleMesh mesh = makeTeapot(n);
    const size_t rawVertices = 32u * (n + 1) * (n + 1);
    // Every cell gives two triangles, except that the row touching the knob top
    // (4 patches) and the base centre (4 patches) loses one per cell.
    EXPECT_EQ(mesh.triangles.size(), 64u * n * n - 8u * n) << n;
    EXPECT_LT(mesh.positions.size(), rawVertices) << n;
    EXPECT_GT(mesh.positions.size(), rawVertices * 8 / 10) << n;
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
    EXPECT_EQ(mesh.uvs.size(), mesh.positions.size());
  }
  EXPECT_EQ(makeTeapot(8).triangles.size(), 4032u);
}

TEST(Teapot, RejectsSubdivisionsOutOfRange) {
  EXPECT_THROW(makeTeapot(0), InputError);
  EXPECT_THROW(makeTeapot(129), InputError);
  EXPECT_NO_THROW(makeTeapot(1));
}

TEST(Teapot, IndicesAndUvsAreValid) {
  TriangleMesh mesh = makeTeapot(8);
  std::vector<bool> used(mesh.positions.size(), false);
  for (const auto& t : mesh.triangles) {
    for (uint32_t i : t) {
      ASSERT_LT(i, mesh.positions.size());
      used[i] = true;
    }
    EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
    EXPECT_GT(glm::length(glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                     mesh.positions[t[2]] - mesh.positions[t[0]])),
              0.0f);
  }
  for (bool u : used) EXPECT_TRUE(u);  // no orphan vertices
  for (const Vec2& uv : mesh.uvs) {
    EXPECT_GE(uv.x, 0.0f);
    EXPECT_LE(uv.x, 1.0f);
    EXPECT_GE(uv.y, 0.0f);
    EXPECT_LE(uv.y, 1.0f);
  }
}

TEST(Teapot, NormalsAreFiniteUnitAndAgreeWithWinding) {
  for (int n : {4, 8, 32}) {
    TriangleMesh mesh = makeTeapot(n);
    for (const Vec3& normal : mesh.normals) {
      ASSERT_TRUE(isFinite(normal));
      EXPECT_NEAR(glm::length(normal), 1.0f, 1e-5f);
    }
    size_t agree = 0, total = 0;
    for (const auto& t : mesh.triangles) {
      Vec3 face = faceNormal(mesh, t);
      for (uint32_t i : t) {
        agree += glm::dot(face, mesh.normals[i]) > 0.0f;
        ++total;
      }
    }
    EXPECT_GT(static_cast<double>(agree) / total, 0.99) << n;
  }
}

TEST(Teapot, NormalsPointOutward) {
  TriangleMesh mesh = makeTeapot(8);
  size_t top = 0, bottom = 0, front = 0, spout = 0;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    if (mesh.positions[i].y > mesh.positions[top].y) top = i;
    if (mesh.positions[i].y < mesh.positions[bottom].y) bottom = i;
    if (mesh.positions[i].z > mesh.positions[front].z) front = i;
    if (mesh.positions[i].x > mesh.positions[spout].x) spout = i;
  }
  EXPECT_GT(mesh.normals[top].y, 0.999f);      // knob top: a degenerate corner
  EXPECT_LT(mesh.normals[bottom].y, -0.999f);  // base centre: another one
  EXPECT_GT(mesh.normals[front].z, 0.9f);      // widest point of the body
  EXPECT_GT(mesh.normals[spout].x, 0.5f);      // outer side of the spout lip
  EXPECT_NEAR(mesh.positions[top].x, 0.0f, 1e-6f);
  EXPECT_NEAR(mesh.positions[bottom].x, 0.0f, 1e-6f);
}

TEST(Teapot, BoundingBoxIsAsDocumented) {
  TriangleMesh mesh = makeTeapot(16);
  Vec3 lo(kInf), hi(-kInf);
  for (const Vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  EXPECT_NEAR(lo.y, 0.0f, 1e-6f);
  EXPECT_NEAR(hi.y, 1.0f, 1e-6f);
  EXPECT_NEAR(lo.x, -3.0f / 3.15f, 1e-4f);  // handle
  EXPECT_NEAR(hi.x, 1.090f, 2e-3f);         // spout lip
  EXPECT_NEAR(lo.z, -2.0f / 3.15f, 1e-4f);  // body radius 2
  EXPECT_NEAR(hi.z, 2.0f / 3.15f, 1e-4f);
}

TEST(Teapot, PatchEdgesAreWeldedSeamlessly) {
  const int n = 8;
  TriangleMesh mesh = makeTeapot(n);
  std::map<std::tuple<long, long, long>, std::vector<uint32_t>> byPosition;
  for (uint32_t i = 0; i < mesh.positions.size(); ++i)
    byPosition[positionKey(mesh.positions[i])].push_back(i);
  // Shared patch edges collapse: far fewer distinct points than grid vertices.
  EXPECT_LT(byPosition.size(), 32u * (n + 1) * (n + 1) * 85 / 100);

  // Vertices at one point (split only for their patch uvs) share one normal,
  // unless they sit on a genuine crease.
  size_t shared = 0, creases = 0;
  for (const auto& [key, ids] : byPosition)
    for (size_t a = 1; a < ids.size(); ++a) {
      float d = glm::dot(mesh.normals[ids[0]], mesh.normals[ids[a]]);
      if (d > 0.5f) {
        EXPECT_GT(d, 1.0f - 1e-6f);
        ++shared;
      } else {
        ++creases;
      }
    }
  EXPECT_GT(shared, 400u);
  EXPECT_LE(creases, 4u);  // 2 at N = 8: where the handle's lower end meets the body
}

TEST(Teapot, PointsThatMeetShareOneNormalEvenAtTheFinestGrid) {
  // Welding searches only patch borders. Vertices a hair apart would be a missed
  // weld; vertices at one point (split for their patch uvs) carry one averaged
  // normal, bit for bit, unless they sit on a crease (more than 60 degrees apart).
  TriangleMesh mesh = makeTeapot(128);
  std::vector<uint32_t> order(mesh.positions.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto& p = mesh.positions;
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return p[a].x < p[b].x; });
  size_t shared = 0;
  for (size_t i = 0; i < order.size(); ++i)
    for (size_t j = i + 1; j < order.size() && p[order[j]].x - p[order[i]].x < 1e-6f; ++j) {
      const uint32_t a = order[i], b = order[j];
      if (glm::length(p[a] - p[b]) >= 1e-6f) continue;
      ASSERT_EQ(p[a], p[b]) << "vertices " << glm::length(p[a] - p[b]) << " apart";
      if (glm::dot(mesh.normals[a], mesh.normals[b]) < 0.5f) continue;
      EXPECT_EQ(mesh.normals[a], mesh.normals[b]);
      ++shared;
    }
  EXPECT_GT(shared, 32u * 4 * 128);  // every patch edge's points, split by uv
}

TEST(Teapot, IsDeterministic) {
  TriangleMesh a = makeTeapot(6), b = makeTeapot(6);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.triangles, b.triangles);
}
