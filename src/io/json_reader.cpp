// JsonNode: typed, range-checked access to scene JSON with path-qualified errors.
#include "io/json_reader.h"

#include "core/error.h"
#include "io/float_checks.h"
#include "io/suggest.h"

#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdio>

namespace penumbra {

using nlohmann::json;

namespace {

// Echoed user text (keys, strings) is cut so one hostile value cannot flood a message.
constexpr size_t kMaxEcho = 60;

std::string truncated(const std::string& s) {
  return s.size() <= kMaxEcho ? s : s.substr(0, kMaxEcho) + "...";
}

std::string formatNumber(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string describeRange(const Range& r) {
  bool hasLo = std::isfinite(r.lo), hasHi = std::isfinite(r.hi);
  std::string lo = (r.loOpen ? "> " : ">= ") + formatNumber(r.lo);
  std::string hi = (r.hiOpen ? "< " : "<= ") + formatNumber(r.hi);
  if (hasLo && hasHi) {
    if (!r.loOpen && !r.hiOpen) return "between " + formatNumber(r.lo) + " and " + formatNumber(r.hi);
    return lo + " and " + hi;
  }
  return hasLo ? lo : hi;
}

// Integer bounds printed exactly (uint64 max would print as 1.84467441e+19).
template <typename T>
std::string integerRange(T lo, T hi) {
  return "between " + std::to_string(lo) + " and " + std::to_string(hi);
}

bool inRange(double v, const Range& r) {
  if (r.loOpen ? !(v > r.lo) : !(v >= r.lo)) return false;
  if (r.hiOpen ? !(v < r.hi) : !(v <= r.hi)) return false;
  return true;
}

// True when `path` is `prefix` itself or lies beneath it.
bool isUnder(const std::string& path, const std::string& prefix) {
  if (path.compare(0, prefix.size(), prefix) != 0) return false;
  return path.size() == prefix.size() || path[prefix.size()] == '.' || path[prefix.size()] == '[';
}

}  // namespace

[[noreturn]] void throwInputError(const std::string& message) {
  std::string line = message;
  for (char& c : line) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  throw InputError(line);
}

std::string describeJson(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case json::value_t::number_integer: return std::to_string(v.get<int64_t>());
    case json::value_t::number_unsigned: return std::to_string(v.get<uint64_t>());
    case json::value_t::number_float: return formatNumber(v.get<double>());
    case json::value_t::string: return "\"" + truncated(v.get<std::string>()) + "\"";
    case json::value_t::array: return "an array of " + std::to_string(v.size());
    case json::value_t::object: return "an object";
    default: return "a binary value";
  }
}

std::string pathKey(const std::string& key) {
  bool plain = !key.empty();
  for (char c : key) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) plain = false;
  }
  return plain ? truncated(key) : "[\"" + truncated(key) + "\"]";
}

void JsonNode::fail(const std::string& problem) const {
  std::string where = path_.empty() ? "(root)" : path_;
  std::string note;
  for (const std::string& p : context_->overridden) {
    if (!path_.empty() && isUnder(path_, p)) note = " (value from --set)";
  }
  throwInputError(context_->file + ": " + where + ": " + problem + note);
}

void JsonNode::requireObject() const {
  if (!value_->is_object()) fail("must be an object, got " + describeJson(*value_));
}

void JsonNode::allowKeys(std::initializer_list<const char*> keys) const {
  requireObject();
  std::vector<std::string> allowed(keys.begin(), keys.end());
  for (const auto& item : value_->items()) {
    bool known = false;
    for (const std::string& k : allowed) known = known || k == item.key();
    if (!known) {
      child(item.key()).fail("unknown key" + didYouMean(item.key(), allowed));
    }
  }
}

bool JsonNode::has(const char* key) const {
  return value_->is_object() && value_->contains(key);
}

JsonNode JsonNode::child(const std::string& key) const {
  requireObject();
  std::string p = pathKey(key);
  std::string childPath = path_.empty() ? p : (p[0] == '[' ? path_ + p : path_ + "." + p);
  auto it = value_->find(key);
  if (it == value_->end()) {
    JsonNode(*value_, childPath, *context_).fail("required key is missing");
  }
  return JsonNode(*it, childPath, *context_);
}

JsonNode JsonNode::required(const char* key, const std::string& what) const {
  requireObject();
  if (!value_->contains(key)) fail("missing required key \"" + std::string(key) + "\"" + what);
  return child(key);
}

std::vector<std::string> JsonNode::keys() const {
  requireObject();
  std::vector<std::string> out;
  for (const auto& item : value_->items()) out.push_back(item.key());
  return out;
}

size_t JsonNode::arraySize() const {
  if (!value_->is_array()) fail("must be an array, got " + describeJson(*value_));
  return value_->size();
}

JsonNode JsonNode::element(size_t index) const {
  arraySize();
  return JsonNode((*value_)[index], path_ + "[" + std::to_string(index) + "]", *context_);
}

double JsonNode::asNumber(const Range& range) const {
  if (!value_->is_number()) fail("must be a number, got " + describeJson(*value_));
  double v = value_->get<double>();
  if (!std::isfinite(v)) fail("must be a finite number, got " + describeJson(*value_));
  if (!inRange(v, range)) fail("must be " + describeRange(range) + ", got " + describeJson(*value_));
  return v;
}

