// The single-precision limits of the scene format: bounds on positions, sphere
// radii, colours, light radiance and power that keep every float the renderer
// derives from them finite (docs/scene-format.md, "Limits", says why each).
#pragma once
#include "core/scene.h"
#include <vector>

namespace penumbra {

class JsonNode;

// Largest |coordinate| of any point: camera, lights, sphere extents and mesh
// vertices after their transform. Embree asserts on ray origins beyond ~1.8e18;
// 1e15 leaves three orders of magnitude for photon discs and ray offsets outside
// the geometry, and keeps squared distances (<= ~1.2e31) far inside float range.
inline constexpr double kMaxCoordinate = 1e15;

// Longest triangle edge. Embree's single-precision triangle test starts to miss hits
// on triangles between 3e13 and 4e13 long (a floor quad seen from above: all camera
// rays hit at 2.8e13, 1 in 16 at 4e13, wherever the triangle lies within
// kMaxCoordinate); 1e13 keeps a margin of three.
inline constexpr double kMaxTriangleEdge = 1e13;

// Largest |texture coordinate| of a mesh vertex (OBJ vt, glTF TEXCOORD_0). A texture
// repeats every unit, so larger values add nothing but lost precision (a float at 1e6
// resolves 1/16 of a repeat); far beyond, the lookup's wrap and filter arithmetic
// overflow and the surface turns black.
inline constexpr double kMaxTexCoord = 1e6;

// Largest colour component, light radiance component, light power and total
// power of all lights: eight orders of magnitude below FLT_MAX (3.4e38), the
// headroom that photon budgets, 4 pi / pi A factors and sums over samples and
// pixels (spp x light_samples <= 4.2e6) need so none of them overflows.
inline constexpr double kMaxColorComponent = 1e30;
inline constexpr float kMaxRadiance = 1e30f;
inline constexpr float kMaxPower = 1e30f;

// Smallest sphere radius relative to its centre's largest coordinate m. The surface
// point c + r n is rounded to the float grid at m (one ulp <= 2^-23 m); r >= 2^-18 m
// keeps >= 32 ulps between surface and centre. (Hits are safe below it too: normals
// are taken in double from o + t d. The bound is about representing the sphere.)
inline constexpr double kMinRadiusRatio = 1.0 / 262144.0;

// Smallest step between an orthographic film's pixels (ortho_height / height)
// relative to the camera position's largest coordinate m. The rays start at
// position + offsets rounded to the float grid at m (one step <= 2^-23 m): a pixel
// of >= 2^-21 m keeps neighbours >= 4 steps apart; finer, whole rows of pixels start
// on one point and one surface point fills the film.
inline constexpr double kMinPixelStepRatio = 1.0 / 2097152.0;

// Index of refraction. Real media are 1..4; ratios below 1 (a bubble in glass)
// are valid. Fresnel and Snell work with ior^2 and 1 - ior^2 sin^2: [0.01, 100]
// keeps those well inside float and every refraction direction finite.
inline constexpr double kMinIor = 0.01;
inline constexpr double kMaxIor = 100.0;

// A vec3 that names a point: finite floats with |coordinate| <= kMaxCoordinate.
Vec3 readPosition(const JsonNode& node);

// Fails at `node` unless every point is within kMaxCoordinate; `what` names them
// in the message ("transformed positions").
void checkPositions(const JsonNode& node, const std::vector<Vec3>& points, const char* what);

// Fails at `radius` when r is below kMinRadiusRatio x the largest coordinate of
// `center`: the points c + r n of a sphere's (or a disc's) rim are rounded to the float
// grid at |c|, and a few dozen ulps of it collapse the shape onto its centre.
void checkRadius(const JsonNode& radius, float r, const Vec3& center);

// The checks that need the whole scene, computed in float as the renderer does:
// every sphere's radius against the scene's extent, each light's radiance and
// power, the sum of all lights' power, and every triangle's edges. Runs after
// addEmitters.
void checkSceneNumbers(const JsonNode& root, const Scene& scene);

}  // namespace penumbra
