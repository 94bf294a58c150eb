// What renders of one scene can share, decided from the scene document after
// its overrides: equal geometry keys share the loaded geometry, the Embree scene
// and the textures; equal photon keys share one photon emission, whatever their
// camera, spp, depth, k or gate (a smaller photon budget is a prefix of a larger).
#pragma once
#include <string>
#include <tuple>
#include <vector>

namespace penumbra {

struct ReuseKeys {
  std::string geometry;  // objects, materials, lights, media, render.model and render.medium
  std::string photons;   // everything but the camera and the gather/render-only settings
  bool operator==(const ReuseKeys& o) const { return geometry == o.geometry && photons == o.photons; }
  bool operator<(const ReuseKeys& o) const { return std::tie(geometry, photons) < std::tie(o.geometry, o.photons); }
};

// Reads `scenePath`, applies `overrides` and derives both keys (canonical JSON
// text). Throws InputError as loadScene would for unreadable or malformed files.
ReuseKeys reuseKeys(const std::string& scenePath, const std::vector<std::string>& overrides);

// What the files a scene read are now: each one's path, size and modification time.
// Part of both keys, so an edited MTL, buffer or texture never shares a stale piece;
// sweep resume compares it too.
std::string inputsStamp(const std::vector<std::string>& inputs);

// The settings left out of the photon key: they change how photons are gathered
// or which are read, never which are emitted.
const std::vector<std::string>& gatherOnlyPhotonKeys();

}  // namespace penumbra
