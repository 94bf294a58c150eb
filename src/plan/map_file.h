// Photon map files (--map-dir): one photon stage's emission stored under its key, so
// another process loads it instead of emitting. Written from the emission's own blocks
// and read straight into the arrays the maps are built from (docs/photon-maps.md).
#pragma once
#include "plan/photon_stage.h"
#include <cstdint>
#include <functional>
#include <string>

namespace penumbra {

// What a file must match to be used, as text: every field of the stage's key, each
// map's light split, and what else decides the photons (the loader's defaults, the
// program's version, the photon records' layout).
std::string mapFileKey(const PhotonStageKey& key, const PhotonNeeds& needs, bool loadDefaults);

// DIR/<16 hex digits of the key text's FNV-1a hash>.pmap
std::string mapFilePath(const std::string& dir, const std::string& keyText);

// Writes `emission` (before a build consumed its photons) to `path` atomically; returns
// the file's bytes. Throws InputError when it cannot be written.
uint64_t writeMapFile(const std::string& path, const std::string& keyText, const Emission& emission);

// Reads `path` into `out` (null: checks it without keeping the photons). Returns ""
// when the file is there and sound for `keyText`, else why it is not used: "missing",
// or a problem (damaged, truncated, another key's, another format) that one line names.
std::string readMapFile(const std::string& path, const std::string& keyText, Emission* out, uint64_t* bytes = nullptr);
inline constexpr const char* kMapFileMissing = "missing";

// What loadOrEmit did: loaded the file, or emitted and wrote it (`note` says why a
// file that was there was not used), in how many seconds of reading or writing.
struct MapFileOutcome {
  bool loaded = false, written = false;
  uint64_t bytes = 0;
  double seconds = 0.0;
  std::string note;
};

// The emission stored under `keyText` in `dir` when its file is sound, else `emit()`'s,
// written there before anything consumes it. `keep` false: a sound file is only
// checked, and an empty emission returned.
Emission loadOrEmit(const std::string& dir, const std::string& keyText, const std::function<Emission()>& emit,
                    MapFileOutcome& outcome, bool keep = true);

}  // namespace penumbra
