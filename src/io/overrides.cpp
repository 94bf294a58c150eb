// Parses and applies --set KEY=VALUE overrides to a scene document.
#include "io/overrides.h"

#include "io/json_parse.h"
#include "io/json_reader.h"

#include <cctype>

namespace penumbra {

using nlohmann::json;

namespace {

// Well-formed UTF-8 (no overlongs, surrogates or code points past U+10FFFF): the
// stats and image metadata are JSON and UTF-8, so a bad byte would fail the write
// after the render. Returns the offset of the first bad byte, or npos.
size_t firstBadUtf8(const std::string& s) {
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  for (size_t i = 0; i < s.size();) {
    const unsigned c = p[i];
    const size_t n = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : 4;
    if (n == 4 || i + n >= s.size()) return i;  // a stray continuation byte, or cut short
    unsigned cp = n == 0 ? c : n == 1 ? (c & 0x1F) : n == 2 ? (c & 0x0F) : (c & 0x07);
    for (size_t k = 1; k <= n; ++k) {
      if ((p[i + k] & 0xC0) != 0x80) return i;
      cp = (cp << 6) | (p[i + k] & 0x3F);
    }
    const unsigned minimum[] = {0, 0x80, 0x800, 0x10000};
    if (cp < minimum[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return i;
    i += n + 1;
  }
  return std::string::npos;
}


// One step of an override path: an object key or an array index.
struct Step {
  std::string key;
  size_t index = 0;
  bool isIndex = false;
};

bool isKeyChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
}

[[noreturn]] void overrideError(const std::string& text, const std::string& problem) {
  std::string shown = text.size() > 80 ? text.substr(0, 80) + "..." : text;
  throwInputError("--set \"" + shown + "\": " + problem);
}

// "objects[2].radius" -> key objects, index 2, key radius.
std::vector<Step> parsePath(const std::string& path, const std::string& text) {
  std::vector<Step> steps;
  size_t i = 0;
  bool expectKey = true;
  while (i < path.size()) {
    if (expectKey) {
      size_t start = i;
      while (i < path.size() && isKeyChar(path[i])) ++i;
      if (i == start) overrideError(text, "expected a key name at position " + std::to_string(start + 1));
      steps.push_back({path.substr(start, i - start)});
      expectKey = false;
    } else if (path[i] == '.') {
      ++i;
      expectKey = true;
      if (i == path.size()) overrideError(text, "key path ends with '.'");
    } else if (path[i] == '[') {
      size_t start = ++i;
      while (i < path.size() && std::isdigit(static_cast<unsigned char>(path[i]))) ++i;
      if (i == start || i >= path.size() || path[i] != ']') {
        overrideError(text, "expected [INDEX] with a non-negative integer");
      }
      if (i - start > 9) overrideError(text, "array index is too large");
      Step s;
      s.isIndex = true;
      s.index = std::stoul(path.substr(start, i - start));
      steps.push_back(s);
      ++i;
    } else {
      overrideError(text, std::string("unexpected character '") + path[i] + "' in key path");
    }
  }
  return steps;
}

std::string canonical(const std::vector<Step>& steps, size_t count) {
  std::string out;
  for (size_t i = 0; i < count; ++i) {
    if (steps[i].isIndex) {
      out += "[" + std::to_string(steps[i].index) + "]";
    } else {
      out += (out.empty() ? "" : ".") + steps[i].key;
    }
  }
  return out;
}

std::string applyOne(json& document, const std::string& text) {
  size_t eq = text.find('=');
  if (eq == std::string::npos) overrideError(text, "expected KEY=VALUE");
  std::string path = text.substr(0, eq);
  std::string valueText = text.substr(eq + 1);
  if (path.empty()) overrideError(text, "empty key before '='");
  std::vector<Step> steps = parsePath(path, text);

  // Plain words are strings: --set photons.estimator=density needs no quoting.
  json value;
  std::string duplicate;
  if (!parseJsonValue(valueText, value, duplicate)) value = valueText;
  if (!duplicate.empty()) overrideError(text, duplicate + ": duplicate key in the value");

  if (!document.is_object()) overrideError(text, "the scene is not a JSON object");
  json* node = &document;
  for (size_t i = 0; i < steps.size(); ++i) {
    const Step& s = steps[i];
    std::string where = canonical(steps, i);
    if (s.isIndex) {
      if (!node->is_array()) {
        overrideError(text, (where.empty() ? std::string("the root") : where) + " is not an array");
      }
      if (s.index >= node->size()) {
        overrideError(text, "index " + std::to_string(s.index) + " is out of range (" + where +
                                " has " + std::to_string(node->size()) + " elements)");
      }
      node = &(*node)[s.index];
    } else {
      if (node->is_null()) *node = json::object();
      if (!node->is_object()) overrideError(text, where + " is not an object");
      node = &(*node)[s.key];
    }
    if (i + 1 < steps.size() && node->is_null() && !steps[i + 1].isIndex) *node = json::object();
  }
  *node = std::move(value);
  return canonical(steps, steps.size());
}

}  // namespace

std::vector<std::string> applyOverrides(json& document, const std::vector<std::string>& overrides) {
  for (const std::string& o : overrides) {
    const size_t bad = firstBadUtf8(o);
    if (bad != std::string::npos) {
      throwInputError("--set: argument is not valid UTF-8 (byte " + std::to_string(bad) + " of '" +
                      o.substr(0, bad) + "...')");
    }
  }
  std::vector<std::string> paths;
  for (const std::string& text : overrides) paths.push_back(applyOne(document, text));
  return paths;
}

}  // namespace penumbra
