// The scene file's participating media: the "media" section, the medium that fills
// the scene (render.medium or environment.medium), and names resolved to indices.
#pragma once
#include "core/scene.h"
#include "io/json_reader.h"

namespace penumbra {

// "media": each medium's coefficients, phase, emission and density grid (a .vdb,
// io/vdb_reader.h) into Scene::media. After readRender: the classic model refuses media.
void readMedia(const JsonNode& root, Scene& scene);

// The index of the medium `name` names (a string node), or a one-line refusal with a
// suggestion.
int resolveMedium(const JsonNode& name, const Scene& scene);

// An object's "medium" (its inside), kNoMedium without the key.
int objectMedium(const JsonNode& object, const Scene& scene);

// The meshes an object with a medium just added (scene.meshes from `first` on): each
// must be closed, else refused naming the object; with no "material" the object is an
// invisible boundary and they move to Scene::boundaryMeshes.
void placeMediumMeshes(const JsonNode& object, int medium, Scene& scene, size_t first);

// render.medium / environment.medium (at most one of them) into Scene::sceneMedium.
void readSceneMedium(const JsonNode& root, Scene& scene);

}  // namespace penumbra
