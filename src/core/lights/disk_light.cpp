// The disk light: set-up per shading point, uniform samples by area (the concentric map),
// the closed form above both horizons, area, photons and its surface.
#include "core/light_sample.h"
#include "core/light_strata.h"
#include "core/sampling.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {
// Rounding of c + R (x t + y b): a few ulps of the largest terms.
float diskPointError(const Light& light) {
  return gammaBound(6) * (maxComponent(glm::abs(light.position)) + light.radius);
}

Vec3 diskPoint(const Light& light, const Vec3& t, const Vec3& b, float u1, float u2) {
  const Vec2 d = concentricDisk(u1, u2);
  return light.position + light.radius * (d.x * t + d.y * b);
}

// The disc lies wholly above the plane through p of unit normal m: its lowest point
// along m, a . m - R |m's part in the disc's plane|, is above 0 (a = centre - p).
bool above(const Vec3& a, const Vec3& normal, float radius, const Vec3& m) {
  const float c = glm::dot(m, normal);
  return glm::dot(m, a) > radius * std::sqrt(std::max(0.0f, 1.0f - c * c));
}
}  // namespace

void DiskLight::prepare(const Light& light, const Vec3&, LightSampler& s) {
  s.normal = light.direction;
  s.area = area(light);
  s.band = 2.0f * diskPointError(light);
  orthonormalBasis(light.direction, s.t, s.b);
}

LightIncidence DiskLight::sample(const LightSampler& s, float u1, float u2) {
  return planarIncidence(s, diskPoint(*s.light, s.t, s.b, u1, u2));
}

bool DiskLight::irradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E) {
  const Light& light = *s.light;
  const Vec3 a = light.position - s.p;
  if (glm::dot(s.normal, a) >= 0.0f) return true;  // behind its emitting side
  if (!above(a, s.normal, light.radius, n) || !above(a, s.normal, light.radius, ng)) return false;
  // In double: the axial and radial parts, written without the differences that cancel
  // near the axis (S^2 - W^2 = 4 R^2 h^2, Z^2 - S^2 = 4 rho^2 R^2).
  const glm::dvec3 nd(s.normal), ad(a);
  const double h = -glm::dot(nd, ad), R2 = double(light.radius) * light.radius;
  const glm::dvec3 radial = -ad - h * nd;  // from the axis out to p, in the disc's plane
  const double rho = glm::length(radial), h2 = h * h, rho2 = rho * rho;
  const double W = h2 + rho2 - R2, Z = h2 + rho2 + R2;
  const double S = std::sqrt(std::max(0.0, (Z - 2.0 * rho * std::sqrt(R2)) * (Z + 2.0 * rho * std::sqrt(R2))));
  if (!(S > 0.0)) return false;
  const double axial = 0.5 * kPi * (W > 0.0 ? 4.0 * R2 * h2 / (S + W) : S - W) / S;
  const double across = kPi * 2.0 * h * rho * R2 / (S * (Z + S));
  // J points from p towards the disc: down its normal, and in towards its axis.
  glm::dvec3 J = -axial * nd;
  if (rho > 0.0) J -= across * (radial / rho);
  const double factor = glm::dot(glm::dvec3(n), J);
  if (factor > 0.0) E = light.radiance() * static_cast<float>(factor);
  return true;
}

float DiskLight::area(const Light& light) { return kPi * light.radius * light.radius; }

PhotonRay DiskLight::photon(const Light& light, const SceneSphere&, float u1, float u2, float u3, float u4) {
  PhotonRay r;
  Vec3 t, b;
  orthonormalBasis(light.direction, t, b);
  r.origin = diskPoint(light, t, b, u1, u2);
  r.normal = light.direction;
  r.error = diskPointError(light);
  r.stratum = stratumOf(u1, u2);
  r.dir = toWorld(cosineHemisphere(u3, u4), r.normal);
  return r;
}

EmitterShape DiskLight::emitter(const Light& light) {
  Vec3 t, b;
  orthonormalBasis(light.direction, t, b);  // t x b = normal: the fan faces its emitting side
  const double step = 2.0 * kPi / kDiskSides;
  // The polygon's area (sides / 2) rho^2 sin(step) equals pi R^2.
  const float rho = light.radius * static_cast<float>(std::sqrt(step / std::sin(step)));
  TriangleMesh mesh;
  mesh.positions.push_back(light.position);
  mesh.uvs.push_back(Vec2(0.5f));
  for (int k = 0; k < kDiskSides; ++k) {
    const float x = static_cast<float>(std::cos(k * step)), y = static_cast<float>(std::sin(k * step));
    mesh.positions.push_back(light.position + rho * (x * t + y * b));
    mesh.uvs.push_back(Vec2(0.5f + 0.5f * x, 0.5f + 0.5f * y));
    const uint32_t next = static_cast<uint32_t>(1 + (k + 1) % kDiskSides);
    mesh.triangles.push_back({0u, static_cast<uint32_t>(1 + k), next});
  }
  mesh.normals.assign(mesh.positions.size(), light.direction);
  EmitterShape e;
  e.mesh = std::move(mesh);
  return e;
}

}  // namespace penumbra
