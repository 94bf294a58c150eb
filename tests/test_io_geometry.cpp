// Scene geometry as the loader builds it: quad and box winding, transforms
// (order, mirroring, normals) and OBJ loading (smooth normals, unification).
#include "core/error.h"
#include "io/mesh_normals.h"
#include "io/obj_loader.h"
#include "io/scene_loader.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace penumbra;

namespace {

const std::string kDataDir = std::string(PENUMBRA_SOURCE_DIR) + "/tests/data/";

// Parses a scene holding the given objects (JSON array body) and returns its meshes.
std::vector<TriangleMesh> meshesOf(const std::string& objects) {
  return parseScene("{\"objects\": [" + objects + "]}", kDataDir + "scene.json").meshes;
}

Vec3 geometricNormal(const TriangleMesh& m, size_t t) {
  const auto& tri = m.triangles[t];
  return glm::normalize(glm::cross(m.positions[tri[1]] - m.positions[tri[0]],
                                   m.positions[tri[2]] - m.positions[tri[0]]));
}

void expectNear(const Vec3& a, const Vec3& b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

// Every triangle of a closed convex mesh faces away from `center`.
void expectOutward(const TriangleMesh& m, const Vec3& center) {
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    Vec3 centroid = (m.positions[tri[0]] + m.positions[tri[1]] + m.positions[tri[2]]) / 3.0f;
    EXPECT_GT(glm::dot(geometricNormal(m, t), centroid - center), 0.0f) << "triangle " << t;
  }
}

}  // namespace

TEST(Geometry, QuadNormalIsCrossOfEdges) {
  auto meshes = meshesOf(
      R"({"type": "quad", "corner": [1, 2, 3], "edge1": [2, 0, 0], "edge2": [0, 0, -3]})");
  ASSERT_EQ(meshes.size(), 1u);
  const TriangleMesh& q = meshes[0];
  ASSERT_EQ(q.positions.size(), 4u);
  expectNear(q.positions[0], Vec3(1, 2, 3));
  expectNear(q.positions[1], Vec3(3, 2, 3));
  expectNear(q.positions[2], Vec3(3, 2, 0));
  expectNear(q.positions[3], Vec3(1, 2, 0));
  // cross((1,0,0), (0,0,-1)) = (0,1,0): both triangles and the stored normals agree.
  expectNear(geometricNormal(q, 0), Vec3(0, 1, 0));
  expectNear(geometricNormal(q, 1), Vec3(0, 1, 0));
  for (const Vec3& n : q.normals) expectNear(n, Vec3(0, 1, 0));
  ASSERT_EQ(q.uvs.size(), 4u);
  EXPECT_EQ(q.uvs[0], Vec2(0, 0));
  EXPECT_EQ(q.uvs[1], Vec2(1, 0));
  EXPECT_EQ(q.uvs[2], Vec2(1, 1));
  EXPECT_EQ(q.uvs[3], Vec2(0, 1));
}

TEST(Geometry, BoxIsFlatAndFacesOutward) {
  auto meshes = meshesOf(R"({"type": "box", "min": [-1, 0, 2], "max": [1, 3, 5]})");
  const TriangleMesh& b = meshes.at(0);
  EXPECT_EQ(b.positions.size(), 8u);
  EXPECT_EQ(b.triangles.size(), 12u);
  EXPECT_TRUE(b.normals.empty());
  EXPECT_TRUE(b.uvs.empty());
  expectOutward(b, Vec3(0, 1.5f, 3.5f));
  // Each axis direction is covered by exactly two triangles.
  int perAxis[6] = {};
  for (size_t t = 0; t < 12; ++t) {
    Vec3 n = geometricNormal(b, t);
    for (int a = 0; a < 3; ++a) {
      if (n[a] > 0.999f) ++perAxis[2 * a + 1];
      if (n[a] < -0.999f) ++perAxis[2 * a];
    }
  }
  for (int count : perAxis) EXPECT_EQ(count, 2);
}

