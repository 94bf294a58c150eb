// The files a glTF model may pull in: URIs resolved (percent-decoded) inside the
// model's folder only, each external file checked by stat before any byte is read,
// handed to tinygltf as its file system so it can open nothing else.
#pragma once
#include <tiny_gltf.h>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace penumbra {

// The path an external (not data:) URI names, inside `folder` (absolute, the
// model's): percent-decoded as tinygltf decodes it, lexically and through symlinks
// still under `folder`. Throws ModelError naming `where` (its JSON path) otherwise.
std::string resolveGltfUri(const std::string& folder, const std::string& uri, const std::string& where,
                           const std::string& path);

// The external files tinygltf may read: only those allowed, and each only as far
// as allowed. Lives as long as the tinygltf loader that uses its callbacks.
class GltfFiles {
 public:
  // `file` (from resolveGltfUri) may be read: its first `readBytes` bytes (0 = all
  // of it, then it must hold at most `maxBytes`).
  void allow(const std::string& file, uint64_t readBytes, uint64_t maxBytes);
  tinygltf::FsCallbacks callbacks();
  const std::vector<std::string>& read() const { return read_; }  // files read, in order
  const std::string& problem() const { return problem_; }         // why a read was refused

 private:
  struct Allowed {
    uint64_t readBytes = 0, maxBytes = 0;
  };
  const Allowed* find(const std::string& file) const;
  static bool exists(const std::string& file, void* self);
  static std::string expand(const std::string& file, void*);
  static bool readWhole(std::vector<unsigned char>* out, std::string* err, const std::string& file, void* self);
  static bool writeWhole(std::string* err, const std::string&, const std::vector<unsigned char>&, void*);

  std::map<std::string, Allowed> allowed_;
  std::vector<std::string> read_;
  std::string problem_;
};

}  // namespace penumbra
