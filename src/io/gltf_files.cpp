// glTF external files: URI confinement to the model's folder and a file system for
// tinygltf that stats before reading and reads no more than the model declared.
#include "io/gltf_files.h"

#include "io/gltf_checks.h"

#include <filesystem>
#include <fstream>

namespace penumbra {

namespace fs = std::filesystem;

namespace {

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// As tinygltf's own decoding ('+' as a space too), so the file we check is the
// file it asks for; a malformed escape or a NUL is refused rather than guessed.
bool decodeUri(const std::string& uri, std::string& out) {
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      out += ' ';
    } else if (uri[i] == '%') {
      if (i + 2 >= uri.size() || hexDigit(uri[i + 1]) < 0 || hexDigit(uri[i + 2]) < 0) return false;
      const char c = static_cast<char>(hexDigit(uri[i + 1]) * 16 + hexDigit(uri[i + 2]));
      if (c == '\0') return false;
      out += c;
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return !out.empty();
}

// `inner` is `outer` or lies below it (both normal, absolute).
bool under(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (o->empty() && std::next(o) == outer.end()) break;  // a trailing separator
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

}  // namespace

std::string resolveGltfUri(const std::string& folder, const std::string& uri, const std::string& where,
                           const std::string& path) {
  std::string decoded;
  if (!decodeUri(uri, decoded)) gltfFail(path, where, "\"" + uri + "\" is not a valid URI");
  const fs::path relative(decoded);
  if (relative.is_absolute() || decoded.find(':') != std::string::npos) {
    gltfFail(path, where, "\"" + uri + "\" is not a path relative to the model's folder (penumbra reads no other files)");
  }
  const fs::path base = fs::path(folder).lexically_normal();
  const fs::path file = (base / relative).lexically_normal();
  // Lexically, then through symlinks: a link inside the folder may point out of it.
  std::error_code ec, baseEc;
  const fs::path real = fs::weakly_canonical(file, ec), realBase = fs::weakly_canonical(base, baseEc);
  if (!under(file, base) || ec || baseEc || !under(real, realBase)) {
    gltfFail(path, where, "\"" + uri + "\" lies outside the model's folder (penumbra reads no other files)");
  }
  return file.string();
}

void GltfFiles::allow(const std::string& file, uint64_t readBytes, uint64_t maxBytes) {
  allowed_[fs::path(file).lexically_normal().string()] = Allowed{readBytes, maxBytes};
}

const GltfFiles::Allowed* GltfFiles::find(const std::string& file) const {
  auto it = allowed_.find(fs::path(file).lexically_normal().string());
  return it == allowed_.end() ? nullptr : &it->second;
}

tinygltf::FsCallbacks GltfFiles::callbacks() {
  return tinygltf::FsCallbacks{&GltfFiles::exists, &GltfFiles::expand, &GltfFiles::readWhole, &GltfFiles::writeWhole, this};
}

bool GltfFiles::exists(const std::string& file, void* self) {
  std::error_code ec;
  return static_cast<GltfFiles*>(self)->find(file) != nullptr && fs::is_regular_file(file, ec);
}

std::string GltfFiles::expand(const std::string& file, void*) { return file; }  // no ~ or $VAR

bool GltfFiles::readWhole(std::vector<unsigned char>* out, std::string* err, const std::string& file, void* selfPtr) {
  GltfFiles& self = *static_cast<GltfFiles*>(selfPtr);
  auto refuse = [&](const std::string& why) {
    if (self.problem_.empty()) self.problem_ = file + ": " + why;
    if (err) *err += file + ": " + why + "\n";
    return false;
  };
  const Allowed* allowed = self.find(file);
  if (!allowed) return refuse("not a file this model names");
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return refuse("not a regular file");
  const uint64_t size = fs::file_size(file, ec);
  if (ec) return refuse("cannot read its size");
  const uint64_t want = allowed->readBytes > 0 ? allowed->readBytes : size;
  if (allowed->readBytes > 0 && size < want) {
    return refuse("holds " + std::to_string(size) + " bytes, fewer than the " + std::to_string(want) + " its buffer declares");
  }
  if (size > allowed->maxBytes) {
    return refuse("is " + std::to_string(size) + " bytes, more than the " + std::to_string(allowed->maxBytes) + " allowed for it");
  }
  std::ifstream in(file, std::ios::binary);
  out->resize(want);
  if (!in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(want))) return refuse("cannot read it");
  self.read_.push_back(file);
  return true;
}

bool GltfFiles::writeWhole(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "penumbra does not write glTF files\n";
  return false;
}

}  // namespace penumbra
