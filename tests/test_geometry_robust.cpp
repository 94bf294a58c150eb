// Ray robustness at any scale: no holes between the triangles of a closed box, no
// spawned ray that meets its own surface again, and a 1e-6 slab crossed as two faces.
// The cases the old absolute 3e-5 offset and Embree's default traversal got wrong.
#include "core/rng.h"
#include "core/sampling.h"
#include "geometry/trace_scene.h"
#include "io/shapes.h"
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

const float kScales[] = {1e-5f, 1e-3f, 1.0f, 1e4f, 1e6f};

Scene boxScene(float s, Vec3 lo, Vec3 hi) {
  Scene scene;
  scene.materials.push_back(Material{});
  scene.meshes.push_back(makeBox(lo * s, hi * s, 0));
  return scene;
}

// From inside a closed box every ray hits, also those aimed exactly at its edges and
// corners, where two triangles meet and a non-watertight test can let a ray through.
TEST(RobustTrace, ClosedBoxHasNoHolesAtAnyScale) {
  for (float s : kScales) {
    const Scene scene = boxScene(s, Vec3(-1.0f, -0.7f, -1.3f), Vec3(1.1f, 0.9f, 0.8f));
    const TraceScene tracer(scene);
    const Vec3 eye = Vec3(0.05f, 0.1f, -0.2f) * s;
    Vec3 blo(kInf), bhi(-kInf);
    for (const Vec3& p : scene.meshes[0].positions) { blo = glm::min(blo, p); bhi = glm::max(bhi, p); }
    int misses = 0, rays = 0;
    Rng rng(7);
    for (int e = 0; e < 12; ++e) {
      // Edge e: axis a varies, the other two sit at a min or max corner.
      const int a = e / 4, b = (a + 1) % 3, c = (a + 2) % 3;
      for (int i = 0; i < 2000; ++i) {
        Vec3 p;
        p[a] = blo[a] + (bhi[a] - blo[a]) * rng.uniform();
        p[b] = (e & 1) ? bhi[b] : blo[b];
        p[c] = (e & 2) ? bhi[c] : blo[c];
        Ray ray{eye, glm::normalize(p - eye)};
        Hit hit;
        misses += tracer.intersect(ray, hit) ? 0 : 1;
        ++rays;
      }
    }
    EXPECT_EQ(misses, 0) << "scale " << s << ": " << misses << " of " << rays << " edge rays escaped";
  }
}

// A ray spawned off a wall of a box, into the box, can only meet another wall: meeting
// the same plane again is self-intersection. Grazing bounces are the hard part.
TEST(RobustTrace, SpawnedRaysNeverMeetTheirOwnWall) {
  for (float s : kScales)
  for (bool tilted : {false, true}) {
    Scene scene = boxScene(s, Vec3(-1.0f, -0.9f, -1.2f), Vec3(1.3f, 2.0f, 1.0f));
    if (tilted) {
      // Walls off the axes: the offset must cover the rounding of every axis it mixes.
      const glm::mat3 r = glm::mat3(glm::cos(0.7f), glm::sin(0.7f), 0.0f, -glm::sin(0.7f), glm::cos(0.7f), 0.0f,
                                    0.0f, 0.0f, 1.0f) *
                          glm::mat3(1.0f, 0.0f, 0.0f, 0.0f, glm::cos(0.4f), glm::sin(0.4f), 0.0f,
                                    -glm::sin(0.4f), glm::cos(0.4f));
      for (Vec3& p : scene.meshes[0].positions) p = r * p + Vec3(0.3f, -0.2f, 0.1f) * s;
    }
    const TraceScene tracer(scene);
    Rng rng(11);
    int selfHits = 0, escapes = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec3 centre = tilted ? Vec3(0.3f, -0.2f, 0.1f) * s : Vec3(0.1f, 0.4f, -0.1f) * s;
      Ray ray{centre, uniformSphere(rng.uniform(), rng.uniform())};
      Hit hit;
      ASSERT_TRUE(tracer.intersect(ray, hit));
      const SurfaceRecord rec = tracer.surface(ray, hit, kSurfaceGeometric);
      // Half the bounces within ~0.06 degrees of the wall's plane.
      const float cosTheta = (i & 1) ? rng.uniform() : 1e-3f * rng.uniform();
      const float phi = 2.0f * kPi * rng.uniform(), sinTheta = std::sqrt(1.0f - cosTheta * cosTheta);
      Vec3 t, b;
      orthonormalBasis(rec.ng, t, b);
      const Vec3 dir = glm::normalize(cosTheta * rec.ng + sinTheta * (std::cos(phi) * t + std::sin(phi) * b));
      Ray bounce{spawnOrigin(rec, dir), dir};
      Hit next;
      if (!tracer.intersect(bounce, next)) { ++escapes; continue; }
      const SurfaceRecord nrec = tracer.surface(bounce, next, kSurfaceGeometric);
      if (glm::dot(nrec.ng, rec.ng) > 0.999f) ++selfHits;
    }
    EXPECT_EQ(selfHits, 0) << "scale " << s << (tilted ? ", tilted" : "");
    EXPECT_EQ(escapes, 0) << "scale " << s << (tilted ? ", tilted" : "");
  }
}

