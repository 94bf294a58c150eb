// Strict JSON text parsing for scene files and --set values: syntax errors with
// line and column, numbers beyond double range, and duplicate keys, which
// nlohmann would otherwise accept silently (the last value winning).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace penumbra {

// Parses a scene document. Throws InputError "FILE:LINE:COLUMN: JSON syntax
// error: ...", "FILE:LINE:COLUMN: JSON number error: ..." or, for a key that
// appears twice in one object, "FILE: PATH: duplicate key ...".
nlohmann::json parseJsonDocument(const std::string& text, const std::string& file);

// Parses a --set value. False when `text` is not JSON (it is then a plain
// string); `duplicate` gets the path inside the value of a repeated key, or "".
bool parseJsonValue(const std::string& text, nlohmann::json& out, std::string& duplicate);

// The part of an nlohmann exception's what() after its "[json.exception...]"
// tag and position: the problem itself.
std::string parseProblem(const std::string& what);

}  // namespace penumbra
