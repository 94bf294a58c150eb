// Alpha masks at load: an image's alpha channel decoded once into the plain bytes
// the geometry layer's cut-out filter reads (core/alpha_mask.h).
#pragma once
#include "core/scene.h"
#include <string>

namespace penumbra {

class JsonNode;

// Scene::alphaMasks' index for the alpha of image `path` (shared when already
// there): its alpha channel, or with `greyIsAlpha` its first channel when it has
// none (a grey mask). -1 when the image has no alpha and !greyIsAlpha: nothing to
// cut out. `sampling` wraps and filters it (a model's sampler; repeat by default).
// Fails at `where` when the image cannot be decoded.
int addAlphaMask(const JsonNode& where, const std::string& path, Scene& scene, bool greyIsAlpha,
                 const TextureSampling& sampling = {});

}  // namespace penumbra