// Off a sphere: a reflected ray leaves it for good, and a ray sent straight in meets
// the far side one diameter later, not its own entry point.
TEST(RobustTrace, SphereSpawnsLeaveAndCrossAtAnyScale) {
  for (float s : kScales) {
    Scene scene;
    scene.materials.push_back(Material{});
    scene.spheres.push_back(Sphere{Vec3(3.0f, 1.0f, -2.0f) * s, 0.5f * s, 0});
    const TraceScene tracer(scene);
    Rng rng(5);
    int reHits = 0, badChords = 0;
    for (int i = 0; i < 5000; ++i) {
      const Vec3 target = scene.spheres[0].center + 0.45f * s * uniformSphere(rng.uniform(), rng.uniform());
      const Vec3 eye = Vec3(0.0f, 0.5f, 4.0f) * s;
      Ray ray{eye, glm::normalize(target - eye)};
      Hit hit;
      if (!tracer.intersect(ray, hit)) continue;
      const SurfaceRecord rec = tracer.surface(ray, hit, kSurfaceGeometric);
      const Vec3 out = glm::reflect(ray.dir, rec.ng);
      Hit again;
      reHits += tracer.intersect(Ray{spawnOrigin(rec, out), out}, again) ? 1 : 0;
      const Vec3 in = -rec.ng;  // ng faces the eye: -ng points at the centre
      Hit far;
      const bool crossed = tracer.intersect(Ray{spawnOrigin(rec, in), in}, far);
      if (!crossed || std::abs(far.t - 1.0f * s) > 1e-3f * s) ++badChords;
    }
    EXPECT_EQ(reHits, 0) << "scale " << s;
    EXPECT_EQ(badChords, 0) << "scale " << s;
  }
}

// A slab 1e-6 thick (8 ulps at z ~ 1) is entered and left as two faces: the ray that
// enters meets the back face one thickness later.
TEST(RobustTrace, MicronSlabHasTwoFaces) {
  const float thickness = 1e-6f;
  const Scene scene = boxScene(1.0f, Vec3(-1.0f, -1.0f, 1.0f), Vec3(1.0f, 1.0f, 1.0f + thickness));
  const TraceScene tracer(scene);
  Rng rng(3);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 eye(0.3f, -0.2f, 3.0f);
    const Vec3 target(rng.uniform() - 0.5f, rng.uniform() - 0.5f, 1.0f);
    Ray ray{eye, glm::normalize(target - eye)};
    Hit front;
    ASSERT_TRUE(tracer.intersect(ray, front));
    const SurfaceRecord rec = tracer.surface(ray, front, kSurfaceGeometric);
    ASSERT_TRUE(rec.frontFace);
    Hit back;
    ASSERT_TRUE(tracer.intersect(Ray{spawnOrigin(rec, ray.dir), ray.dir}, back)) << i;
    const SurfaceRecord brec = tracer.surface(ray, back, kSurfaceGeometric);
    // The back face (z = 1), met from inside, to within its own rounding.
    EXPECT_FALSE(brec.frontFace) << i;
    EXPECT_NEAR(brec.position.z, 1.0f, brec.error) << i;
    EXPECT_LT(back.t, 2.0f * thickness / std::abs(ray.dir.z)) << i;
  }
}

// Rays Embree would abort on (NaN, beyond +-1.844e18, negative tnear) are misses for
// intersect and blocked for occluded: the process lives and no light arrives.
TEST(RobustTrace, RaysOutsideEmbreesDomainAreRefusedNotFatal) {
  const Scene scene = boxScene(1.0f, Vec3(-1.0f), Vec3(1.0f));
  const TraceScene tracer(scene);
  const float nan = std::nanf("");
  const Ray bad[] = {Ray{Vec3(nan, 0, 0), Vec3(0, 0, 1)}, Ray{Vec3(0.0f), Vec3(0, nan, 1)},
                     Ray{Vec3(2e18f, 0, 0), Vec3(-1, 0, 0)}, Ray{Vec3(0.0f), Vec3(0, 0, 1), -1.0f},
                     Ray{Vec3(0.0f), Vec3(0, 0, 1), 0.0f, nan}};
  for (const Ray& r : bad) {
    Hit hit;
    EXPECT_FALSE(tracer.intersect(r, hit));
    EXPECT_TRUE(tracer.occluded(r));
  }
  Hit hit;
  EXPECT_TRUE(tracer.intersect(Ray{Vec3(0.0f), Vec3(0, 0, 1)}, hit));  // the guard passes real rays
}

}  // namespace
}  // namespace penumbra
