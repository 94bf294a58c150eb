// Readers for the sections of a scene document, called in order by
// scene_loader.cpp; each validates its part and fills the Scene.
#pragma once
#include "core/scene.h"
#include "io/json_reader.h"

namespace penumbra {

// `modelAspect` > 0: the model file's aspect ratio, which a new width alone keeps.
void readCamera(const JsonNode& camera, Camera& out, double modelAspect = 0.0);
void readLights(const JsonNode& lights, std::vector<Light>& out);
void readRender(const JsonNode& render, RenderSettings& out);
void readPhotons(const JsonNode& photons, PhotonSettings& out);

// "materials" (and the textures they reference). Without a "materials" key the
// scene gets one implicit material named "default".
void readMaterials(const JsonNode& root, Scene& scene);

// "objects": spheres into Scene::spheres, everything else into Scene::meshes.
// Needs the materials read first.
void readObjects(const JsonNode& root, Scene& scene);

// Area lights' surfaces as scene objects (a quad mesh or a sphere with an emitting
// black material); after readObjects, so object indices stay as written.
void addEmitters(Scene& scene);

// Every material with an emission (JSON "emission", MTL Ke, glTF emissive) that no
// light owns yet becomes one mesh light over the triangles of all meshes using it
// (core/lights/emissive_mesh.h); its surface then only glows, like a quad light's. After
// addEmitters. Throws InputError past 65535 lights in all.
void addMeshEmitters(Scene& scene);

// "environment": a constant sky or an HDR lat-long map, appended as the last light
// (core/lights/environment_map.h); after addMeshEmitters, so every other light keeps its index.
void readEnvironment(const JsonNode& environment, Scene& scene);

// A path from the scene file made absolute against the scene's folder.
std::string resolvePath(const JsonNode& where, const std::string& file);

}  // namespace penumbra
