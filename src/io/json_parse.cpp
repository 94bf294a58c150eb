// JSON text to nlohmann::json with positioned syntax errors and a parse
// callback that refuses duplicate keys, naming their JSON path.
#include "io/json_parse.h"

#include "io/json_reader.h"

#include <fmt/format.h>
#include <algorithm>
#include <unordered_set>
#include <vector>

namespace penumbra {

namespace {

using nlohmann::json;

// Thrown from the parse callback; nlohmann lets them through untouched.
struct DuplicateKey {
  std::string path;
};
struct TooDeep {
  std::string path;
};

// Deeper nesting than any scene needs: the parser keeps a frame per level, and
// nlohmann's values are destroyed recursively.
constexpr int kMaxJsonDepth = 64;

// A parser message quotes the bytes it last read: bytes outside printable ASCII
// are shown as \xNN, so binary input never reaches the terminal raw.
std::string printable(const std::string& s) {
  std::string out;
  for (unsigned char c : s) {
    if (c >= 0x20 && c < 0x7f) out += static_cast<char>(c);
    else out += fmt::format("\\x{:02x}", c);
    if (out.size() > 200) return out + "...";
  }
  return out;
}

// Follows the parser's events to know where it is, and remembers the keys seen
// in every open object. Duplicates must be caught here: once parsed, the
// document holds only the last value.
class DuplicateKeyGuard {
 public:
  bool operator()(int depth, json::parse_event_t event, json& parsed) {
    if (depth > kMaxJsonDepth) throw TooDeep{path()};
    switch (event) {
      case json::parse_event_t::object_start: frames_.push_back(Frame{false, 0, {}, {}}); break;
      case json::parse_event_t::array_start: frames_.push_back(Frame{true, 0, {}, {}}); break;
      case json::parse_event_t::key: {
        Frame& frame = frames_.back();
        frame.key = parsed.get<std::string>();
        if (!frame.keys.insert(frame.key).second) throw DuplicateKey{path()};
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        nextElement();
        break;
      case json::parse_event_t::value: nextElement(); break;
    }
    return true;
  }

 private:
  struct Frame {
    bool array;
    size_t index = 0;  // arrays: the element being parsed
    std::string key;   // objects: the key being parsed
    std::unordered_set<std::string> keys;
  };

  void nextElement() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }

  // The JSON path of the current key, spelt as JsonNode spells paths.
  std::string path() const {
    std::string out;
    for (const Frame& f : frames_) {
      std::string step = f.array ? "[" + std::to_string(f.index) + "]" : pathKey(f.key);
      out += out.empty() || step[0] == '[' ? step : "." + step;
    }
    return out;
  }

  std::vector<Frame> frames_;
};

// 1-based line and column of the 0-based byte offset in text.
std::string lineColumn(const std::string& text, size_t offset) {
  offset = std::min(offset, text.size());
  size_t line = 1, lineStart = 0;
  for (size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      lineStart = i + 1;
    }
  }
  return std::to_string(line) + ":" + std::to_string(offset - lineStart + 1);
}

}  // namespace

// nlohmann's what() is "[json.exception.parse_error.101] parse error at line 3,
// column 4: syntax error while ..."; keep only the part after the position.
std::string parseProblem(const std::string& what) {
  size_t at = what.find("column ");
  size_t colon = what.find(": ", at == std::string::npos ? 0 : at);
  if (colon != std::string::npos) return what.substr(colon + 2);
  size_t bracket = what.find("] ");
  return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

json parseJsonDocument(const std::string& text, const std::string& file) {
  try {
    return json::parse(text, DuplicateKeyGuard());
  } catch (const DuplicateKey& d) {
    throwInputError(file + ": " + d.path + ": duplicate key (each key may appear once per object)");
  } catch (const TooDeep& d) {
    const std::string where = d.path.size() > 40 ? d.path.substr(0, 40) + "..." : d.path;
    throwInputError(fmt::format("{}: {}: nested deeper than {} levels", file, where.empty() ? "(root)" : where,
                                kMaxJsonDepth));
  } catch (const json::parse_error& e) {
    // e.byte is 1-based: the offending character sits at offset byte - 1.
    size_t offset = e.byte > 0 ? e.byte - 1 : 0;
    throwInputError(file + ":" + lineColumn(text, offset) +
                    ": JSON syntax error: " + printable(parseProblem(e.what())));
  } catch (const json::out_of_range& e) {
    // Raised for numbers beyond double range ("1e400"); nlohmann gives no
    // position, so locate the literal it quotes.
    std::string problem = parseProblem(e.what());
    size_t q1 = problem.find('\''), q2 = problem.rfind('\'');
    if (q1 != std::string::npos && q2 > q1) {
      size_t offset = text.find(problem.substr(q1 + 1, q2 - q1 - 1));
      if (offset != std::string::npos) {
        throwInputError(file + ":" + lineColumn(text, offset) + ": JSON number error: " +
                        problem + " (numbers must be finite)");
      }
    }
    throwInputError(file + ": JSON number error: " + problem);
  } catch (const json::exception& e) {
    throwInputError(file + ": JSON error: " + parseProblem(e.what()));
  }
}

bool parseJsonValue(const std::string& text, json& out, std::string& duplicate) {
  duplicate.clear();
  try {
    json value = json::parse(text, DuplicateKeyGuard(), /*allow_exceptions=*/false);
    if (value.is_discarded()) return false;
    out = std::move(value);
    return true;
  } catch (const DuplicateKey& d) {
    duplicate = d.path;
    return true;
  } catch (const TooDeep&) {
    return false;
  } catch (const json::exception&) {
    return false;  // e.g. a number beyond double range: not JSON we can use
  }
}

}  // namespace penumbra
