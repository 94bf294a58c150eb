// The validation layer over nlohmann::json: a JsonNode knows its JSON path and
// turns every type, range and unknown-key problem into a one-line InputError.
#pragma once
#include "core/math.h"
#include "io/load_limits.h"
#include <nlohmann/json.hpp>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

namespace penumbra {

// What every node needs to phrase an error and resolve a relative path.
class LoadCache;

struct LoadContext {
  std::string file;                    // the scene file as given, for messages
  std::filesystem::path baseDir;       // relative paths in the scene resolve here
  std::vector<std::string> overridden;  // JSON paths set by --set, to say so in errors
  LoadLimits limits;                    // what the scene's files may cost (io/load_limits.h)
  LoadCache* cache = nullptr;           // files shared with earlier loads (io/load_cache.h)
};

// An inclusive or exclusive numeric interval; the defaults accept any finite number.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool loOpen = false;
  bool hiOpen = false;
  static Range atLeast(double lo) { return {lo, std::numeric_limits<double>::infinity()}; }
  static Range above(double lo) { return {lo, std::numeric_limits<double>::infinity(), true}; }
  static Range between(double lo, double hi) { return {lo, hi}; }
};

// A non-owning view of one JSON value plus where it sits ("objects[3].radius").
class JsonNode {
 public:
  JsonNode(const nlohmann::json& value, std::string path, const LoadContext& context)
      : value_(&value), path_(std::move(path)), context_(&context) {}

  const nlohmann::json& value() const { return *value_; }
  const std::string& path() const { return path_; }
  const LoadContext& context() const { return *context_; }

  // Throws InputError "FILE: PATH: problem", flattened to one line.
  [[noreturn]] void fail(const std::string& problem) const;

  // Objects. allowKeys() also checks this is an object, and rejects any key not
  // listed, suggesting the closest listed one.
  void requireObject() const;
  void allowKeys(std::initializer_list<const char*> keys) const;
  bool has(const char* key) const;
  JsonNode child(const std::string& key) const;      // fails if the key is missing
  JsonNode required(const char* key, const std::string& what) const;  // same, says what needs it
  std::vector<std::string> keys() const;

  // Arrays.
  size_t arraySize() const;  // fails unless an array
  JsonNode element(size_t index) const;

  // Scalars; each fails with the expected type and the value it got.
  double asNumber(const Range& range = {}) const;  // finite, in range
  float asFloat(const Range& range = {}) const;    // also within float range
  int64_t asInt(int64_t lo, int64_t hi) const;     // integral (5e6 counts), in [lo, hi]
  uint64_t asUint(uint64_t lo, uint64_t hi) const;
  bool asBool() const;
  std::string asString() const;
  Vec3 asVec3() const;                             // [x, y, z], finite
  Color asColor() const;                           // [r, g, b] or one grey number, >= 0
  float asColorComponent() const;                  // >= 0 and <= kMaxColorComponent
  size_t asEnum(const std::vector<std::string>& names) const;  // index into names

  // Optional keys: the default when absent, else the checked value.
  float floatOr(const char* key, float fallback, const Range& range = {}) const;
  int intOr(const char* key, int fallback, int lo, int hi) const;
  uint64_t uintOr(const char* key, uint64_t fallback, uint64_t lo, uint64_t hi) const;
  bool boolOr(const char* key, bool fallback) const;
  Vec3 vec3Or(const char* key, const Vec3& fallback) const;
  Color colorOr(const char* key, const Color& fallback) const;
  size_t enumOr(const char* key, size_t fallback, const std::vector<std::string>& names) const;

 private:
  const nlohmann::json* value_;
  std::string path_;
  const LoadContext* context_;
};

// A short, single-line description of a JSON value for messages: 1.5, "abc",
// null, an array, an object. Never dumps a whole subtree.
std::string describeJson(const nlohmann::json& value);

// How a key appears in a JSON path: red, or ["odd key"] when it is not a plain word.
std::string pathKey(const std::string& key);

// Throws InputError "FILE: problem" / "FILE: PATH: problem" with control
// characters replaced so the message stays on one line.
[[noreturn]] void throwInputError(const std::string& message);

}  // namespace penumbra