TEST(Geometry, MirroringScaleFlipsWinding) {
  auto meshes = meshesOf(R"({"type": "box", "min": [0, 0, 0], "max": [1, 2, 3], "scale": -1},
                            {"type": "box", "min": [0, 0, 0], "max": [1, 2, 3], "scale": [-2, 1, 1]},
                            {"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0],
                             "edge2": [0, 1, 0], "scale": [1, 1, -1]})");
  // Mirrored boxes occupy the mirrored space and still face outwards.
  expectNear(meshes[0].positions[7], Vec3(-1, -2, -3));
  expectOutward(meshes[0], Vec3(-0.5f, -1, -1.5f));
  expectOutward(meshes[1], Vec3(-1, 1, 1.5f));
  // A quad in z = 0 mirrored in z keeps its +z normal (the plane maps onto
  // itself), and the flipped winding agrees with the transformed normals.
  expectNear(meshes[2].normals[0], Vec3(0, 0, -1));
  expectNear(geometricNormal(meshes[2], 0), Vec3(0, 0, -1));
  expectNear(geometricNormal(meshes[2], 1), Vec3(0, 0, -1));
}

TEST(Geometry, RotationOrderIsXThenYThenZ) {
  const char* quad = R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0],)";
  auto meshes = meshesOf(std::string(quad) + R"("rotate": [0, 0, 90]},)" + quad +
                         R"("rotate": [90, 0, 0]},)" + quad + R"("rotate": [90, 90, 0]},)" +
                         quad + R"("scale": 2, "rotate": [0, 0, 90], "translate": [1, 0, 0]})");
  // 90 degrees about z: x -> y, y -> -x; the normal stays +z. Exactly, not nearly.
  EXPECT_EQ(meshes[0].positions[1], Vec3(0, 1, 0));
  EXPECT_EQ(meshes[0].positions[3], Vec3(-1, 0, 0));
  expectNear(meshes[0].normals[0], Vec3(0, 0, 1));
  // 90 degrees about x: y -> z, z -> -y.
  EXPECT_EQ(meshes[1].positions[3], Vec3(0, 0, 1));
  expectNear(meshes[1].normals[0], Vec3(0, -1, 0));
  expectNear(geometricNormal(meshes[1], 0), Vec3(0, -1, 0));
  // X first, then Y: y -> z -> x. (Y first would give y -> y -> z.)
  EXPECT_EQ(meshes[2].positions[3], Vec3(1, 0, 0));
  // Scale, then rotate, then translate: (1,0,0) -> (2,0,0) -> (0,2,0) -> (1,2,0).
  EXPECT_EQ(meshes[3].positions[1], Vec3(1, 2, 0));
}

TEST(Geometry, NonUniformScaleTransformsNormalsByInverseTranspose) {
  // A 45-degree slope x + y = 1 stretched by 2 in x becomes x/2 + y = 1, whose
  // normal is (1, 2, 0)/sqrt(5); transforming the normal like a point would give (2, 1, 0).
  auto meshes = meshesOf(R"({"type": "quad", "corner": [1, 0, 0], "edge1": [0, 0, -1],
                             "edge2": [-1, 1, 0], "scale": [2, 1, 1]})");
  Vec3 expected = glm::normalize(Vec3(1, 2, 0));
  expectNear(meshes[0].normals[0], expected);
  expectNear(geometricNormal(meshes[0], 0), expected);
}

TEST(Geometry, ObjWithoutNormalsGetsAngleWeightedNormals) {
  TriangleMesh m = loadObj(kDataDir + "tetra_no_normals.obj");
  EXPECT_EQ(m.name, "tetra_no_normals");
  ASSERT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(m.normals.size(), 4u);
  EXPECT_TRUE(m.uvs.empty());
  EXPECT_EQ(m.triangles.size(), 4u);
  // Vertices are numbered in order of first use, so look them up by position.
  auto normalAt = [&](const Vec3& p) {
    for (size_t i = 0; i < m.positions.size(); ++i) {
      if (m.positions[i] == p) return m.normals[i];
    }
    ADD_FAILURE() << "no vertex at the expected position";
    return Vec3(0.0f);
  };
  // At the origin three right angles meet, normals -x, -y, -z: (-1,-1,-1)/sqrt(3).
  expectNear(normalAt(Vec3(0, 0, 0)), Vec3(-1.0f) / std::sqrt(3.0f));
  // At X = (1,0,0): faces -z and -y with 45-degree corners and the slanted face
  // (1,1,1)/sqrt(3) with a 60-degree corner:
  //   n ~ pi/4 (0,0,-1) + pi/4 (0,-1,0) + pi/3 (1,1,1)/sqrt(3)
  //     = (0.6045998, -0.1807984, -0.1807984) -> (0.9210245, -0.2754214, -0.2754214).
  // Area weighting would give (1,0,0), an unweighted mean (0.695,-0.509,-0.509).
  expectNear(normalAt(Vec3(1, 0, 0)), Vec3(0.9210245f, -0.2754214f, -0.2754214f));
  expectNear(normalAt(Vec3(0, 1, 0)), Vec3(-0.2754214f, 0.9210245f, -0.2754214f));
}

