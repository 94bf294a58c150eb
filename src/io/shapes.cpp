// Tessellation of the analytic scene shapes that travel as TriangleMesh.
#include "io/shapes.h"

namespace penumbra {

TriangleMesh makeBox(const Vec3& min, const Vec3& max, int material) {
  TriangleMesh mesh;
  mesh.name = "box";
  mesh.material = material;
  // Corner i takes max on axis k when bit k of i is set: 0 = min, 7 = max.
  for (uint32_t i = 0; i < 8; ++i) {
    mesh.positions.push_back(Vec3((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y,
                                  (i & 4) ? max.z : min.z));
  }
  // Each face as a loop a-b-c-d, counter-clockwise seen from outside.
  const uint32_t faces[6][4] = {
      {0, 4, 6, 2},  // -x
      {1, 3, 7, 5},  // +x
      {0, 1, 5, 4},  // -y
      {2, 6, 7, 3},  // +y
      {0, 2, 3, 1},  // -z
      {4, 5, 7, 6},  // +z
  };
  for (const auto& f : faces) {
    mesh.triangles.push_back({f[0], f[1], f[2]});
    mesh.triangles.push_back({f[0], f[2], f[3]});
  }
  return mesh;
}

}  // namespace penumbra
