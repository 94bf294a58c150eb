// The scene as plain data: what io fills in and every stage reads. No behaviour
// lives here; quads, boxes, OBJ files and teapots all arrive as TriangleMesh.
#pragma once
#include "core/alpha_mask.h"
#include "core/light_types.h"
#include "core/media/medium.h"
#include "core/shading_model.h"
#include "core/math.h"
#include "core/shared_list.h"
#include "core/texture_sampling.h"
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace penumbra {

struct Camera {
  Vec3 position{0.0f, 0.0f, 5.0f};
  Vec3 lookAt{0.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float fovY = 45.0f;  // vertical field of view, degrees
  // > 0: an orthographic camera whose view is this tall in scene units (fovY unused);
  // 0: the pinhole.
  float orthoHeight = 0.0f;
  int width = 640;
  int height = 480;
  int spp = 1;  // samples per pixel and pass (one pass at spp 1: the pixel centre)
  // The thin lens (core/thin_lens.h): an aperture radius in scene units or an f-number
  // (0: not given; at most one of the two), and the focus distance (0: to look_at).
  // No aperture is the pinhole.
  float apertureRadius = 0.0f;
  float fNumber = 0.0f;
  float focusDistance = 0.0f;
};

struct EnvironmentMap;  // core/lights/environment_map.h
struct MeshEmission;    // core/emission_map.h

struct Light {
  LightType type{};  // the first of core/light_types.h's list: a point light
  // Its shape; each type's header (core/lights/) says which fields it reads.
  Vec3 position{0.0f};              // point, spot; quad corner; sphere, disk centre
  Vec3 direction{0.0f, -1.0f, 0.0f};  // directional, spot: the way the light travels; disk: its normal (unit)
  Vec3 edge1{0.0f}, edge2{0.0f};    // quad: it emits on the side of edge1 x edge2
  float radius = 0.0f;              // sphere, disk
  Color color{1.0f};
  // Point, spot: radiant intensity (W/sr); directional: irradiance (W/m^2); an area
  // light: emitted radiance (W/(sr m^2)), uniform over the surface; environment: its
  // radiance, times the map's texel when there is one.
  float intensity = 1.0f;
  // Mesh: the emitting triangles in world space, 3 corners each, emitting on the side
  // of (b - a) x (c - a); their cumulative areas (sampling by area, back() = total);
  // a bound on the rounding of a sampled point; the emitting material's index.
  std::vector<Vec3> triangles;
  std::vector<float> areaCdf;
  float pointError = 0.0f;
  int material = -1;
  // Mesh: emits on both sides of each triangle (glTF's doubleSided); and its emissive
  // texture with the tables that draw triangles by luminance (null: uniform radiance).
  bool twoSided = false;
  std::shared_ptr<const MeshEmission> emission;
  // Spot: full intensity within `spotCosInner` of `direction`, falling to 0 at
  // `spotCosOuter` (glTF's cone angles, as cosines). setSpotCone sets them and the type.
  float spotCosInner = -1.0f, spotCosOuter = -1.0f;
  bool isSpot() const { return spotCosOuter > -1.0f; }
  // Environment: the lat-long map and its sampling tables, shared by the copies of a
  // scene a sweep or batch makes (null: a constant sky).
  std::shared_ptr<const EnvironmentMap> environment;
  // The medium around the light, where its photons start (kNoMedium without media).
  int medium = kNoMedium;
  Color radiance() const { return color * intensity; }
};

enum class TextureBlend { Multiply, Add };

// Where a hit's uv lands in a texture: scaled, then rotated (radians, counter-
// clockwise in uv), then offset, as glTF's KHR_texture_transform orders them.
struct UvTransform {
  Vec2 scale{1.0f};
  Vec2 offset{0.0f};
  float rotation = 0.0f;
  UvTransform() = default;
  UvTransform(Vec2 s) : scale(s) {}  // NOLINT: a plain repeat converts implicitly
  UvTransform(Vec2 s, Vec2 o, float r) : scale(s), offset(o), rotation(r) {}
  bool scalesOnly() const { return offset == Vec2(0.0f) && rotation == 0.0f; }
  Vec2 apply(Vec2 uv) const {
    const Vec2 s = uv * scale;
    const float c = std::cos(rotation), n = std::sin(rotation);
    return Vec2(c * s.x + n * s.y, -n * s.x + c * s.y) + offset;
  }
};

struct Material {
  std::string name;
  Color ambient{0.1f};
  Color diffuse{0.8f};
  Color specular{0.0f};
  float shininess = 32.0f;
  float kr = 0.0f;  // mirror reflection weight (opaque materials)
  bool transparent = false;  // transparent: Fresnel decides kr, kt = 1 - kr
  float ior = 1.5f;
  Color tint{1.0f};  // transmission filter colour
  float pR = 0.0f;   // photon Russian roulette: reflect with pR,
  float pT = 0.0f;   // transmit with pT, absorb otherwise
  int texture = -1;  // index into Scene::textures, -1 = none
  Vec2 uvScale{1.0f};  // texture repeats in (u, v); v wraps too when it is not 1
  Vec2 uvOffset{0.0f};    // glTF's KHR_texture_transform, with uvScale
  float uvRotation = 0.0f;
  UvTransform uvTransform() const { return {uvScale, uvOffset, uvRotation}; }
  TextureBlend textureBlend = TextureBlend::Multiply;
  // An area light's own surface: the radiance camera and specular rays see on its
  // emitting side (the light's sampling accounts for it everywhere else).
  Color emission{0.0f};
  bool twoSidedEmission = false;  // a sphere emits all round, a quad or disk on one side
  int light = -1;                 // the area light this surface belongs to, -1 = none
  int emissionTexture = -1;       // times emission (colour, sRGB-decoded), -1 = none
  // glTF's model adds emission to the surface's BSDF; a scene file's emitting material
  // is a light's surface and only glows, as a quad light's does.
  bool emitterShades = false;
  // glTF's metallic-roughness model (the physical model's MetalRough BSDF, the classic
  // model's Phong terms); `diffuse` is its base colour and `texture` the base map.
  bool metalRough = false;
  float metallic = 0.0f;
  float roughness = 1.0f;          // perceptual, as glTF gives it: GGX alpha = roughness^2
  int metalRoughTexture = -1;      // B scales metallic, G scales roughness (linear data)
  // A tangent-space normal map (linear data, 2 x texel - 1 = (T, B, N) components) and
  // its glTF `scale` on the T and B components; meshes using it carry tangents.
  int normalTexture = -1;
  float normalScale = 1.0f;
  // Cut-outs (glTF alphaMode): coverage = alpha x the mask's texel at uv (1 without a
  // mask) x the mesh's vertex alpha (1 without colours). Mask keeps a hit where
  // coverage >= alphaCutoff; Blend keeps it with probability coverage. Cut out for
  // every ray, photons included (the Embree filter).
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alpha = 1.0f;         // the base colour factor's alpha
  float alphaCutoff = 0.5f;
  int alphaMask = -1;         // index into Scene::alphaMasks, -1 = none
};

struct Sphere {
  Sphere() = default;
  // The shape and material, as `{centre, radius, material}` read everywhere.
  Sphere(const Vec3& c, float r, int m = 0, const MediumInterface& mi = {})
      : center(c), radius(r), material(m), media(mi) {}
  Vec3 center{0.0f};
  float radius = 1.0f;
  int material = 0;
  MediumInterface media;  // what its surface separates (scenes with media)
};

struct TriangleMesh {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // per vertex, empty = flat shading
  std::vector<Vec2> uvs;      // per vertex, empty = spherical mapping
  // Per vertex, only for a normal-mapped material (else empty): xyz the unit tangent
  // along +u, w = +-1 with the bitangent cross(n, t) x w pointing up the image (-v).
  std::vector<glm::vec4> tangents;
  // Per vertex, only when the file gives colours that are not all white (else empty):
  // linear RGBA in [0, 1] (glTF's COLOR_0, OBJ's `v x y z r g b`). RGB multiplies the
  // base colour, A the alpha a cut-out material tests.
  std::vector<glm::vec4> colors;
  std::vector<std::array<uint32_t, 3>> triangles;
  int material = 0;
  MediumInterface media;  // what its surface separates (scenes with media)
};

// Embree reads each vertex with a 16-byte load, 4 bytes past the last one's end. The
// tracer hands a mesh's positions to Embree without copying them only when their
// storage reaches that far (capacity above size): loaders leave it so (padVertices).
inline bool hasVertexPadding(const std::vector<Vec3>& positions) {
  return positions.capacity() > positions.size();
}
inline void padVertices(std::vector<Vec3>& positions) {
  if (positions.capacity() == positions.size()) positions.reserve(positions.size() + 1);
  positions.push_back(Vec3(0.0f));  // the padding's bytes defined, then left outside the size
  positions.pop_back();
}

struct Texture {
  std::string path;  // absolute, resolved against the scene file's folder
  bool data = false;  // values, not colours: never decoded from sRGB (metallic-roughness)
  // A model's sampler (glTF); none: the scene file's rule (u wraps, v clamps unless
  // the material repeats the texture, trace/texture_lookup.h).
  std::optional<TextureSampling> sampler;
  bool operator==(const Texture& o) const { return path == o.path && data == o.data && sampler == o.sampler; }
};

struct RenderSettings {
  ShadingModel model = kDefaultShadingModel;
  int maxDepth = 4;
  Color background{0.0f};  // what rays leaving the scene see when it has no environment
  // What camera rays leaving the scene see when it has one: unset, the environment
  // itself; set (environment.background, the studio's grey), this colour.
  std::optional<Color> environmentBackground;
  Color ambient{1.0f};     // global ambient light, multiplies Material::ambient
  float minWeight = 1e-3f;  // recursion stops when the path weight falls below
  uint64_t seed = 1;
  bool shadows = true;      // false: lights reach every surface facing them
  std::string aov = "beauty";  // default view; the CLI's --aov overrides it
  int lightSamples = 16;       // samples per area light per shading point
  int volumeSamples = 1;       // single-scattering samples per light per medium stretch
  bool packets = true;  // camera rays (and their shadow rays) as Embree packets; same image
  // Camera rays that leave the scene see nothing: colour premultiplied by coverage, and
  // the beauty carries A = coverage (docs/scene-format.md, "Alpha").
  bool transparentBackground = false;
  // Adaptive pixel sampling (core/adaptive_sampling.h): unset, the model's default.
  std::optional<bool> adaptive;
  float adaptiveThreshold = 2.0f;  // a pixel's error over this many times the lighting's takes more samples
  int adaptiveMaxSpp = 16;         // the most camera samples one pixel takes in a pass
};

enum class IndirectEstimator { Classic, Density };
// on: always ask the shadow map; off: every shadow test is a ray; auto: build the
// shadow map only where the cost model says it pays (plan/gate_decision.h).
enum class GateMode { Off, On, Auto };
// exact: every gate vote and estimate gathers its k nearest photons (the definition);
// precomputed: both are computed once per cell of a hash grid and read by one query;
// auto: precomputed where the plan's cost model finds exact gathers would dominate
// the frame (plan/lookup_decision.h), exact otherwise.
enum class PhotonLookup { Exact, Precomputed, Auto };
enum class HemisphereSampling { Uniform, Cosine };

struct PhotonSettings {
  uint64_t shadowPhotons = 5'000'000;
  uint64_t indirectPhotons = 0;  // 0 = no indirect map, the ambient term stays
  int kShadow = 50;
  int kIndirect = 50;
  float maxRadius = 0.0f;  // 0 = unlimited
  IndirectEstimator estimator = IndirectEstimator::Classic;
  HemisphereSampling sampling = HemisphereSampling::Uniform;
  int maxBounces = 16;
  GateMode gateMode = GateMode::Auto;  // photons.gate / --gate
  // Physical model (docs/photon-maps.md, "physical model").
  uint64_t globalPhotons = 200'000;   // emitted per pass; stored after >= 1 diffuse bounce
  uint64_t causticPhotons = 200'000;  // emitted per pass towards specular objects
  int kGlobal = 100;
  int kCaustic = 50;
  int passes = 1;         // progressive passes, each with fresh photons and smaller gathers
  // Gather shrink per pass, r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1): 2/3 makes the mean
  // of the passes' bias and its noise both fall as passes^(-1/3) (Knaus & Zwicker 2011).
  float alpha = 2.0f / 3.0f;
  float radius = 0.0f;    // passes > 1: one first-pass radius for every point; 0 = each point's k nearest
  // Scenes with a medium (docs/photon-maps.md, "volume map"): photons emitted per pass
  // for the volume map; the photons a camera ray's beam gathers at the first pass; a
  // fixed first-pass beam radius (0: from k_volume).
  uint64_t volumePhotons = 200'000;
  int kVolume = 100;
  float volumeRadius = 0.0f;
  PhotonLookup lookup = PhotonLookup::Auto;
  float lookupCell = 1.0f;  // precomputed: cell size in units of the typical gather radius
};

// What loading found missing, added or left unread, for the notes and --stats; no
// render stage reads it, the plan only for a model's default quality bound
// (io/scene_defaults.h, io/gltf_extensions.h, plan/render_budget.h).
struct LoadReport {
  std::vector<std::string> notes;              // one line each, shown as "note: ..."
  std::vector<std::string> ignoredExtensions;  // optional glTF extensions penumbra does not read
  bool noCamera = false, noLight = false;      // a model scene whose files place no camera, give no light
  bool framedCamera = false, defaultSky = false;  // ... and what loading added for them
  std::string modelFile;  // the glTF or OBJ file that is the scene; empty for a JSON scene
  bool qualityGiven = false;  // its settings or overrides set camera.spp or photons.passes
  size_t implicitMaterials = 0;  // Scene::materials loading added that no file names ("default")
};

struct Scene {
  std::string name;
  std::string file;  // the scene file it came from, for messages and metadata
  // Every file loading read, as opened: the scene or model file, a glTF's sidecar JSON,
  // buffers and images, OBJ meshes and their MTLs, textures. Outputs may overwrite
  // none of them; batch's up-to-date check and the reuse keys read them all.
  std::vector<std::string> inputs;
  Camera camera;
  std::vector<Light> lights;
  std::vector<Material> materials;
  std::vector<Sphere> spheres;
  SharedList<TriangleMesh> meshes;  // shared by copies: the heavy part of a scene
  std::vector<Texture> textures;
  SharedList<AlphaMask> alphaMasks;  // decoded at load; the geometry's cut-out filter reads them
  RenderSettings render;
  PhotonSettings photons;
  LoadReport load;
  // Participating media (core/media/medium.h). A medium fills the scene (sceneMedium),
  // or the inside of closed objects (their MediumInterface). A medium's boundary without
  // a material is invisible: it only changes a ray's medium, and lives in the boundary
  // lists, which no surface query sees. cameraMedium: the medium around the camera.
  std::vector<Medium> media;
  int sceneMedium = kNoMedium;
  int cameraMedium = kNoMedium;
  std::vector<Sphere> boundarySpheres;
  SharedList<TriangleMesh> boundaryMeshes;
  bool hasMedia() const { return !media.empty(); }
};

}  // namespace penumbra
