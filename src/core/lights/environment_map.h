// The environment light: radiance by direction from a constant sky or a lat-long
// map, the map's importance sampling by luminance (a 2D piecewise-constant
// distribution), its pdf in solid angle, and the photons it sends through the scene.
#pragma once
#include "core/light_sample.h"
#include <memory>
#include <vector>

namespace penumbra {

// A lat-long (equirectangular) map and its sampling tables. Pixel (i, j), row i from
// the top, covers theta in [i, i + 1] pi / height from +y and phi in [j, j + 1] 2 pi /
// width; direction(theta, phi) = (-sin theta sin phi, cos theta, sin theta cos phi), so
// the map's centre column looks along -z (where the default camera looks) and columns
// to its right turn towards +x. The tables live here, in core, beside the sampler that
// reads them: io only decodes pixels, and the trace, emit and plan stages all sample.
struct EnvironmentMap {
  int width = 0, height = 0;
  std::vector<Color> texels;  // row-major, linear radiance before Light::radiance()
  float rotation = 0.0f;      // radians about +y, right-handed: the map's +z turns towards +x
  // Rows drawn by luminance x sin(theta) summed over the row, then a column by
  // luminance within it: marginal has height + 1 entries, conditional height x (width + 1),
  // each a normalised CDF (0 .. 1); a row of zero weight keeps a uniform CDF.
  std::vector<float> marginal;
  std::vector<float> conditional;
  // Sum of luminance x sin(theta) / (width x height): the (u, v) density of pixel (i, j)
  // is lum x sin(theta_i) / weightMean.
  double weightMean = 0.0;
  Color integral{0.0f};  // per channel, the integral of the map's radiance over the sphere
};

// The bytes a width x height map holds once built: its texels and both tables. The
// loader judges a map by it before decoding one, and the resource estimate counts it.
double environmentMapBytes(int width, int height);

// Builds the sampling tables from `texels` (width x height, every value finite and
// >= 0: the loader checks). `rotationDegrees` turns the map about +y.
std::shared_ptr<const EnvironmentMap> makeEnvironmentMap(int width, int height, std::vector<Color> texels,
                                                         float rotationDegrees);

// An environment light of radiance color x intensity, times the map's texel when
// there is one (a constant sky otherwise).
Light makeEnvironmentLight(const Color& color, float intensity, std::shared_ptr<const EnvironmentMap> map);

// The scene's environment light, or null. The loader appends it last, after every
// other light (at most one), so it is found without a search.
inline const Light* environmentOf(const Scene& scene) {
  return !scene.lights.empty() && scene.lights.back().type == LightType::Environment ? &scene.lights.back()
                                                                                     : nullptr;
}

// Radiance arriving from direction `wi` (unit, pointing away from the scene).
Color environmentRadiance(const Light& light, const Vec3& wi);

// One direction towards the environment: wi, the radiance from there and the pdf (in
// solid angle) of having drawn it; invalid when pdf is 0.
struct EnvironmentSample {
  Vec3 wi{0.0f};
  Color radiance{0.0f};
  float pdf = 0.0f;
  bool valid = false;
};

// A map is sampled by its luminance (pdf(u, v) / (2 pi^2 sin theta)); a constant sky,
// which has nothing to importance-sample, cosine-weighted about the shading normal n,
// so a Lambertian surface gets its exact irradiance from every sample (pdf cos / pi).
EnvironmentSample sampleEnvironment(const Light& light, const Vec3& n, float u1, float u2);
// The density sampleEnvironment draws wi with at a point of shading normal n.
float environmentPdf(const Light& light, const Vec3& n, const Vec3& wi);

// Without a normal (photons, generic light sampling): the map by luminance, a constant
// sky uniformly over the sphere (pdf 1 / (4 pi)).
EnvironmentSample sampleEnvironmentSphere(const Light& light, float u1, float u2);

// The flux entering the scene's bounding sphere: pi R^2 x the integral of L over the
// sphere of directions (each direction a parallel beam through the disc of radius R).
Color environmentPower(const Light& light, const SceneSphere& bounds);

// A photon from the environment: a direction drawn as sampleEnvironmentSphere (u1, u2),
// travelling from a uniform point (u3, u4) of the disc of radius R facing it, placed
// outside the bounding sphere. Its weight L(w) / (pdf(w) x integral of L), per channel,
// averages 1, so power / count x weight keeps the light's flux.
PhotonRay environmentPhoton(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3,
                            float u4);

}  // namespace penumbra