float JsonNode::asFloat(const Range& range) const {
  double v = asNumber(range);
  if (std::fabs(v) > FLT_MAX) fail("is too large for single precision, got " + describeJson(*value_));
  const float f = static_cast<float>(v);
  // The renderer sees f, not v: 1e-50 passes "> 0" in double but is 0 in float.
  // Rounding is monotonic, so comparing against the rounded bounds only refuses
  // values that collapse onto an open bound.
  Range rounded{static_cast<float>(range.lo), static_cast<float>(range.hi), range.loOpen,
                range.hiOpen};
  if (!inRange(f, rounded)) {
    fail("must be " + describeRange(range) + ", got " + describeJson(*value_) + " (" +
         formatNumber(f) + " in single precision)");
  }
  return f;
}

int64_t JsonNode::asInt(int64_t lo, int64_t hi) const {
  if (!value_->is_number()) fail("must be an integer, got " + describeJson(*value_));
  std::string want = "must be " + integerRange(lo, hi) + ", got " + describeJson(*value_);
  if (value_->is_number_integer() && !value_->is_number_unsigned()) {
    int64_t v = value_->get<int64_t>();
    if (v < lo || v > hi) fail(want);
    return v;
  }
  if (value_->is_number_unsigned()) {
    uint64_t v = value_->get<uint64_t>();
    if (hi < 0 || v > static_cast<uint64_t>(hi) || static_cast<int64_t>(v) < lo) fail(want);
    return static_cast<int64_t>(v);
  }
  double d = value_->get<double>();
  if (!std::isfinite(d) || d != std::floor(d)) fail("must be an integer, got " + describeJson(*value_));
  if (d < static_cast<double>(lo) || d > static_cast<double>(hi)) fail(want);
  return static_cast<int64_t>(d);
}

uint64_t JsonNode::asUint(uint64_t lo, uint64_t hi) const {
  if (!value_->is_number()) fail("must be an integer, got " + describeJson(*value_));
  std::string want = "must be " + integerRange(lo, hi) + ", got " + describeJson(*value_);
  if (value_->is_number_unsigned() || value_->is_number_integer()) {
    if (!value_->is_number_unsigned() && value_->get<int64_t>() < 0) fail(want);
    uint64_t v = value_->get<uint64_t>();
    if (v < lo || v > hi) fail(want);
    return v;
  }
  double d = value_->get<double>();
  if (!std::isfinite(d) || d != std::floor(d)) fail("must be an integer, got " + describeJson(*value_));
  // 2^64 itself is the first double past the uint64 range.
  if (d < 0.0 || d >= 18446744073709551616.0) fail(want);
  uint64_t v = static_cast<uint64_t>(d);
  if (v < lo || v > hi) fail(want);
  return v;
}

bool JsonNode::asBool() const {
  if (!value_->is_boolean()) fail("must be true or false, got " + describeJson(*value_));
  return value_->get<bool>();
}

std::string JsonNode::asString() const {
  if (!value_->is_string()) fail("must be a string, got " + describeJson(*value_));
  return value_->get<std::string>();
}

Vec3 JsonNode::asVec3() const {
  if (!value_->is_array() || value_->size() != 3) {
    fail("must be an array of 3 numbers [x, y, z], got " + describeJson(*value_));
  }
  return Vec3(element(0).asFloat(), element(1).asFloat(), element(2).asFloat());
}

// A colour component: >= 0, and bounded like radiance (io/float_checks.h) so
// products of colours and lights stay finite.
float JsonNode::asColorComponent() const {
  const float c = asFloat(Range::atLeast(0.0));
  if (c > kMaxColorComponent) {
    fail("must be <= 1e+30 (single-precision headroom for products and sums), got " +
         describeJson(*value_));
  }
  return c;
}

Color JsonNode::asColor() const {
  if (value_->is_number()) return Color(asColorComponent());
  if (!value_->is_array() || value_->size() != 3) {
    fail("must be a colour [r, g, b] or a grey number, got " + describeJson(*value_));
  }
  return Color(element(0).asColorComponent(), element(1).asColorComponent(),
               element(2).asColorComponent());
}

size_t JsonNode::asEnum(const std::vector<std::string>& names) const {
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "\"" : ", \"") + n + "\"";
  if (!value_->is_string()) fail("must be one of " + list + ", got " + describeJson(*value_));
  std::string s = value_->get<std::string>();
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == s) return i;
  }
  std::string hint = didYouMean(s, names);
  fail("unknown value " + describeJson(*value_) + (hint.empty() ? ", expected one of " + list : hint));
}

float JsonNode::floatOr(const char* key, float fallback, const Range& range) const {
  return has(key) ? child(key).asFloat(range) : fallback;
}

int JsonNode::intOr(const char* key, int fallback, int lo, int hi) const {
  return has(key) ? static_cast<int>(child(key).asInt(lo, hi)) : fallback;
}

uint64_t JsonNode::uintOr(const char* key, uint64_t fallback, uint64_t lo, uint64_t hi) const {
  return has(key) ? child(key).asUint(lo, hi) : fallback;
}

bool JsonNode::boolOr(const char* key, bool fallback) const {
  return has(key) ? child(key).asBool() : fallback;
}

Vec3 JsonNode::vec3Or(const char* key, const Vec3& fallback) const {
  return has(key) ? child(key).asVec3() : fallback;
}

Color JsonNode::colorOr(const char* key, const Color& fallback) const {
  return has(key) ? child(key).asColor() : fallback;
}

size_t JsonNode::enumOr(const char* key, size_t fallback,
                        const std::vector<std::string>& names) const {
  return has(key) ? child(key).asEnum(names) : fallback;
}

}  // namespace penumbra
