// Which medium every part of a scene with media sits in: each object's MediumInterface,
// the camera's medium and each light's (docs/scene-format.md, "Media").
#pragma once
#include "core/scene.h"

namespace penumbra {

// Fills Sphere::media and TriangleMesh::media (surfaces and boundaries), cameraMedium
// and Light::medium. A closed object separates its inside (its medium, or vacuum) from
// the inside of the smallest closed object around it (else sceneMedium); open meshes
// separate nothing. Does nothing for a scene without media.
void bindMedia(Scene& scene);

}  // namespace penumbra