TEST(Geometry, AngleWeightedNormalsSkipDegenerateFaces) {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {5, 5, 5}};
  // Triangle 2 is a zero-area sliver along the x axis; position 4 only has it.
  std::vector<Vec3> n = angleWeightedNormals(p, {{0, 1, 2}, {0, 3, 1}, {4, 4, 4}});
  expectNear(n[0], Vec3(0, 0, 1));
  expectNear(n[1], Vec3(0, 0, 1));
  expectNear(n[4], Vec3(0, 0, 1));  // untouched: the documented fallback
}

TEST(Geometry, ObjVerticesAreUnifiedPerIndexTriple) {
  TriangleMesh m = loadObj(kDataDir + "quad_uv_seam.obj");
  // Corners (1,1) (2,2) (3,3) | (1,4) (3,3) (4,5): five distinct triples.
  ASSERT_EQ(m.positions.size(), 5u);
  ASSERT_EQ(m.uvs.size(), 5u);
  ASSERT_EQ(m.triangles.size(), 2u);
  const auto& t0 = m.triangles[0];
  const auto& t1 = m.triangles[1];
  EXPECT_EQ(t0[2], t1[1]);  // (3,3) is shared
  EXPECT_NE(t0[0], t1[0]);  // position 1 is split by its two uvs
  EXPECT_EQ(m.positions[t0[0]], m.positions[t1[0]]);
  // v flipped: OBJ's v = 0 is the image's bottom, the lookup's t = 0 its top.
  EXPECT_EQ(m.uvs[t0[0]], Vec2(0, 1));
  EXPECT_EQ(m.uvs[t1[0]], Vec2(0.25f, 1));
  EXPECT_EQ(m.uvs[t1[2]], Vec2(0, 0));
  // The seam does not split the smooth normal: both copies share it.
  for (const Vec3& n : m.normals) expectNear(n, Vec3(0, 0, 1));
}

TEST(Geometry, ObjNormalsFromFileAreRenormalised) {
  TriangleMesh m = loadObj(kDataDir + "quad_normals.obj");
  EXPECT_EQ(m.triangles.size(), 2u);  // the 4-gon was triangulated
  EXPECT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(m.normals.size(), 4u);
  for (const Vec3& n : m.normals) EXPECT_EQ(n, Vec3(0, 0, 1));
  expectNear(geometricNormal(m, 0), Vec3(0, 0, 1));
}

TEST(Geometry, MeshObjectsResolveRelativePathsAndTransform) {
  auto meshes = meshesOf(R"({"type": "mesh", "file": "tetra_no_normals.obj",
                             "translate": [0, 10, 0], "rotate": [0, 0, 90]})");
  ASSERT_EQ(meshes.size(), 1u);
  // The file lists the origin first; rotated 90 degrees about z, x -> y.
  expectNear(meshes[0].positions[0], Vec3(0, 10, 0));
  expectNear(meshes[0].normals[0], Vec3(1, -1, -1) / std::sqrt(3.0f));
  bool foundX = false;
  for (const Vec3& p : meshes[0].positions) foundX = foundX || glm::length(p - Vec3(0, 11, 0)) < 1e-6f;
  EXPECT_TRUE(foundX);
}

TEST(Geometry, TeapotIsTransformedAndBound) {
  Scene s = parseScene(R"({"materials": {"china": {}},
      "objects": [{"type": "teapot", "subdivisions": 2, "material": "china",
                   "translate": [0, 5, 0]}]})",
                       kDataDir + "scene.json");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_FALSE(s.meshes[0].triangles.empty());
  for (const Vec3& p : s.meshes[0].positions) EXPECT_GE(p.y, 5.0f - 1e-4f);
}
